// SceneDescription: a scene file (docs/reference/scene-format.md) as plain structs.
//
// Why plain structs. The loader (loader.hpp) turns YAML into these, checks every
// value and the geometry, and fills in every default; after that nothing in the
// program reads YAML again. `rheodda check` prints them, `rheodda run` builds the
// engine's model from them (build.hpp), summary.json echoes them.
//
// Names: each field has the name of its YAML key (snake_case), which is also its
// CSV column and the word the docs use. Units are the scene's own (`units:`):
// [length], [force], [time]; derived: [stress] = force/length^2 (per unit
// thickness: 2D), [mass] = force*time^2/length. Geometry is 2D, unit thickness.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/core/methods.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/laws/contact_rheology.hpp"
#include "rheodda/laws/parameters.hpp"
#include "rheodda/rockmass/cut.hpp"
#include "rheodda/rockmass/generate.hpp"
#include "rheodda/scene/error.hpp"
#include "rheodda/scene/water.hpp"

namespace rheodda::scene {

using Point = std::array<double, 2>;  ///< (x, y) [length]

/// Unit labels, repeated in every output. A bare number in the file is in these units; a
/// value written with a unit of its own ("2600 kg/m^3") is converted into them, which
/// needs labels UDUNITS-2 knows (m, mm, N, kN, s, h, d, ...; docs/reference/scene-format.md, "Units").
struct Units {
  std::string length;  ///< e.g. "m", "mm"
  std::string force;   ///< e.g. "N", "MN"
  std::string time;    ///< e.g. "s", "h", "d"
  /// "force/length^2" spelled with the labels, e.g. "N/mm^2".
  std::string stress() const { return force + "/" + length + "^2"; }
};

enum class AnalysisType { static_analysis, dynamic_analysis };

/// `time_integration: shi|trapezoidal`: the engine's (core/model.hpp).
using TimeIntegration = core::TimeIntegration;
/// `history`: history.csv's rows at the output times (and the steps that end a dynamic
/// stage, open a collapse stage or fail a contact's law), or at every accepted step.
enum class HistoryRows { outputs, steps };

/// The warnings a scene's author may turn off, having checked what they warn of
/// (scene_warnings): `analysis.accept_*`, declared in acceptance_specs (keys.hpp) as the
/// engine's settings are, by key word, unit, range, default and meaning.
struct Acceptances {
  /// `accept_unresolved_impacts`: dynamic steps above a tenth of the contacts' vibration
  /// period, where a joint set's restitution does not act as given, do not change the
  /// answer (checked e.g. with `rheodda check --refine`) [-].
  bool accept_unresolved_impacts = false;
  /// `accept_other_gravity`: a gravity other than the Earth's is deliberate (no warning
  /// that |gravity| is not 9.81 m/s^2 within 2 % in the scene's units) [-].
  bool accept_other_gravity = false;
};

/// The run's own numbers and flags (how long, what is written, when it stops):
/// `analysis.duration`, `output_interval`, `frames`, `max_travel_ratio` and
/// `max_output_size`, declared in run_control_specs (keys.hpp) as the engine's settings
/// are, by key word, unit, range, default (these initializers) and meaning.
struct RunControls {
  double duration = 0.0;         ///< simulated time [time]; required, > 0
  double output_interval = 0.0;  ///< time between output times [time]; 0: duration / 100, dt when longer
  /// `frames`: contacts.csv, bolts.csv and the VTK frames are written at the output
  /// times; false: history.csv, events.csv and summary.json only (a study's cases).
  bool frames = true;
  /// Run guard: the run stops when a block vertex has moved more than this times the
  /// model size (largest extent of the initial blocks) [-]; 0 = no limit.
  double max_travel_ratio = 10.0;
  /// Run guard: the run stops when its outputs (CSV files and frames) exceed this size [MB]; 0 = no limit.
  double max_output_size = 10000.0;
};

/// `analysis:` — time stepping, contact numerics, outputs.
///
/// It is the engine's settings (core::Settings: dt, dt_growth, ..., the settling stage
/// `settle`, the choices solver, contact_solver, integrator, time_integration, gravity) and
/// the contact layer's (contact::ContactSettings: penalty, ..., stick_keeps_force, scheme)
/// themselves: a key of the name of a declared setting (core/settings.hpp,
/// contact/contact_settings_specs.hpp) reads into the member, with the declaration's unit,
/// range, default and meaning (keys.cpp), and build_scene hands both on whole. What
/// follows are the scene's own: the analysis type and duration, the outputs and the run
/// guards.
///
/// Defaults: Settings{}'s and ContactSettings{}'s, but those of a static analysis (the
/// default `type`) where the declaration says they differ (dynamic_ratio, open_close_limit);
/// the loader gives a dynamic one the engine's dynamic default, and stick_keeps_force the
/// rule its declaration states. `gravity` is required (0 until read).
struct Analysis : core::Settings, contact::ContactSettings, Acceptances, RunControls {
  Analysis();
  AnalysisType type = AnalysisType::static_analysis;  ///< `type: static|dynamic`
  /// The scene has a settling stage (`settle:`; Settings::settle, whose `until` the
  /// loader always sets > 0 then).
  bool has_settle() const { return settle.until > 0.0; }
  /// The run has dynamic steps: a dynamic analysis, or a dynamic settling stage (by the
  /// analysis's type, where Settings::has_dynamic_steps goes by dynamic_ratio).
  bool has_dynamic_steps() const {
    return type == AnalysisType::dynamic_analysis || (has_settle() && settle.dynamic);
  }
  bool stick_keeps_force_given = false;  ///< the scene gave stick_keeps_force (else a dynamic settling
                                         ///< stage of a static analysis keeps the force, its static steps not)
  /// `output_times`: output times besides every output_interval [time]; strictly
  /// increasing, in (0, duration]; empty: none. A study adds its `times` here.
  std::vector<double> output_times;
  /// `history`: which steps history.csv has a row of (docs/reference/outputs.md, "history.csv").
  HistoryRows history = HistoryRows::outputs;
  SourceLocation where{};
};

/// `materials: {NAME: {...}}` — block material.
/// `materials: {NAME: {...}}`: the engine's Material, whose density, young_modulus,
/// poisson_ratio and damping_ratio are declared in core/property_specs.hpp (the keys of
/// the same names; build_scene hands it on whole). A scene requires the first three, and
/// its `plane` defaults to strain (the engine's Material{} to plane stress).
struct Material : core::Material {
  Material() { plane = core::PlaneMode::plane_strain; }
  std::string name;
  SourceLocation where{};
};

/// `law:` of a joint set: a law of laws::LawRegistry::builtin() with complete, validated parameters.
struct LawChoice {
  std::string name;               ///< e.g. "burgers"
  laws::ParameterValues parameters;  ///< by the registry's names (E1, E2, eta1, eta2, ...), defaults filled in
  // What a fit says of the law (`rheodda fit --yaml` writes them; docs/guide/fitting.md,
  // "What a fitted law carries into a scene"); a joint set's law only.
  /// `unidentified: [Fs, ...]`: parameters the data it was fitted to do not determine.
  std::vector<std::string> unidentified;
  /// `tested_stress: [lowest, highest]` [stress]: the shear stresses of the tests it was fitted to.
  std::optional<std::vector<double>> tested_stress;
  /// `tested_duration` [time]: the duration of the longest test it was fitted to.
  std::optional<double> tested_duration;
};

/// `joint_sets: {NAME: {...}}` — joints: strength, stiffness, optional creep law. Its
/// strength and stiffness are the contact layer's JointProperties (friction_angle,
/// cohesion, ... restitution), whose declarations (contact/joint_set_specs.hpp) are the
/// keys of the same names; friction_angle is required in a scene.
struct JointSetDescription : contact::JointProperties {
  std::string name;
  std::optional<LawChoice> law;   ///< creep of the shear spring; unset: none
  bool record = false;            ///< history.csv gets this set's mean shear displacement and force
  SourceLocation where{};
};

/// One block after expansion of the shorthands (`rectangle`, `grid`).
struct BlockDescription {
  std::string name;              ///< user name, or "block<i>", or "<grid>.r<row>.c<col>"
  int material = 0;              ///< index into SceneDescription::materials
  std::vector<Point> polygon;    ///< counter-clockwise, first vertex not repeated [length]
  std::vector<int> edge_joint_set;  ///< joint set index of edge k (vertex k -> k+1)
  bool fixed = false;            ///< fixed points at every vertex
  std::array<double, 3> initial_stress{0.0, 0.0, 0.0};    ///< (sigma_x, sigma_y, tau_xy) [stress]
  std::array<double, 3> initial_velocity{0.0, 0.0, 0.0};  ///< (vx, vy [length/time], omega [1/time])
  SourceLocation where{};
};

/// A point attached to a block (fixed, loaded or measured).
struct BlockPoint {
  std::string name;       ///< fixed_points, loads: optional `name` a stage removes it by (empty: none)
  Point point{0.0, 0.0};  ///< [length]
  int block = 0;          ///< index into SceneDescription::blocks
  /// fixed_points only: what is held, `both` directions, `x` or `y` (a penalty spring in
  /// that direction alone) or `rotation` (the block's rotation alone, a rotational spring;
  /// build_fixed_point; docs/reference/scene-format.md, "fixed_points").
  std::string hold = "both";
  SourceLocation where{};
};

/// `loads:` — a point load, constant or piecewise linear in time.
struct LoadDescription {
  BlockPoint at;
  /// (t [time], fx, fy [force]) samples, strictly increasing t; linear in between,
  /// held constant before the first and after the last. A constant `force` is one sample at t = 0.
  std::vector<std::array<double, 3>> history;
};

/// `measurement_points:` — a point whose displacement goes to history.csv.
struct MeasurementPoint {
  std::string name;  ///< column prefix in history.csv
  BlockPoint at;
};

/// `rock_mass:` — blocks cut from a region by joint sets (docs/guide/rockmass.md). The loader
/// generates the traces, cuts the region (rockmass::cut_blocks) and appends the blocks
/// to SceneDescription::blocks; this keeps what was asked and what came out.
struct RockMassDescription {
  std::string name = "rock";        ///< block names are <name>.<k>, k = 1, 2, ...
  int material = 0;                 ///< index into SceneDescription::materials
  rockmass::Region region;          ///< outer polygon and holes [length]
  int boundary_joint_set = 0;       ///< joint set of the edges on the region's boundary
  std::uint64_t seed = 1;           ///< of the random generation
  double sliver_area = 0.0;         ///< blocks below this area are merged into a neighbour [length^2]
  std::vector<rockmass::JointSetGeneration> joint_sets;  ///< tag = index into SceneDescription::joint_sets
  std::vector<rockmass::Trace> traces;                   ///< explicit traces; tag as above
  // What came out:
  std::size_t first_block = 0;      ///< the generated blocks are blocks[first_block, first_block + block_count)
  std::size_t block_count = 0;
  std::vector<std::vector<bool>> edge_on_boundary;  ///< per generated block and edge: on the region's boundary
  /// Per rock_mass joint set: its traces that reach the region (drawn over the region's box,
  /// clipped to it; those outside a concave region or only in a hole not counted).
  std::vector<std::size_t> traces_generated;
  std::map<int, double> joint_length;  ///< per joint set index (-1: the region's boundary): edge length in blocks [length]
  int merged_slivers = 0;
  int dangling_removed = 0;
  int extended_traces = 0;          ///< traces continued so that every block is a simple polygon
  int added_traces = 0;             ///< of these, joints added parallel to a block's joints (a hole no trace reached)
  int collapsed_blocks = 0;         ///< blocks of rounding size dropped when their vertices were welded
  double area_error = 0.0;          ///< |sum of block areas - region area| / region area [-]
  rockmass::CutEstimate estimate;   ///< what the cut was expected to cost, before cutting
  SourceLocation where{};
};

}  // namespace rheodda::scene

