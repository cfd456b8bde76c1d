// The declared keys of `materials:`, `joint_sets:` and a `law:` (keys.hpp), one entry per
// key, in the order of docs/reference/scene-format.md; a joint set's properties are the
// contact layer's declarations (contact/joint_set_specs.hpp). What ties keys together (a
// residual strength at most the peak: contact::check_joint_set; damping only with dynamic
// steps, a law's E1 and shear_stiffness) and a law's parameters (the law registry's) are
// read_joint_sets.cpp's.
#include <algorithm>
#include <iterator>

#include "key_builders.hpp"
#include "rheodda/contact/joint_set_specs.hpp"
#include "rheodda/core/property_specs.hpp"

namespace rheodda::scene {

using detail::kNonNegative;
using detail::kPositive;

std::vector<EntryKey<Material>>& material_keys() {
  static std::vector<EntryKey<Material>> keys = [] {
    using E = Material;
    // The material's properties: each the key of its declaration (core/property_specs.hpp),
    // read into and from the core::Material a scene's Material is.
    std::vector<EntryKey<E>> k = detail::declared_keys_of<E>("materials", core::material_specs());
    for (const auto& [name, required] : {std::pair{"density", "[mass/length^3]"}, std::pair{"young_modulus", "E [stress]"},
                                         std::pair{"poisson_ratio", "nu [-]"}}) {
      detail::key_named(k, name).required = required;
      detail::key_named(k, name).default_text = "required";
    }
    EntryKey<E>& damping = detail::key_named(k, "damping_ratio");
    damping.echoed = false;
    damping.get = [](const E& m) -> KeyValue {  // 0 is none: `check` names the damping only where there is some
      if (m.damping_ratio > 0.0) return m.damping_ratio;
      return std::monostate{};
    };
    // The material's choices (`plane`): declared beside the properties; the default is the
    // scene's Material's (plane strain), not the engine's.
    auto at = k.begin() + 3;  // after the three required properties, in the declarations' order
    for (const core::MaterialChoiceSpec& c : core::material_choice_specs()) {
      KeyInfo i = detail::choice_info("materials", c);
      i.default_text = "`" + c.word_of(E{}) + "`";
      at = std::next(k.insert(at, detail::custom_key<E>(
          std::move(i), [&c](const E& m) -> KeyValue { return c.word_of(m); },
          [&c](E& m, const KeyValue& v) { c.set(m, std::get<std::string>(v)); })));
    }
    return k;
  }();
  return keys;
}

KeyInfo detail::joint_property_info(const std::string& map, const std::string& name) {
  const contact::JointPropertySpec& s = contact::joint_property_spec(name);
  const laws::ParameterSpec& p = s.parameter;
  return KeyInfo{.map = map, .name = name, .type = KeyType::number, .unit = p.unit,
                 .range = {p.min, p.min_exclusive, p.max, p.max_exclusive}, .default_text = s.default_text(),
                 .meaning = p.meaning};
}

std::vector<EntryKey<JointSetDescription>>& joint_set_keys() {
  static std::vector<EntryKey<JointSetDescription>> keys = [] {
    using E = JointSetDescription;
    std::vector<EntryKey<E>> k;
    // The joint set's properties: each the key of its declaration (contact/joint_set_specs.hpp),
    // read into and from the JointProperties a JointSetDescription is.
    for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
      EntryKey<E>& key = k.emplace_back();
      static_cast<KeyInfo&>(key) = detail::joint_property_info("joint_sets", s.name());
      key.get = [&s](const E& j) -> KeyValue {
        if (const std::optional<double> v = s.value(j)) return *v;
        return std::monostate{};
      };
      key.set = [&s](E& j, const KeyValue& v) { s.set(j, std::get<double>(v)); };
    }
    auto key = [&k](const std::string& name) -> EntryKey<E>& {
      return *std::find_if(k.begin(), k.end(), [&name](const EntryKey<E>& e) { return e.name == name; });
    };
    key("friction_angle").required = "friction angle phi [deg] in " + contact::joint_property_spec("friction_angle").range_text();
    key("friction_angle").default_text = "required";
    // Unset: the peak's (summary.json echoes the value that acts).
    key("residual_friction_angle").get = [](const E& j) -> KeyValue {
      return j.residual_friction_angle.value_or(j.friction_angle);
    };
    key("restitution").echoed = false;
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
