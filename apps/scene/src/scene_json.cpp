// The scene as summary.json's "inputs" (docs/reference/outputs.md, "summary.json"): every
// key the run used, defaults filled in.
#include <nlohmann/json.hpp>

#include "rheodda/scene/describe.hpp"
#include "bolts_text.hpp"
#include "key_json.hpp"
#include "rheodda/scene/keys.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {
namespace {

using json = nlohmann::ordered_json;
using detail::entry_json;
using detail::key_json;
using detail::law_json;

/// The declared keys of one map (keys.hpp) as a JSON object, in their order; a
/// sub-map (`settle`) the scene does not give, whose keys all do not apply, is null.
json section_of(const Analysis& a, const std::string& map) {
  json o = json::object();
  bool applies = false;
  for (const KeySpec& k : analysis_keys()) {
    if (k.map != map) continue;
    o[k.name] = k.type == KeyType::map ? section_of(a, map + "." + k.name) : key_json(k.get(a));
    applies = applies || !o[k.name].is_null();
  }
  return applies ? o : json(nullptr);
}

/// `stages:` as read, block and joint set names resolved (docs/reference/stages.md).
json stages_json(const SceneDescription& s) {
  json list = json::array();
  for (const StageDescription& st : s.stages) {
    json o = {{"name", st.name}};
    if (st.start == StageStart::at)
      o["at"] = st.at;
    else
      o["after"] = "settled";
    auto points = [&](const std::vector<StagePoint>& ps, bool load) {
      json a = json::array();
      for (const StagePoint& p : ps) {
        json e = {{"name", p.name}, {"point", p.point}, {"block", s.blocks[static_cast<std::size_t>(p.block)].name}};
        if (load) e["history"] = p.history;
        a.push_back(e);
      }
      return a;
    };
    if (!st.remove_fixed_points.empty()) o["remove_fixed_points"] = st.remove_fixed_points;
    if (!st.remove_loads.empty()) o["remove_loads"] = st.remove_loads;
    if (!st.remove_blocks.empty()) {
      json names = json::array();
      for (int b : st.remove_blocks) names.push_back(s.blocks[static_cast<std::size_t>(b)].name);
      o["remove_blocks"] = names;
    }
    if (!st.add_fixed_points.empty()) o["add_fixed_points"] = points(st.add_fixed_points, false);
    if (!st.add_loads.empty()) o["add_loads"] = points(st.add_loads, true);
    for (const BoltDescription& b : st.add_bolts) o["add_bolts"].push_back(bolt_json(s, b));  // bolts_text.cpp
    for (const StageJointSet& c : st.joint_sets) {
      json js = json::object();
      if (c.friction_angle) js["friction_angle"] = *c.friction_angle;
      if (c.cohesion) js["cohesion"] = *c.cohesion;
      if (c.tensile_strength) js["tensile_strength"] = *c.tensile_strength;
      if (c.residual_friction_angle) js["residual_friction_angle"] = *c.residual_friction_angle;
      if (c.residual_cohesion) js["residual_cohesion"] = *c.residual_cohesion;
      if (c.law_name) {
        json law = {{"name", *c.law_name}};
        for (const auto& [k, v] : c.law_parameters) law[k] = v;
        js["law"] = law;
      }
      o["joint_sets"][s.joint_sets[static_cast<std::size_t>(c.joint_set)].name] = js;
    }
    if (st.dynamic_ratio)
      o["analysis"] = {{"type", *st.dynamic_ratio > 0.0 ? "dynamic" : "static"}, {"dynamic_ratio", *st.dynamic_ratio}};
    if (st.settle) o["settle"] = true;
    if (st.water) o["water"] = json::parse(water_json_text(*st.water));
    list.push_back(o);
  }
  return list;
}

json scene_json(const SceneDescription& s) {
  json j;
  j["file"] = s.file;
  j["title"] = s.title;
  j["units"] = {{"length", s.units.length}, {"force", s.units.force}, {"time", s.units.time},
                {"stress", s.units.stress()}};
  j["analysis"] = section_of(s.analysis, "analysis");  // every declared key (keys.hpp), in order
  for (const auto& m : s.materials) j["materials"][m.name] = entry_json(material_keys(), "materials", m);
  for (const auto& js : s.joint_sets)
    j["joint_sets"][js.name] =
        entry_json(joint_set_keys(), "joint_sets", js, [&](const KeyInfo&) { return law_json(js.law); });
  j["blocks"] = json::array();
  for (const auto& b : s.blocks) {
    json e = {{"name", b.name}, {"material", s.materials[b.material].name}, {"polygon", b.polygon}};
    json sets = json::array();
    for (int k : b.edge_joint_set) sets.push_back(s.joint_sets[k].name);
    e["edge_joint_sets"] = sets;
    e["fixed"] = b.fixed;
    e["initial_stress"] = b.initial_stress;
    e["initial_velocity"] = b.initial_velocity;
    j["blocks"].push_back(e);
  }
  j["fixed_points"] = json::array();
  for (const auto& f : s.fixed_points) {
    j["fixed_points"].push_back({{"point", f.point}, {"block", s.blocks[f.block].name}});
    if (!f.name.empty()) j["fixed_points"].back()["name"] = f.name;  // only when given (docs/reference/stages.md)
  }
  j["loads"] = json::array();
  for (const auto& l : s.loads) {
    j["loads"].push_back({{"point", l.at.point}, {"block", s.blocks[l.at.block].name}, {"history", l.history}});
    if (!l.at.name.empty()) j["loads"].back()["name"] = l.at.name;
  }
  j["measurement_points"] = json::array();
  for (const auto& m : s.measurement_points)
    j["measurement_points"].push_back({{"name", m.name}, {"point", m.at.point}, {"block", s.blocks[m.at.block].name}});
  if (s.water) j["water"] = json::parse(water_json_text(*s.water));  // only with water (water.hpp)
  if (!s.stages.empty()) j["stages"] = stages_json(s);
  add_bolts_json(s, j);  // bolts_text.cpp
  return j;
}

}  // namespace

std::string scene_json_text(const SceneDescription& s) { return scene_json(s).dump(); }

}  // namespace rheodda::scene
