// The declarations of contact::ContactSettings (contact_settings_specs.hpp), one entry per
// setting, in the order of the docs. Each entry: the member, its unit, its range and its
// meaning; the default is the member's initializer (joint_set.hpp), read from
// ContactSettings{}.
#include "rheodda/contact/contact_settings_specs.hpp"

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "rheodda/laws/spec_lookup.hpp"

namespace rheodda::contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::max();
constexpr laws::ParameterRange kPositive = laws::kPositiveRange;  ///< > 0

std::vector<ContactSettingSpec> declare_contact_settings() {
  using CS = ContactSettings;
  using laws::declare_setting;
  std::vector<ContactSettingSpec> out;
  auto add = [&out](ContactSettingSpec s) -> ContactSettingSpec& { return out.emplace_back(std::move(s)); };
  add(declare_setting("penalty", "stress", kPositive, &CS::penalty,
                      "normal contact penalty p_n (the seed's eq. 17, p_n = k1·E, k1 = 10–100)"))
      .default_meaning = "the host's (0: not set)";
  add(declare_setting("shear_normal_ratio", "–", kPositive, &CS::shear_normal_ratio,
                      "p_n / p_s of penalty shear springs"));
  add(declare_setting("search_factor", "–", kPositive, &CS::search_factor,
                      "contact search distance / (max_displacement_ratio · half model size)"));
  add(declare_setting("angle_tolerance", "deg", {0.0, true, 45.0, false}, &CS::angle_tolerance,
                      "angle rule tolerance"));
  add(declare_setting("penetration_ratio", "–", {0.0, true, 1.0, false}, &CS::penetration_ratio,
                      "allowed penetration / half model size; above it the penalty is raised"));
  add(declare_setting("friction_tolerance", "–", kPositive, &CS::friction_tolerance,
                      "a sliding contact whose normal force moved by more than this fraction between two "
                      "iterates asks for another iterate (its friction is taken from the last iterate's N)"));
  add(declare_setting("force_resolution", "–", {0.0, false, 1.0, true}, &CS::force_resolution,
                      "force resolution of the open–close decisions as a fraction of the largest contact normal "
                      "force of the last iterate (at most the stiffest spring's at `penetration_ratio`): a contact "
                      "closes, opens, slides or sticks only when the force at stake exceeds it"));
  add(declare_setting("max_flips", "–", {1.0, false, 1000.0, false}, &CS::max_flips,
                      "state changes of one contact in one step after which it may only change to locked "
                      "(anti-chattering)"));
  add(declare_setting("max_refinements", "–", {0.0, false, 1000.0, false}, &CS::max_refinements,
                      "friction refinements (see `friction_tolerance`) one contact may ask for in one step"));
  add(declare_setting("stick_keeps_force", "–", {}, &CS::stick_keeps_force,
                      "`true`: a sliding contact that sticks keeps the friction force it slid against in its "
                      "shear spring (an elastic–plastic joint); `false`: the spring restarts unstretched (Shi's "
                      "rule). Fewer iterates and cuts on walls and slopes at their friction limit, but a "
                      "creeping slope at its limit then takes step-dependent paths "
                      "(docs/notes/contact-solves.md, \"Stick and slip\")"))
      .host_default =
      "`true` in a dynamic analysis (Shi's rule ratchets a slope that stands down its friction "
      "limit at small steps) and in a static one with collapse stages (`settle.collapse_dt`: "
      "the static steps keep the stages' rule, docs/reference/engine.md \"Collapse stages\"), `false` in "
      "other static ones";
  add(declare_setting("penalty_raise", "–", {1.0, false, kInf, false}, &CS::penalty_raise,
                      "factor on the penalty when a step's largest penetration exceeds `penetration_ratio` × "
                      "the half model size"));
  add(declare_setting("penalty_max_factor", "–", {1.0, false, kInf, false}, &CS::penalty_max_factor,
                      "largest penalty / initial penalty"));
  return out;
}

/// The choices of ContactSettings: the scheme, `automatic` (no scheme: per joint set and
/// step) or one of laws::Scheme's by its name.
std::vector<ContactChoiceSpec> declare_contact_choices() {
  using Row = laws::ChoiceWord<std::optional<laws::Scheme>>;
  std::vector<Row> schemes{{std::nullopt, "automatic"}};
  for (laws::Scheme m : {laws::Scheme::lagged, laws::Scheme::implicit, laws::Scheme::exponential_linear})
    schemes.push_back(Row{m, laws::scheme_name(m)});
  std::vector<ContactChoiceSpec> out;
  out.push_back(laws::declare_choice("scheme", schemes, &ContactSettings::scheme,
      "creep integration scheme of the joint laws: `lagged`, `implicit`, `exponential-linear` "
         "(docs/reference/laws.md), or `automatic`: per joint set and step, exponential-linear where the "
         "step is below its no-ringing limit, implicit otherwise"));
  return out;
}

}  // namespace

const std::vector<ContactChoiceSpec>& contact_choice_specs() {
  static const std::vector<ContactChoiceSpec> specs = declare_contact_choices();
  return specs;
}

const ContactChoiceSpec& contact_choice_spec(std::string_view name) {
  return laws::spec_named(contact_choice_specs(), name, "contact::ContactSettings", "choice");
}

const std::vector<ContactSettingSpec>& contact_setting_specs() {
  static const std::vector<ContactSettingSpec> specs = declare_contact_settings();
  return specs;
}

const ContactSettingSpec& contact_setting_spec(std::string_view name) {
  return laws::spec_named(contact_setting_specs(), name, "contact::ContactSettings", "setting");
}

void check_contact_setting_ranges(const ContactSettings& s) {
  for (const ContactSettingSpec& spec : contact_setting_specs())
    if (const double v = spec.value(s); !spec.admits(v))
      throw std::invalid_argument("contact setting " + spec.name() + ": " + laws::setting_refusal(spec, v));
}

}  // namespace rheodda::contact
