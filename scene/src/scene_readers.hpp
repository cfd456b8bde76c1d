// The readers of a scene file's sections, one file each (read_*.cpp), and the
// geometry checks (scene_checks.cpp); parse_scene (loader.cpp) calls them in order.
// Internal to the loader; not installed.
#pragma once

#include <array>

#include <string>
#include <vector>

#include "rheodda/scene/scene.hpp"
#include "yaml_reader.hpp"

namespace rheodda::scene::detail {

/// A block entry before the geometry checks: one or many blocks (grid).
struct RawBlock {
  BlockDescription block;
  std::string path;
  YAML::Node node;
  YAML::Node geometry_node;
};

/// `units:` (read_analysis.cpp).
Units read_units(const Ctx& ctx, const YAML::Node& n);
/// `analysis:` with its `settle:` (read_analysis.cpp).
Analysis read_analysis(const Ctx& ctx, const YAML::Node& n);
/// `materials:` (read_joint_sets.cpp).
std::vector<Material> read_materials(const Ctx& ctx, const YAML::Node& n, bool dynamic_steps);
/// A joint set's `law:` (read_joint_sets.cpp).
/// A `law:` map: its name, parameters and what a fit says of it (`unidentified`,
/// `tested_stress`, `tested_duration`), which are refused with `fit_marks_refused` as the
/// reason when that is not null (a bolt's law, a stage's).
LawChoice read_law(const Ctx& ctx, const YAML::Node& n, const std::string& path, const char* fit_marks_refused);
/// A stage's `joint_sets: {NAME: {...}}` (load_stages.cpp); also the joint set
/// changes of the Python scripting API (joint_set_changes.cpp).
std::vector<StageJointSet> read_stage_joint_sets(const Ctx& ctx, const YAML::Node& n, const std::string& path,
                                                 const SceneDescription& s);
/// `joint_sets:` (read_joint_sets.cpp).
std::vector<JointSetDescription> read_joint_sets(const Ctx& ctx, const YAML::Node& n, bool dynamic_steps);
/// `blocks:` (read_blocks.cpp).
void read_blocks(const Ctx& ctx, const YAML::Node& n, SceneDescription& s, std::vector<RawBlock>& raw);
/// `rock_mass:` (read_rock_mass.cpp).
void read_rock_mass(const Ctx& ctx, const YAML::Node& n, SceneDescription& s, std::vector<RawBlock>& raw);
/// Tolerance for "same place": a billionth of the model size [length] (read_points.cpp).
double geometry_tolerance(const std::vector<BlockDescription>& blocks);
/// `{point, block}` of a fixed point, load, measurement point or bolt's end, by the keys
/// `keys` of its map (read_points.cpp).
BlockPoint read_block_point(const Ctx& ctx, const MapReader& m, const PointOnBlock& keys, const SceneDescription& s,
                            double tol);
/// A load's `force: [fx, fy]` (already read into `history` as its one sample) or
/// `history: [[t, fx, fy], ...]` (times >= 0, strictly increasing) into `history`;
/// exactly one of them. `times` ends the message asking for one (" (t from the
/// stage's start)" for a stage's load). `keys`: the two keys of the load's map.
void read_force_or_history(const Ctx& ctx, const MapReader& m, const ForceOrHistory& keys,
                           std::vector<std::array<double, 3>>& history, const std::string& times);
/// `fixed_points:`, `loads:`, `measurement_points:` (read_points.cpp).
void read_points(const Ctx& ctx, const MapReader& top, SceneDescription& s);
/// `water:` (load_water.cpp; after the blocks: its surface must span them).
/// `path`: where the map stands ("water", or a stage's "stages[i].water").
WaterDescription read_water(const Ctx& ctx, const YAML::Node& n, const SceneDescription& s,
                            const std::string& path = "water");
/// `stages:` (load_stages.cpp), after every other section.
void read_stages(const Ctx& ctx, const YAML::Node& n, SceneDescription& s);
/// `bolts:` (load_bolts.cpp).
void read_bolts(const Ctx& ctx, const MapReader& top, SceneDescription& s);
/// One bolt (load_bolts.cpp): of `bolts:`, or installed by a stage (`at_stage`: each
/// end on a block names its block, its point is where the block stands then);
/// `taken`: the names of the bolts read before it.
BoltDescription read_bolt(const Ctx& ctx, const YAML::Node& n, const std::string& path, const SceneDescription& s,
                          const std::vector<std::string>& taken, bool at_stage);
/// The names of the scene's bolts and of those its stages read so far install.
std::vector<std::string> bolt_names(const SceneDescription& s);
/// Every block a simple polygon, no two overlapping, edges' joint sets (scene_checks.cpp).
void check_geometry(const Ctx& ctx, std::vector<RawBlock>& raw, SceneDescription& s);

}  // namespace rheodda::scene::detail
