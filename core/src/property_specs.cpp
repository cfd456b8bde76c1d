// The declarations of core::Material, core::BoltProperties and core::WaterProperties
// (property_specs.hpp), one entry per property, in the order of the docs. Each entry: the
// member, its unit, its range and its meaning; the default is the member's initializer
// (model.hpp, bolt.hpp, water.hpp), read from the struct's S{}.
#include "rheodda/core/property_specs.hpp"

#include <array>
#include <limits>

#include "rheodda/laws/spec_lookup.hpp"

namespace rheodda::core {

namespace {

using Range = laws::ParameterRange;
constexpr Range kPositive = laws::kPositiveRange;  ///< > 0
constexpr Range kAny{std::numeric_limits<double>::lowest(), false, std::numeric_limits<double>::max(), false};

std::vector<MaterialSpec> declare_material() {
  using M = Material;
  return {
      laws::declare_setting("density", "mass/length³", kPositive, &M::density, "mass density ρ"),
      laws::declare_setting("young_modulus", "stress", kPositive, &M::young_modulus, "Young's modulus E"),
      laws::declare_setting("poisson_ratio", "–", {0.0, false, 0.5, true}, &M::poisson_ratio, "Poisson's ratio ν"),
      laws::declare_setting("damping_ratio", "–", {0.0, false, 1.0, false}, &M::damping_ratio,
                            "ζ: Kelvin–Voigt damping of each block's strain, ζ on its lowest strain mode "
                            "(docs/reference/engine.md, \"Block damping\"); dynamic analysis only"),
  };
}

std::vector<MaterialChoiceSpec> declare_material_choices() {
  static constexpr std::array<laws::ChoiceWord<PlaneMode>, 2> kPlanes{
      {{PlaneMode::plane_strain, "strain"}, {PlaneMode::plane_stress, "stress"}}};
  return {laws::declare_choice("plane", kPlanes, &Material::plane,
                               "`strain` (long body) or `stress` (thin plate)")};
}

std::vector<BoltSpec> declare_bolt() {
  using B = BoltProperties;
  std::vector<BoltSpec> out{
      laws::declare_setting("axial_stiffness", "force/length", kPositive, &B::axial_stiffness,
                            "k, axial force per unit elongation"),
      laws::declare_setting("pretension", "force", kAny, &B::pretension,
                            "axial force when installed (t = 0, or the stage that installs it), tension > 0, "
                            "within `yield_force`"),
      laws::declare_setting("yield_force", "force", kPositive, &B::yield_force,
                            "N_y: the axial force stays within ±N_y; at it the bolt stretches (or shortens) "
                            "plastically"),
      laws::declare_setting("rupture_elongation", "length", kPositive, &B::rupture_elongation,
                            "once the elongation exceeds it the bolt carries nothing for the rest of the run"),
  };
  out[2].default_meaning = "never yields";     // infinity
  out[3].default_meaning = "never ruptures";   // infinity
  return out;
}

std::vector<WaterSpec> declare_water() {
  return {laws::declare_setting("unit_weight", "force/length³", kPositive, &WaterProperties::unit_weight,
                                "the water's unit weight γ_w (9810 N/m³)")};
}

}  // namespace

const std::vector<MaterialSpec>& material_specs() {
  static const std::vector<MaterialSpec> specs = declare_material();
  return specs;
}

const std::vector<MaterialChoiceSpec>& material_choice_specs() {
  static const std::vector<MaterialChoiceSpec> specs = declare_material_choices();
  return specs;
}

const std::vector<BoltSpec>& bolt_specs() {
  static const std::vector<BoltSpec> specs = declare_bolt();
  return specs;
}

const std::vector<WaterSpec>& water_specs() {
  static const std::vector<WaterSpec> specs = declare_water();
  return specs;
}

const MaterialSpec& material_spec(std::string_view name) {
  return laws::spec_named(material_specs(), name, "core::Material", "property");
}

const MaterialChoiceSpec& material_choice_spec(std::string_view name) {
  return laws::spec_named(material_choice_specs(), name, "core::Material", "choice");
}

const BoltSpec& bolt_spec(std::string_view name) {
  return laws::spec_named(bolt_specs(), name, "core::BoltProperties", "property");
}

const WaterSpec& water_spec(std::string_view name) {
  return laws::spec_named(water_specs(), name, "core::WaterProperties", "property");
}

}  // namespace rheodda::core
