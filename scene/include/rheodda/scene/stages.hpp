// `stages:` of a scene file (docs/reference/stages.md): an ordered list of changes to
// the model during the run - blocks removed (excavation), fixed points and
// loads added or removed, joint sets given new strength or law parameters, the
// analysis switched between static and dynamic, a settling stage opened -
// each at a time or when the settling stage opened by the stage before it has
// ended at rest. Read by load_stages.cpp, applied by run_stages.cpp. Included by
// scene.hpp after the types it uses (BoltDescription); include scene.hpp, not this.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/laws/parameters.hpp"
#include "rheodda/scene/error.hpp"
#include "rheodda/scene/water.hpp"

namespace rheodda::scene {

/// When a stage begins.
enum class StageStart {
  at,       ///< `at: <time>`: a step ends exactly there
  settled,  ///< `after: settled`: at the end of the step in which the settling stage
            ///< opened before it (the stage before's `settle: true`, or for the first
            ///< stage the analysis's `settle:`) ended at rest
};

/// A fixed point or load a stage adds: `{name, point, block}` (+ force or history for a load).
struct StagePoint {
  std::string name;        ///< optional; what a later stage removes it by
  std::array<double, 2> point{0.0, 0.0};  ///< where the material point stands at the stage [length]
  int block = 0;           ///< index into SceneDescription::blocks (`block:` is required)
  std::string hold = "both";  ///< add_fixed_points: what is held, `both`, `x`, `y` or `rotation`
  /// Loads: (t [time] from the stage's start, fx, fy [force]) samples, strictly
  /// increasing t; a constant `force` is one sample at 0. Empty for a fixed point.
  std::vector<std::array<double, 3>> history;
  SourceLocation where{};
};

/// `joint_sets: {NAME: {...}}` of a stage: the values given replace the joint
/// set's; those not given keep theirs.
struct StageJointSet {
  int joint_set = 0;                            ///< index into SceneDescription::joint_sets
  /// The joint set's properties it changes, by name (contact/joint_set_specs.hpp: those
  /// declared between_steps; each in its declared unit and range); the others unchanged.
  std::map<std::string, double, std::less<>> properties;
  /// `law: {name, parameters...}`: the law given whole (its parameters; its
  /// name must be the joint set's law: a stage cannot add, remove or replace a law).
  std::optional<std::string> law_name;
  laws::ParameterValues law_parameters;  ///< every parameter, defaults filled in
  SourceLocation where{};
};

/// One stage.
struct StageDescription {
  std::string name;                     ///< required, unique; history.csv's `stage` column
  StageStart start = StageStart::at;
  double at = 0.0;                      ///< `at` [time]; in (0, duration), increasing
  /// `remove_blocks:` resolved to block indices (by `names`, by `region`: initial
  /// centroid inside the polygon, by `rock_mass_inside`: generated blocks whose
  /// initial centroid is inside the polygon), in increasing order.
  std::vector<int> remove_blocks;
  std::vector<std::string> remove_fixed_points;  ///< by name
  std::vector<std::string> remove_loads;         ///< by name
  std::vector<StagePoint> add_fixed_points;
  std::vector<StagePoint> add_loads;
  std::vector<StageJointSet> joint_sets;
  /// `add_bolts:` bolts installed at the stage (the keys of `bolts:`; their end
  /// points are where the ends stand at the stage; an end whose `block:` is left
  /// out has block -1: the block standing there at the stage). Installed at the
  /// length between its ends then.
  std::vector<BoltDescription> add_bolts;
  /// `analysis: {type: static|dynamic, dynamic_ratio}`: the share of velocity
  /// carried from now on (0 static; default 1 for dynamic) [-]; unset: unchanged.
  std::optional<double> dynamic_ratio;
  bool settle = false;                  ///< `settle: true`: a settling stage opens (analysis.settle's values)
  /// `water:` from the stage on: the keys of the scene's `water:` (water.hpp), its
  /// times counted from the stage's start (as a stage's load histories); unset: unchanged.
  std::optional<WaterDescription> water;
  SourceLocation where{};
  SourceLocation remove_blocks_where{}, remove_fixed_points_where{}, remove_loads_where{}, add_fixed_points_where{},
      add_loads_where{}, joint_sets_where{}, settle_where{}, water_where{}, add_bolts_where{};
};

}  // namespace rheodda::scene
