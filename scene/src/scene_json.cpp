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
using detail::left_out;
using detail::Unset;

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

/// A block's name, as summary.json names the block of a point, a load or a stage's change.
json block_name(const SceneDescription& s, int block) { return s.blocks[static_cast<std::size_t>(block)].name; }

/// A point's `point` and `block` as the reader resolved them (keys_points.cpp, keys_stages.cpp).
json point_key(const SceneDescription& s, const KeyInfo& k, const Point& point, int block) {
  if (k.name == "point") return point;
  if (k.name == "block") return block_name(s, block);
  return left_out();
}

/// A load's keys read by the reader: point, block and the history (a `force` is its one sample).
json load_key(const SceneDescription& s, const KeyInfo& k, const Point& point, int block,
              const std::vector<std::array<double, 3>>& history) {
  if (k.name == "history") return history;
  return point_key(s, k, point, block);
}

/// `water:` (keys_water.cpp): the unit weight and the one form of the surface given.
json water_json(const WaterDescription& w) {
  return entry_json(water_keys(), "water", w, [&](const KeyInfo& k) -> json {
    const auto& h = w.history;
    if (k.name == "surface" && w.form == WaterDescription::Form::surface) return h[0].surface;
    if (k.name == "level_history" && w.form == WaterDescription::Form::level_history) {
      json samples = json::array();
      for (const auto& x : h) samples.push_back({x.time, x.level});
      return samples;
    }
    if (k.name == "surface_history" && w.form == WaterDescription::Form::surface_history) {
      json samples = json::array();
      for (const auto& x : h)
        samples.push_back(entry_json(water_sample_keys(), "water.surface_history", x, [&](const KeyInfo& sk) -> json {
          return sk.name == "surface" ? json(x.surface) : left_out();
        }));
      return samples;
    }
    return left_out();
  }, Unset::omit);
}

/// `rock_mass:` (keys_blocks.cpp) as the reader read it, names resolved: every key, the
/// defaults filled in (null: a trace_length not given is persistent, an origin not given
/// a random offset). The blocks it was cut into are in `blocks`.
json rock_mass_json(const SceneDescription& s, const RockMassDescription& r) {
  auto joint_set = [&](int tag) { return json(s.joint_sets[static_cast<std::size_t>(tag)].name); };
  return entry_json(rock_mass_keys(), "rock_mass", r, [&](const KeyInfo& k) -> json {
    if (k.name == "material") return s.materials[static_cast<std::size_t>(r.material)].name;
    if (k.name == "region") return r.region.outer;
    if (k.name == "holes") return r.region.holes;
    if (k.name == "boundary_joint_set") return joint_set(r.boundary_joint_set);
    json list = json::array();
    if (k.name == "joint_sets") {
      for (const auto& g : r.joint_sets)
        list.push_back(entry_json(rock_mass_joint_set_keys(), "rock_mass.joint_sets", g, [&](const KeyInfo& gk) {
          return gk.name == "joint_set" ? joint_set(g.tag) : left_out();
        }));
      return list;
    }
    if (k.name == "traces") {
      for (const auto& t : r.traces)
        list.push_back(entry_json(rock_mass_trace_keys(), "rock_mass.traces", t, [&](const KeyInfo& tk) {
          return tk.name == "joint_set" ? joint_set(t.tag) : left_out();
        }));
      return list;
    }
    return left_out();
  });
}

/// A stage's `joint_sets:` entry (keys_stages.cpp): the values it changes, its law.
json stage_joint_set_json(const StageJointSet& c) {
  return entry_json(stage_joint_set_keys(), "stages.joint_sets", c, [&](const KeyInfo& k) -> json {
    if (k.name != "law" || !c.law_name) return left_out();
    LawChoice law;  // a stage's law: its parameters only (read_law refuses a fit's marks there)
    law.name = *c.law_name;
    law.parameters = c.law_parameters;
    return law_json(law);
  }, Unset::omit);
}