#include "rheodda/scene/bolts.hpp"   // uses BlockPoint and LawChoice above
#include "rheodda/scene/stages.hpp"  // uses BoltDescription

namespace rheodda::scene {

/// A value the file gave with a unit of its own ("2600 kg/m^3"): `rheodda check` shows it
/// in the scene's units beside the text it was given as.
struct GivenQuantity {
  std::string key;         ///< "materials.rock.density", "analysis.gravity[1]"
  SourceLocation where;    ///< of the value in the file
  std::string text;        ///< as written: "2600 kg/m^3"
  double value = 0.0;      ///< in the scene's units
  std::string unit;        ///< the scene's unit it is now in ("N*s^2/m^4"); "" for none
  /// A force given as a bare force unit ("84.5 kN"): read as per unit thickness of the
  /// scene's length (a 2D scene's forces are per unit thickness).
  bool per_thickness = false;
};

struct SceneDescription {
  std::string file;   ///< the scene file's path as given
  std::string title;  ///< `title:`; default: the file name
  Units units;
  Analysis analysis;
  std::vector<Material> materials;
  std::vector<JointSetDescription> joint_sets;
  std::vector<BlockDescription> blocks;
  std::vector<BlockPoint> fixed_points;  ///< explicit ones only; `fixed: true` blocks are in BlockDescription
  std::vector<LoadDescription> loads;
  std::vector<MeasurementPoint> measurement_points;
  std::optional<RockMassDescription> rock_mass;  ///< `rock_mass:`, if given
  std::optional<WaterDescription> water;          ///< `water:`, if given (water.hpp)
  std::vector<StageDescription> stages;          ///< `stages:` (docs/reference/stages.md), in order
  std::vector<BoltDescription> bolts;  ///< `bolts:` (bolts.hpp); empty: none
  std::vector<GivenQuantity> given_quantities;  ///< the values written with a unit, in file order
};

}  // namespace rheodda::scene
