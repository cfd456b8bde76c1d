// The handles by which the scene's readers look up the keys of a map (MapReader::find,
// has, child, required; yaml_reader.hpp): `key::settle::until` is the key `until` of
// the map `analysis.settle`. Internal to the loader; not installed.
//
// Why handles and not the words: a reader's cross-key check that asked for a word the
// map does not declare (a typo, a key renamed) would find nothing and never apply. A
// handle is made only here, from the registry below, and only for a word the registry
// lists for its map: a reader cannot write another word, and a handle with a word
// missing from the registry does not compile. The registry's words are checked against
// the maps' declarations (keys*.cpp, declared_key_names) by one test
// (tests/scene/key_names_test.cpp). A handle is bound to its map: MapReader refuses a
// handle of another map (std::logic_error), as the word may mean something else there.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string_view>

namespace rheodda::scene::detail {

/// The words of one declared map (keys.hpp: "analysis.settle", "stages", ...) that the
/// readers look up by handle, separated by spaces.
struct LookedUpKeys {
  std::string_view map;
  std::string_view words;
};

/// Every key a reader looks up by handle, by map: the one list the handles are made
/// from, and that key_names_test checks against the declarations.
inline constexpr std::array key_registry{
    LookedUpKeys{"top", "units analysis materials joint_sets blocks rock_mass fixed_points loads measurement_points "
                        "water bolts stages"},
    LookedUpKeys{"analysis", "dt settle dynamic_ratio time_integration integrator static_force_ratio "
                             "static_max_cycles static_local_damping explicit_safety explicit_damping "
                             "stage_local_damping stage_cycles step_tolerance step_extrapolation dt_max dt_growth "
                             "stick_keeps_force output_interval output_times"},
    LookedUpKeys{"analysis.settle", "until max_displacement_ratio rest_tolerance force_ratio dt type collapse_dt "
                                    "gravity_ramp"},
    LookedUpKeys{"materials", "damping_ratio"},
    LookedUpKeys{"joint_sets", "restitution law shear_stiffness"},
    LookedUpKeys{"law", "unidentified tested_stress tested_duration"},
    LookedUpKeys{"blocks", "material initial_velocity polygon rectangle grid joint_set edge_joint_sets"},
    LookedUpKeys{"rock_mass", "material region holes boundary_joint_set joint_sets traces"},
    LookedUpKeys{"rock_mass.joint_sets", "joint_set spacing spacing_deviation trace_length gap"},
    LookedUpKeys{"rock_mass.traces", "joint_set to"},
    LookedUpKeys{"fixed_points", "name point block"},
    LookedUpKeys{"loads", "name point block force history"},
    LookedUpKeys{"measurement_points", "name point block"},
    LookedUpKeys{"water", "level surface level_history surface_history"},
    LookedUpKeys{"water.surface_history", "time surface"},
    LookedUpKeys{"bolts", "name from to law axial_stiffness pretension"},
    LookedUpKeys{"bolts.from", "point block"},
    LookedUpKeys{"bolts.to", "fixed point block"},
    LookedUpKeys{"stages", "name at after remove_fixed_points remove_loads remove_blocks add_fixed_points add_loads "
                           "add_bolts joint_sets analysis settle water"},
    LookedUpKeys{"stages.remove_blocks", "names region rock_mass_inside"},
    LookedUpKeys{"stages.add_fixed_points", "name block"},
    LookedUpKeys{"stages.add_loads", "name block force history"},
    LookedUpKeys{"stages.joint_sets", "law"},
    LookedUpKeys{"stages.analysis", "type dynamic_ratio"},
};

/// The path of a declared map as a template argument (KeyMap<"analysis.settle">).
template <std::size_t N>
struct MapPath {
  char text[N]{};
  consteval MapPath(const char (&s)[N]) { std::copy_n(s, N, text); }
  constexpr std::string_view view() const { return {text, N - 1}; }
};

template <MapPath Map>
class KeyMap;

/// One key of one declared map, as a reader names it: made only by the KeyMaps below.
class KeyName {
 public:
  constexpr std::string_view map() const { return map_; }
  constexpr std::string_view word() const { return word_; }

