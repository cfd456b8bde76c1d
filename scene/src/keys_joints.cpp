// The declared keys of `materials:`, `joint_sets:` and a `law:` (keys.hpp), one entry per
// key, in the order of docs/reference/scene-format.md. What ties keys together (a
// residual strength at most the peak, damping only with dynamic steps, a law's E1 and
// shear_stiffness) and a law's parameters (the law registry's) stay in read_joint_sets.cpp.
#include "key_builders.hpp"

namespace rheodda::scene {

using detail::kNonNegative;
using detail::kPositive;

std::vector<EntryKey<Material>>& material_keys() {
  static std::vector<EntryKey<Material>> keys = [] {
    using E = Material;
    std::vector<EntryKey<E>> k;
    k.push_back(detail::field_key(
        KeyInfo{.map = "materials", .name = "density", .type = KeyType::number, .unit = "mass/length³",
                .range = kPositive, .required = "[mass/length^3]", .default_text = "required", .meaning = "> 0"},
        &E::density));
    k.push_back(detail::field_key(
        KeyInfo{.map = "materials", .name = "young_modulus", .type = KeyType::number, .unit = "stress",
                .range = kPositive, .required = "E [stress]", .default_text = "required", .meaning = "E, > 0"},
        &E::young_modulus));
    k.push_back(detail::field_key(
        KeyInfo{.map = "materials", .name = "poisson_ratio", .type = KeyType::number, .unit = "–",
                .range = {0.0, false, 0.5, true}, .required = "nu [-]", .default_text = "required",
                .meaning = "ν, in [0, 0.5)"},
        &E::poisson_ratio));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "materials", .name = "plane", .type = KeyType::choice, .unit = "–",
                .choices = {"strain", "stress"}, .default_text = "`strain`",
                .meaning = "`strain` (long body) or `stress` (thin plate)"},
        [](const E& m) -> KeyValue { return std::string(plane_name(m.plane)); },
        [](E& m, const KeyValue& v) {
          m.plane = std::get<std::string>(v) == "strain" ? PlaneKind::strain : PlaneKind::stress;
        }));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "materials", .name = "damping_ratio", .type = KeyType::number, .unit = "–",
                .range = {0.0, false, 1.0, false}, .default_text = "`0` (none)",
                .meaning = "ζ in [0, 1]: Kelvin–Voigt damping of each block's strain, ζ on its lowest strain mode "
                           "(docs/reference/engine.md, \"Block damping\"); dynamic analysis only",
                .echoed = false},
        // 0 is none: `check` names the damping only where there is some.
        [](const E& m) -> KeyValue {
          if (m.damping_ratio > 0.0) return m.damping_ratio;
          return std::monostate{};
        },
        [](E& m, const KeyValue& v) { m.damping_ratio = std::get<double>(v); }));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<JointSetDescription>>& joint_set_keys() {
  static std::vector<EntryKey<JointSetDescription>> keys = [] {
    using E = JointSetDescription;
    std::vector<EntryKey<E>> k;
    k.push_back(detail::field_key(
        KeyInfo{.map = "joint_sets", .name = "friction_angle", .type = KeyType::number, .unit = "deg",
                .range = {0.0, false, 90.0, true}, .required = "phi [deg], 0 <= phi < 90",
                .default_text = "required", .meaning = "Mohr–Coulomb φ, in [0, 90)"},
        &E::friction_angle));
    k.push_back(detail::field_key(
        KeyInfo{.map = "joint_sets", .name = "cohesion", .type = KeyType::number, .unit = "stress",
                .range = kNonNegative, .default_text = "0",
                .meaning = "c, ≥ 0; acts until the contact first slides or opens"},
        &E::cohesion));
    k.push_back(detail::field_key(
        KeyInfo{.map = "joint_sets", .name = "tensile_strength", .type = KeyType::number, .unit = "stress",
                .range = kNonNegative, .default_text = "0",
                .meaning = "≥ 0; acts until the contact first slides or opens"},
        &E::tensile_strength));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "joint_sets", .name = "residual_friction_angle", .type = KeyType::number, .unit = "deg",
                .range = kNonNegative, .default_text = "`friction_angle`",
                .meaning = "φ_r in [0, `friction_angle`]: the friction of a contact once it slid or opened, or its "
                           "damage law failed (residual strength, as UDEC and 3DEC; docs/reference/contacts.md, "
                           "\"Friction, cohesion, tension\")"},
        // Unset: the peak's (summary.json echoes the value that acts).
        [](const E& j) -> KeyValue { return j.residual_friction_angle.value_or(j.friction_angle); },
        [](E& j, const KeyValue& v) { j.residual_friction_angle = std::get<double>(v); }));
    k.push_back(detail::field_key(
        KeyInfo{.map = "joint_sets", .name = "residual_cohesion", .type = KeyType::number, .unit = "stress",
                .range = kNonNegative, .default_text = "0",
                .meaning = "c_r in [0, `cohesion`]: the cohesion of such a contact (its tensile strength is 0)"},
        &E::residual_cohesion));
    k.push_back(detail::optional_key(
        KeyInfo{.map = "joint_sets", .name = "normal_stiffness", .type = KeyType::number, .unit = "stress/length",
                .range = kPositive, .default_text = "the penalty",
                .meaning = "joint normal stiffness per unit joint area, > 0"},
        &E::normal_stiffness));
    k.push_back(detail::optional_key(
        KeyInfo{.map = "joint_sets", .name = "shear_stiffness", .type = KeyType::number, .unit = "stress/length",
                .range = kPositive, .default_text = "penalty / `shear_normal_ratio`",
                .meaning = "joint shear stiffness per unit joint area, > 0"},
        &E::shear_stiffness));
    k.push_back(detail::optional_key(
        KeyInfo{.map = "joint_sets", .name = "restitution", .type = KeyType::number, .unit = "–",
                .range = {0.0, false, 1.0, false}, .default_text = "none (Shi's undamped springs)",
                .meaning = "coefficient of restitution e in [0, 1] of an impact on this joint set: dashpots beside "
                           "the contact springs (docs/reference/contacts.md, \"Contact damping\"); dynamic "
                           "analysis only",
                .echoed = false},
        &E::restitution));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "joint_sets", .name = "law", .type = KeyType::map, .unit = "–", .default_text = "none",
                .meaning = "creep law of the joint's shear spring (below)", .submap = "law"}));
    k.push_back(detail::field_key(
        KeyInfo{.map = "joint_sets", .name = "record", .type = KeyType::flag, .unit = "–", .default_text = "`false`",
                .meaning = "`true`: history.csv gets this set's mean shear displacement and force"},
        &E::record));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<LawChoice>>& law_keys() {
  static std::vector<EntryKey<LawChoice>> keys = [] {
    std::vector<EntryKey<LawChoice>> k;
    // Read by read_law (read_joint_sets.cpp): the name picks the parameters the map also takes.
    k.push_back(detail::reader_key<LawChoice>(
        KeyInfo{.map = "law", .name = "name", .type = KeyType::name, .unit = "–",
                .default_text = "required", .meaning = "a law of `rheodda law list`"},
        [](const LawChoice& l) -> KeyValue { return l.name; }));
    // What a fit says of the law (rheodda fit --yaml writes them): read by read_law too
    // (a list of the law's parameter names), and the range the law was tested over;
    // the warnings they raise: law_choice.cpp.
    k.push_back(detail::reader_key<LawChoice>(
        KeyInfo{.map = "law", .name = "unidentified", .type = KeyType::list, .unit = "–", .default_text = "none",
                .meaning = "`[NAME, ...]`: the law's parameters that the data it was fitted to do not determine "
                           "(`rheodda fit --yaml` writes it): their values are one choice among many the data allow; "
                           "`check` and `run` warn, saying what the choice decides; a joint set's law only"},
        [](const LawChoice& l) -> KeyValue {
          if (l.unidentified.empty()) return std::monostate{};
          std::string names;
          for (const auto& n : l.unidentified) names += (names.empty() ? "" : ", ") + n;
          return names;
        }));
    k.push_back(detail::optional_key(
        KeyInfo{.map = "law", .name = "tested_stress", .type = KeyType::numbers, .unit = "stress",
                .default_text = "not stated",
                .meaning = "`[lowest, highest]`, 0 < lowest ≤ highest: the shear stresses of the tests the law was "
                           "fitted to (`rheodda fit --yaml` writes it); `run` warns where the contacts' shear stresses "
                           "at the end of settling lie outside, with the factor; a joint set's law only",
                .count = 2},
        &LawChoice::tested_stress));
    k.push_back(detail::optional_key(
        KeyInfo{.map = "law", .name = "tested_duration", .type = KeyType::number, .unit = "time", .range = kPositive,
                .default_text = "not stated",
                .meaning = "> 0: the duration of the longest test the law was fitted to (`rheodda fit --yaml` writes "
                           "it); `check` and `run` warn when the run lasts longer, with the factor; a joint set's law "
                           "only"},
        &LawChoice::tested_duration));
    return k;
  }();
  return keys;
}

}  // namespace rheodda::scene
