// The `materials:` and `joint_sets:` sections of a scene file, with each joint set's `law:`.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <unordered_set>

#include "read_keys.hpp"
#include "rheodda/contact/joint_set_specs.hpp"
#include "scene_readers.hpp"

namespace rheodda::scene::detail {

std::vector<Material> read_materials(const Ctx& ctx, const YAML::Node& n, bool dynamic_steps) {
  if (!n.IsMap() || n.size() == 0)
    ctx.fail(n, "materials", "expected a map of named materials, e.g. `rock: {density: ..., ...}`");
  std::vector<Material> out;
  std::vector<std::string> names;  // every name is a valid key of this map
  for (auto it = n.begin(); it != n.end(); ++it) names.push_back(it->first.IsScalar() ? it->first.Scalar() : "");
  const MapReader all(ctx, n, "materials", "", names);
  for (const auto& e : all.entries()) {
    Material mat;
    mat.name = name_text(ctx, e.key_node, "materials");
    const MapReader m = declared_reader(ctx, e.value, all.child_named(e.key), material_keys(), "materials");
    mat.where = location(e.key_node);
    read_declared(ctx, m, material_keys(), mat);  // keys_joints.cpp
    // Block damping damps velocities; a static analysis carries none.
    if (YAML::Node v = m.find(key::material::damping_ratio); v.IsDefined() && !dynamic_steps)
      ctx.fail(v, m.child(key::material::damping_ratio),
               "a static analysis carries no velocity; damping_ratio needs `analysis: {type: dynamic}` "
               "or a dynamic settling stage (`settle: {type: dynamic, ...}`)");
    out.push_back(std::move(mat));
  }
  return out;
}

namespace {

/// `unidentified: [NAME, ...]`: names of parameters of the law `info`, each once.
std::vector<std::string> read_unidentified(const Ctx& ctx, const YAML::Node& v, const std::string& path,
                                           const laws::LawInfo& info) {
  std::vector<std::string> params;
  for (const auto& p : info.parameters) params.push_back(p.name);
  if (!v.IsSequence())
    ctx.fail(v, path, fmt::format("expected a list of the law's parameters, e.g. `[{}]`; law '{}' has {}",
                                  params.back(), info.name, join(params)));
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string item_path = fmt::format("{}[{}]", path, i);
    const std::string name = text(ctx, v[i], item_path);
    if (std::find(params.begin(), params.end(), name) == params.end()) {
      const std::string hint = laws::nearest_name(name, params);
      ctx.fail(v[i], item_path,
               fmt::format("law '{}' has no parameter '{}'{}; its parameters: {}", info.name, name,
                           hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint), join(params)));
    }
    if (std::find(out.begin(), out.end(), name) != out.end())
      ctx.fail(v[i], item_path, fmt::format("'{}' is listed twice", name));
    out.push_back(name);
  }
  return out;
}

}  // namespace