/// One stage (keys_stages.cpp): the changes it gives, block and joint set names resolved
/// (docs/reference/stages.md).
json stage_json(const SceneDescription& s, const StageDescription& st) {
  auto points = [&](const std::vector<EntryKey<StagePoint>>& keys, const std::string& map,
                    const std::vector<StagePoint>& ps) {
    json a = json::array();
    for (const StagePoint& p : ps)
      a.push_back(entry_json(keys, map, p, [&](const KeyInfo& k) { return load_key(s, k, p.point, p.block, p.history); },
                             Unset::omit));
    return a;
  };
  return entry_json(stage_keys(), "stages", st, [&](const KeyInfo& k) -> json {
    if (k.name == "remove_fixed_points" && !st.remove_fixed_points.empty()) return st.remove_fixed_points;
    if (k.name == "remove_loads" && !st.remove_loads.empty()) return st.remove_loads;
    if (k.name == "remove_blocks" && !st.remove_blocks.empty()) {
      json names = json::array();
      for (int b : st.remove_blocks) names.push_back(block_name(s, b));
      return names;
    }
    if (k.name == "add_fixed_points" && !st.add_fixed_points.empty())
      return points(stage_fixed_point_keys(), "stages.add_fixed_points", st.add_fixed_points);
    if (k.name == "add_loads" && !st.add_loads.empty())
      return points(stage_load_keys(), "stages.add_loads", st.add_loads);
    if (k.name == "add_bolts" && !st.add_bolts.empty()) {
      json bolts = json::array();
      for (const BoltDescription& b : st.add_bolts) bolts.push_back(bolt_json(s, b));  // bolts_text.cpp
      return bolts;
    }
    if (k.name == "joint_sets" && !st.joint_sets.empty()) {
      json sets = json::object();
      for (const StageJointSet& c : st.joint_sets)
        sets[s.joint_sets[static_cast<std::size_t>(c.joint_set)].name] = stage_joint_set_json(c);
      return sets;
    }
    if (k.name == "analysis" && st.dynamic_ratio)
      return entry_json(stage_analysis_keys(), "stages.analysis", st, {}, Unset::omit);
    if (k.name == "water" && st.water) return water_json(*st.water);
    return left_out();
  }, Unset::omit);
}

/// One section of the file (keys_top.cpp) as summary.json echoes it; left out: a
/// section the scene does not give (rock_mass, water, bolts, stages).
json section_json(const SceneDescription& s, const KeyInfo& section) {
  const std::string& k = section.name;
  if (k == "units") {
    json u = entry_json(units_keys(), "units", s.units);
    u["stress"] = s.units.stress();
    return u;
  }
  if (k == "analysis") return section_of(s.analysis, "analysis");  // every declared key (keys.hpp), in order
  if (k == "materials") {
    json o;
    for (const auto& m : s.materials) o[m.name] = entry_json(material_keys(), "materials", m);
    return o;
  }
  if (k == "joint_sets") {
    json o;
    for (const auto& js : s.joint_sets)
      o[js.name] = entry_json(joint_set_keys(), "joint_sets", js, [&](const KeyInfo& jk) {
        return jk.name == "law" ? law_json(js.law) : left_out();
      });
    return o;
  }
  json list = json::array();
  if (k == "blocks") {
    // Each block as built: a rectangle or grid is its polygon, a `joint_set` its edges' joint sets.
    for (const auto& b : s.blocks)
      list.push_back(entry_json(block_keys(), "blocks", b, [&](const KeyInfo& bk) -> json {
        if (bk.name == "material") return s.materials[static_cast<std::size_t>(b.material)].name;
        if (bk.name == "polygon") return b.polygon;
        if (bk.name != "edge_joint_sets") return left_out();
        json sets = json::array();
        for (int e : b.edge_joint_set) sets.push_back(s.joint_sets[static_cast<std::size_t>(e)].name);
        return sets;
      }));
    return list;
  }
  // The points (keys_points.cpp); a name only when given (docs/reference/stages.md).
  if (k == "fixed_points") {
    for (const auto& f : s.fixed_points)
      list.push_back(entry_json(fixed_point_keys(), "fixed_points", f,
                                [&](const KeyInfo& pk) { return point_key(s, pk, f.point, f.block); }, Unset::omit));
    return list;
  }
  if (k == "loads") {
    for (const auto& l : s.loads)
      list.push_back(entry_json(load_keys(), "loads", l,
                                [&](const KeyInfo& pk) { return load_key(s, pk, l.at.point, l.at.block, l.history); },
                                Unset::omit));
    return list;
  }
  if (k == "measurement_points") {
    for (const auto& m : s.measurement_points)
      list.push_back(entry_json(measurement_point_keys(), "measurement_points", m,
                                [&](const KeyInfo& pk) { return point_key(s, pk, m.at.point, m.at.block); }));
    return list;
  }
  if (k == "rock_mass" && s.rock_mass) return rock_mass_json(s, *s.rock_mass);
  if (k == "water" && s.water) return water_json(*s.water);  // only with water (water.hpp)
  if (k == "bolts" && !s.bolts.empty()) {
    for (const auto& b : s.bolts) list.push_back(bolt_json(s, b));  // bolts_text.cpp
    return list;
  }
  if (k == "stages" && !s.stages.empty()) {
    for (const StageDescription& st : s.stages) list.push_back(stage_json(s, st));
    return list;
  }
  return left_out();
}

/// The scene: its file, then every section (keys_top.cpp) in the order of the docs.
json scene_json(const SceneDescription& s) {
  json j;
  j["file"] = s.file;
  j.update(entry_json(top_keys(), "top", s, [&](const KeyInfo& k) { return section_json(s, k); }, Unset::omit));
  return j;
}

}  // namespace

std::string scene_json_text(const SceneDescription& s) { return scene_json(s).dump(); }

}  // namespace rheodda::scene