 private:
  template <MapPath Map>
  friend class KeyMap;
  constexpr KeyName(std::string_view map, std::string_view word) : map_(map), word_(word) {}
  std::string_view map_;
  std::string_view word_;
};

/// The base of the handles of the map `Map`: `handle(word)` is its key `word`, refused
/// at compile time (a throw in a consteval call) unless the registry lists the word for
/// the map. The views it gives point into the registry.
template <MapPath Map>
class KeyMap {
 protected:
  static consteval KeyName handle(std::string_view word) {
    for (const LookedUpKeys& e : key_registry) {
      if (e.map != Map.view()) continue;
      for (std::size_t at = 0; at < e.words.size();) {
        const std::size_t end = std::min(e.words.find(' ', at), e.words.size());
        if (e.words.substr(at, end - at) == word) return KeyName(e.map, e.words.substr(at, end - at));
        at = end + 1;
      }
      throw std::logic_error("the registry lists no such key for this map");
    }
    throw std::logic_error("the registry lists no such map");
  }
};

/// The handles, by map: `key::<entry>::<key>`, the entry named as one of its map's items.
namespace key {

struct top : KeyMap<"top"> {
  static constexpr KeyName units = handle("units"), analysis = handle("analysis"), materials = handle("materials"),
      joint_sets = handle("joint_sets"), blocks = handle("blocks"), rock_mass = handle("rock_mass"),
      fixed_points = handle("fixed_points"), loads = handle("loads"),
      measurement_points = handle("measurement_points"), water = handle("water"), bolts = handle("bolts"),
      stages = handle("stages");
};
struct analysis : KeyMap<"analysis"> {
  static constexpr KeyName dt = handle("dt"), settle = handle("settle"), dynamic_ratio = handle("dynamic_ratio"),
      time_integration = handle("time_integration"), integrator = handle("integrator"),
      static_force_ratio = handle("static_force_ratio"), static_max_cycles = handle("static_max_cycles"),
      static_local_damping = handle("static_local_damping"), explicit_safety = handle("explicit_safety"),
      explicit_damping = handle("explicit_damping"), stage_local_damping = handle("stage_local_damping"),
      stage_cycles = handle("stage_cycles"), step_tolerance = handle("step_tolerance"),
      step_extrapolation = handle("step_extrapolation"), dt_max = handle("dt_max"), dt_growth = handle("dt_growth"),
      stick_keeps_force = handle("stick_keeps_force"), output_interval = handle("output_interval"),
      output_times = handle("output_times");
};
struct settle : KeyMap<"analysis.settle"> {
  static constexpr KeyName until = handle("until"), max_displacement_ratio = handle("max_displacement_ratio"),
      rest_tolerance = handle("rest_tolerance"), force_ratio = handle("force_ratio"), dt = handle("dt"),
      type = handle("type"), collapse_dt = handle("collapse_dt"), gravity_ramp = handle("gravity_ramp");
};
struct material : KeyMap<"materials"> {
  static constexpr KeyName damping_ratio = handle("damping_ratio");
};
struct joint_set : KeyMap<"joint_sets"> {
  static constexpr KeyName restitution = handle("restitution"), law = handle("law"),
      shear_stiffness = handle("shear_stiffness");
};
struct law : KeyMap<"law"> {
  static constexpr KeyName unidentified = handle("unidentified"), tested_stress = handle("tested_stress"),
      tested_duration = handle("tested_duration");
};
struct block : KeyMap<"blocks"> {
  static constexpr KeyName material = handle("material"), initial_velocity = handle("initial_velocity"),
      polygon = handle("polygon"), rectangle = handle("rectangle"), grid = handle("grid"),
      joint_set = handle("joint_set"), edge_joint_sets = handle("edge_joint_sets");
};
struct rock_mass : KeyMap<"rock_mass"> {
  static constexpr KeyName material = handle("material"), region = handle("region"), holes = handle("holes"),
      boundary_joint_set = handle("boundary_joint_set"), joint_sets = handle("joint_sets"),
      traces = handle("traces");
};
struct rock_mass_joint_set : KeyMap<"rock_mass.joint_sets"> {
  static constexpr KeyName joint_set = handle("joint_set"), spacing = handle("spacing"),
      spacing_deviation = handle("spacing_deviation"), trace_length = handle("trace_length"), gap = handle("gap");
};
struct trace : KeyMap<"rock_mass.traces"> {
  static constexpr KeyName joint_set = handle("joint_set"), to = handle("to");
};
struct fixed_point : KeyMap<"fixed_points"> {
  static constexpr KeyName name = handle("name"), point = handle("point"), block = handle("block");
};
struct load : KeyMap<"loads"> {
  static constexpr KeyName name = handle("name"), point = handle("point"), block = handle("block"),
      force = handle("force"), history = handle("history");
};
struct measurement_point : KeyMap<"measurement_points"> {
  static constexpr KeyName name = handle("name"), point = handle("point"), block = handle("block");
};
struct water : KeyMap<"water"> {
  static constexpr KeyName level = handle("level"), surface = handle("surface"),
      level_history = handle("level_history"), surface_history = handle("surface_history");
};
struct surface_sample : KeyMap<"water.surface_history"> {
  static constexpr KeyName time = handle("time"), surface = handle("surface");
};
struct bolt : KeyMap<"bolts"> {
  static constexpr KeyName name = handle("name"), from = handle("from"), to = handle("to"), law = handle("law"),
      axial_stiffness = handle("axial_stiffness"), pretension = handle("pretension");
};
struct bolt_from : KeyMap<"bolts.from"> {
  static constexpr KeyName point = handle("point"), block = handle("block");
};
struct bolt_to : KeyMap<"bolts.to"> {
  static constexpr KeyName fixed = handle("fixed"), point = handle("point"), block = handle("block");
};
struct stage : KeyMap<"stages"> {
  static constexpr KeyName name = handle("name"), at = handle("at"), after = handle("after"),
      remove_fixed_points = handle("remove_fixed_points"), remove_loads = handle("remove_loads"),
      remove_blocks = handle("remove_blocks"), add_fixed_points = handle("add_fixed_points"),
      add_loads = handle("add_loads"), add_bolts = handle("add_bolts"), joint_sets = handle("joint_sets"),
      analysis = handle("analysis"), settle = handle("settle"), water = handle("water");
};
struct removed_blocks : KeyMap<"stages.remove_blocks"> {
  static constexpr KeyName names = handle("names"), region = handle("region"),
      rock_mass_inside = handle("rock_mass_inside");
};
struct stage_fixed_point : KeyMap<"stages.add_fixed_points"> {
  static constexpr KeyName name = handle("name"), block = handle("block");
};
struct stage_load : KeyMap<"stages.add_loads"> {
  static constexpr KeyName name = handle("name"), block = handle("block"), force = handle("force"),
      history = handle("history");
};
struct stage_joint_set : KeyMap<"stages.joint_sets"> {
  static constexpr KeyName law = handle("law");
};
struct stage_analysis : KeyMap<"stages.analysis"> {
  static constexpr KeyName type = handle("type"), dynamic_ratio = handle("dynamic_ratio");
};

}  // namespace key

/// The keys of a point on a block (`{point, block}`), in whichever map holds one (a
/// fixed point, a load, a measurement point, a bolt's end): what read_block_point reads.
struct PointOnBlock {
  KeyName point;
  KeyName block;
};
template <class Map>
inline constexpr PointOnBlock point_on_block{Map::point, Map::block};

/// The keys of a load's force (`force: [fx, fy]` or `history: [[t, fx, fy], ...]`), of
/// the scene's loads or a stage's: what read_force_or_history reads.
struct ForceOrHistory {
  KeyName force;
  KeyName history;
};
template <class Map>
inline constexpr ForceOrHistory force_or_history{Map::force, Map::history};

}  // namespace rheodda::scene::detail