LawChoice read_law(const Ctx& ctx, const YAML::Node& n, const std::string& path, const char* fit_marks_refused) {
  const auto& registry = laws::LawRegistry::builtin();
  if (!n.IsMap()) ctx.fail(n, path, fmt::format("expected a map `{{name: LAW, PARAM: value, ...}}`, got {}", type_word(n)));
  YAML::Node name_node = n["name"];
  if (!name_node.IsDefined())
    ctx.fail(n, path + ".name", "missing required key 'name' (the law: see `rheodda law list`)");
  const std::string name = text(ctx, name_node, path + ".name");
  const laws::LawInfo* info = registry.find(name);
  if (!info) {
    std::vector<std::string> names;
    for (const auto& l : registry.laws()) names.push_back(l.name);
    const std::string hint = laws::nearest_name(name, names);
    ctx.fail(name_node, path + ".name",
             fmt::format("unknown law '{}'{}; known laws: {}", name,
                         hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint), join(names)));
  }
  std::vector<std::string> allowed = key_names(law_keys(), "law");  // keys_joints.cpp
  for (const auto& p : info->parameters) allowed.push_back(p.name);
  const MapReader m(ctx, n, path, "law", allowed);
  LawChoice law;
  law.name = name;
  read_declared(ctx, m, law_keys(), law);  // the declared keys but `name` (read above), keys_joints.cpp
  // What a fit says of the law (keys_joints.cpp): a joint set's law only.
  for (const KeyName k : {key::law::unidentified, key::law::tested_stress, key::law::tested_duration})
    if (YAML::Node v = m.find(k); v.IsDefined() && fit_marks_refused)
      ctx.fail(v, m.child(k), fmt::format("{} marks a fitted law of a joint set; {}", k.word(), fit_marks_refused));
  if (YAML::Node v = m.find(key::law::unidentified); v.IsDefined())
    law.unidentified = read_unidentified(ctx, v, m.child(key::law::unidentified), *info);
  if (YAML::Node v = m.find(key::law::tested_stress); v.IsDefined()) {
    const auto& range = *law.tested_stress;
    if (!(range[0] > 0.0 && range[0] <= range[1]))
      ctx.fail(v, m.child(key::law::tested_stress),
               fmt::format("[{:g}, {:g}] is not [lowest, highest] with 0 < lowest <= highest: the shear stresses "
                           "of the tests the law was fitted to",
                           range[0], range[1]));
  }
  const std::vector<std::string> declared = key_names(law_keys(), "law");
  laws::ParameterValues given;  // the rest: the law's parameters
  for (const auto& e : m.entries())
    if (std::find(declared.begin(), declared.end(), e.key) == declared.end()) {
      // Its dimension from the law's declaration ("stress*time/length"): a value may carry its unit.
      const auto spec = std::find_if(info->parameters.begin(), info->parameters.end(),
                                     [&e](const laws::ParameterSpec& p) { return p.name == e.key; });
      given[e.key] = number(ctx, e.value, m.child_named(e.key), any(spec == info->parameters.end() ? "" : spec->unit.c_str()));
    }
  try {
    law.parameters = laws::validate_parameters(name, info->parameters, given);
  } catch (const laws::LawError& err) {
    YAML::Node at = m.find_named(err.key());
    ctx.fail(at.IsDefined() ? at : n, m.child_named(err.key()), err.what());
  }
  // The law must also build (a law may check relations between its parameters).
  try {
    (void)registry.create(name, law.parameters);
  } catch (const laws::LawError& err) {
    YAML::Node at = m.find_named(err.key());
    ctx.fail(at.IsDefined() ? at : n, m.child_named(err.key()), err.what());
  }
  return law;
}

std::vector<JointSetDescription> read_joint_sets(const Ctx& ctx, const YAML::Node& n, bool dynamic_steps) {
  if (!n.IsMap() || n.size() == 0)
    ctx.fail(n, "joint_sets", "expected a map of named joint sets, e.g. `bedding: {friction_angle: 30}`");
  std::vector<std::string> names;  // every name is a valid key of this map
  for (auto it = n.begin(); it != n.end(); ++it) names.push_back(it->first.IsScalar() ? it->first.Scalar() : "");
  const MapReader all(ctx, n, "joint_sets", "", names);
  std::vector<JointSetDescription> out;
  for (const auto& e : all.entries()) {
    JointSetDescription js;
    js.name = name_text(ctx, e.key_node, "joint_sets");
    js.where = location(e.key_node);
    const MapReader m = declared_reader(ctx, e.value, all.child_named(e.key), joint_set_keys(), "joint_sets");
    read_declared(ctx, m, joint_set_keys(), js);  // keys_joints.cpp
    // The contact layer's checks of the properties (contact/joint_set_specs.hpp: the declared
    // ranges, which the keys have checked, and a residual strength at most the peak), at the
    // key they name. The law's E1 and shear_stiffness: below, in the scene's words.
    contact::JointSet properties;
    static_cast<contact::JointProperties&>(properties) = js;
    properties.name = js.name;
    try {
      contact::check_joint_set(properties, out.size());
    } catch (const contact::JointSetError& err) {
      const YAML::Node at = m.find_named(err.key());
      ctx.fail(at.IsDefined() ? at : e.value, m.child_named(err.key()), err.message());
    }
    // Contact dashpots damp motion; a static analysis has none to damp.
    if (YAML::Node v = m.find(key::joint_set::restitution); v.IsDefined() && !dynamic_steps)
      ctx.fail(v, m.child(key::joint_set::restitution),
               "a static analysis carries no velocity; restitution needs `analysis: {type: dynamic}` "
               "or a dynamic settling stage (`settle: {type: dynamic, ...}`)");
    if (YAML::Node v = m.find(key::joint_set::law); v.IsDefined()) {
      js.law = read_law(ctx, v, m.child(key::joint_set::law), nullptr);
      // A law with an instantaneous spring E1 (burgers, maxwell, nishihara) is the
      // joint's elastic shear spring, k_s = E1 l: one value, given once.
      if (js.shear_stiffness && js.law->parameters.count("E1"))
        ctx.fail(m.find(key::joint_set::shear_stiffness), m.child(key::joint_set::shear_stiffness),
                 fmt::format("law '{}' sets the joint's elastic shear stiffness with its E1; "
                             "remove shear_stiffness (or use a law without E1)", js.law->name));
    }
    out.push_back(std::move(js));
  }
  return out;
}

}  // namespace rheodda::scene::detail
