// The declarations of contact::JointProperties (joint_set_specs.hpp), one entry per
// property, in the order of the docs. Each entry: the member, its unit, its range and its
// meaning; the default is the member's initializer (joint_set.hpp), read from
// JointProperties{}. check_joint_set: the declared ranges, then the checks that tie
// properties together.
#include "rheodda/contact/joint_set_specs.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "rheodda/laws/spec_lookup.hpp"

namespace rheodda::contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::max();
constexpr laws::ParameterRange kPositive = laws::kPositiveRange;        ///< > 0
constexpr laws::ParameterRange kNonNegative = laws::kNonNegativeRange;  ///< >= 0
constexpr laws::ParameterRange kAngle{0.0, false, 90.0, true};          ///< [0, 90) [deg]

/// The declaration of the member `field`, named `name` (the scene's word).
template <class T>
JointPropertySpec declare(const char* name, const char* unit, const laws::ParameterRange& r,
                          T JointProperties::*field, const char* meaning) {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>);
  JointPropertySpec s;
  s.parameter = laws::declare_parameter(name, unit, r, meaning);
  s.parameter.default_value = JointProperties{}.*field;  // an optional: none while unset
  s.field = field;
  return s;
}

std::vector<JointPropertySpec> declare_properties() {
  std::vector<JointPropertySpec> out;
  auto add = [&out](JointPropertySpec s) -> JointPropertySpec& { return out.emplace_back(std::move(s)); };

  add(declare("friction_angle", "deg", kAngle, &JointProperties::friction_angle,
              "Mohr–Coulomb friction angle φ")).between_steps = true;
  add(declare("cohesion", "stress", kNonNegative, &JointProperties::cohesion,
              "cohesion c; acts until the contact first slides or opens")).between_steps = true;
  add(declare("tensile_strength", "stress", kNonNegative, &JointProperties::tensile_strength,
              "tensile strength; acts until the contact first slides or opens")).between_steps = true;
  JointPropertySpec& residual_friction = add(declare(
      "residual_friction_angle", "deg", kAngle, &JointProperties::residual_friction_angle,
      "φ_r in [0, `friction_angle`]: the friction of a contact once it slid or opened, or its damage law failed "
      "(residual strength, as UDEC and 3DEC; docs/reference/contacts.md, \"Friction, cohesion, tension\")"));
  residual_friction.unset_meaning = "`friction_angle`";
  residual_friction.between_steps = true;
  add(declare("residual_cohesion", "stress", kNonNegative, &JointProperties::residual_cohesion,
              "c_r in [0, `cohesion`]: the cohesion of such a contact (its tensile strength is 0)"))
      .between_steps = true;
  add(declare("normal_stiffness", "stress/length", kPositive, &JointProperties::normal_stiffness,
              "joint normal stiffness per unit joint area"))
      .unset_meaning = "the penalty";
  add(declare("shear_stiffness", "stress/length", kPositive, &JointProperties::shear_stiffness,
              "joint shear stiffness per unit joint area; not with a law that has an E1 (the law's E1 is it)"))
      .unset_meaning = "penalty / `shear_normal_ratio`";
  add(declare("restitution", "–", {0.0, false, 1.0, false}, &JointProperties::restitution,
              "coefficient of restitution e of an impact on this joint set: dashpots beside the contact springs "
              "(docs/reference/contacts.md, \"Contact damping\"); dynamic analysis only"))
      .unset_meaning = "none (Shi's undamped springs)";
  return out;
}

/// A number in its shortest form, as the scene loader prints it (60, 0.25, 1e+09).
std::string shortest(double v) { return fmt::format("{:g}", v); }

}  // namespace

std::optional<double> JointPropertySpec::value(const JointProperties& j) const {
  return std::visit([&j](auto m) -> std::optional<double> { return j.*m; }, field);
}

void JointPropertySpec::set(JointProperties& j, double v) const {
  std::visit([&j, v](auto m) { j.*m = v; }, field);
}

bool JointPropertySpec::admits(double v) const { return std::isfinite(v) && parameter.admits(v); }

std::string JointPropertySpec::range_text() const {
  const laws::ParameterSpec& p = parameter;
  return (p.min_exclusive ? "(" : "[") + shortest(p.min) + ", " + (p.max == kInf ? "inf" : shortest(p.max)) +
         (p.max_exclusive ? ")" : "]");
}

std::string JointPropertySpec::default_text() const {
  return parameter.default_value ? shortest(*parameter.default_value) : unset_meaning;
}

const std::vector<JointPropertySpec>& joint_property_specs() {
  static const std::vector<JointPropertySpec> specs = declare_properties();
  return specs;
}

const JointPropertySpec& joint_property_spec(std::string_view name) {
  return laws::spec_named(joint_property_specs(), name, "contact::JointProperties", "property");
}

void check_joint_set(const JointSet& js, std::size_t index) {
  auto refuse = [&](const std::string& key, const std::string& message) {
    throw JointSetError(index, js.name, key, message);
  };
  // Every declared property within its range, in the loader's words (scene/src/yaml_reader.cpp).
  for (const JointPropertySpec& spec : joint_property_specs())
    if (const std::optional<double> v = spec.value(js); v && !spec.admits(*v))
      refuse(spec.name(), shortest(*v) + " is out of range " + spec.range_text() +
                              (spec.parameter.unit == "–" ? "" : " [" + spec.parameter.unit + "]"));
  // A residual strength is at most the peak.
  if (js.residual_friction_angle && !(*js.residual_friction_angle <= js.friction_angle))
    refuse("residual_friction_angle", shortest(*js.residual_friction_angle) + " deg is above the peak friction_angle " +
                                          shortest(js.friction_angle) +
                                          " deg: a residual strength is at most the peak");
  if (!(js.residual_cohesion <= js.cohesion))
    refuse("residual_cohesion", shortest(js.residual_cohesion) + " is above the peak cohesion " +
                                    shortest(js.cohesion) + ": a residual strength is at most the peak");
  // One elastic shear stiffness per joint: a law's instantaneous spring E1 is it.
  if (js.law && js.law->instantaneous_stiffness() && js.shear_stiffness)
    refuse("shear_stiffness", "shear_stiffness and the E1 of law '" + std::string(js.law->name()) +
                                  "' both set the joint's elastic shear stiffness; give only E1");
}

}  // namespace rheodda::contact
