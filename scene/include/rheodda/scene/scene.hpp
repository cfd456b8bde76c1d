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

#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/contact/joint_set.hpp"
#include "rheodda/core/methods.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/core/setting_defaults.hpp"
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

enum class TimeIntegration { shi, trapezoidal };
/// `history`: history.csv's rows at the output times (and the steps that end a dynamic
/// stage, open a collapse stage or fail a contact's law), or at every accepted step.
enum class HistoryRows { outputs, steps };

/// `analysis:` — time stepping, contact numerics, outputs.
///
/// A field named as a setting of the engine (core/settings.hpp: dt_growth, dt_cut,
/// max_cuts, ...) is that setting as the scene gives it: its key's unit, range, default
/// and meaning are the setting's declaration (keys.cpp), its default here the engine's
/// in a static analysis (the default `type`; the loader gives a dynamic one the
/// engine's dynamic default where it differs: dynamic_ratio, open_close_limit), and
/// build_scene copies it into core::Settings through the declarations.
struct Analysis {
  /// The default of the engine's setting `name` in a static analysis.
  template <class T>
  static T default_of(std::string_view name) { return core::setting_default_as<T>(name, false); }
  /// The default of the contact layer's declared setting `name` (contact/contact_settings_specs.hpp).
  template <class T>
  static T contact_default_of(std::string_view name) {
    return static_cast<T>(*contact::contact_setting_spec(name).parameter.default_value);
  }
  AnalysisType type = AnalysisType::static_analysis;  ///< `type: static|dynamic`
  double duration = 0.0;               ///< simulated time [time]; required, > 0
  double dt = 0.0;                     ///< first and largest time step [time]; required, > 0
  double dt_growth = default_of<double>("dt_growth");              ///< fixed dt: after a cut, each accepted step grows by this factor,
                                       ///< up to dt [-]; >= 1; not under creep_tolerance or step_tolerance
  double dt_cut = default_of<double>("dt_cut");                 ///< factor on the step when a step is cut [-]; in (0, 1)
  int max_cuts = default_of<int>("max_cuts");                   ///< cuts of dt (x dt_cut each) allowed in one step before the run fails [-]
  double max_displacement_ratio = default_of<double>("max_displacement_ratio");  ///< Shi's g2: allowed step displacement / half model size [-]
  /// `settle: {until, dt, max_displacement_ratio, type, collapse_dt, gravity_ramp, rest_tolerance}`: a settling stage at the start
  /// (docs/reference/engine.md, "Settling stage"): steps of at most `dt` with the displacement
  /// limit `max_displacement_ratio` until `until`, then the analysis's own.
  struct Settle {
    double until = 0.0;                   ///< end of the stage [time]; > 0, < duration
    double dt = 0.0;                      ///< largest step in it [time]; > 0, <= until
    double max_displacement_ratio = 0.0;  ///< Shi's g2 of the stage's steps [-]; default the analysis's
    /// `type: dynamic`: the stage's steps carry velocity (with the materials'
    /// damping_ratio and the joint sets' restitution), and a static analysis
    /// goes on from rest after it; default `static` (the analysis's own kind).
    bool dynamic = false;
    /// Collapse stages (docs/reference/engine.md, "Collapse stages"): a later static step
    /// that moves as a mechanism is cut down to this size, then taken as a
    /// dynamic stage as long as this one [time]; 0 = none; dynamic stage only.
    double collapse_dt = 0.0;
    /// `gravity_ramp`: gravity rises linearly from zero at t = 0 to its full value
    /// at this time, within the stage (docs/reference/engine.md, "Gravity ramp") [time];
    /// 0 = gravity at once; > 0, <= until.
    double gravity_ramp = 0.0;
    /// `rest_tolerance`: the stage, and every collapse stage, ends at rest:
    /// after a step whose motion's kinetic energy is below this fraction of the
    /// energy the stage took in or released (docs/reference/engine.md, "Dynamic
    /// stages"); `until` is then the longest a stage may last (default: the
    /// duration) [-]; 0 = stages last `until`; in (0, 1); dynamic stage only.
    double rest_tolerance = 0.0;
    /// `force_ratio`: with the explicit step, a stage's explicit step is at rest when its
    /// unbalanced-force ratio (the largest unbalanced force of a moving block over the mean
    /// force applied to the moving blocks) is below this, instead of the kinetic-energy test
    /// of `rest_tolerance` (docs/reference/explicit-step.md, "Rest by the unbalanced force")
    /// [-]; 0 = the kinetic-energy test; in (0, 1); with `rest_tolerance` only.
    double force_ratio = 0.0;
    /// `open_close_limit`: open-close iterates before a step of a dynamic stage
    /// is cut [-]; 0 (not given) = the analysis's `open_close_limit`.
    int open_close_limit = 0;
  };
  /// The run has dynamic steps: a dynamic analysis, or a dynamic settling stage.
  bool has_dynamic_steps() const {
    return type == AnalysisType::dynamic_analysis || (settle && settle->dynamic);
  }
  std::optional<Settle> settle;
  double dynamic_ratio = default_of<double>("dynamic_ratio");  ///< share of velocity carried to the next step [-]
  /// Inertia terms `time_integration: shi|trapezoidal` (docs/reference/engine.md); trapezoidal needs
  /// a dynamic analysis with dynamic_ratio > 0.
  TimeIntegration time_integration = TimeIntegration::shi;
  /// Rheology scheme `lagged|implicit|exponential-linear`; unset (`automatic`, the default):
  /// per joint set and step, exponential-linear where the step is below its no-ringing
  /// limit, implicit otherwise (contact::ContactSettings::scheme).
  std::optional<laws::Scheme> scheme;
  double creep_tolerance = default_of<double>("creep_tolerance");        ///< adaptive creep stepping: creep error allowed per step [length]; 0 = fixed dt
  double step_tolerance = default_of<double>("step_tolerance");         ///< step doubling: vertex difference allowed between one step of dt
                                       ///< and two of dt/2 [length]; 0 = off; not with creep_tolerance
  bool step_extrapolation = default_of<bool>("step_extrapolation");      ///< under step_tolerance: accept 2 y(dt/2) - y(dt) (second order)
  double dt_max = default_of<double>("dt_max");                 ///< largest step under creep_tolerance or step_tolerance [time];
                                       ///< 0 = no limit
  bool creep_restart_on_contact_change = default_of<bool>("creep_restart_on_contact_change");  ///< under creep_tolerance: restart from dt after a step
                                                ///< in which a creeping contact changed state
  // The contact layer's settings of the same names (contact/contact_settings_specs.hpp
  // declares them; their defaults are ContactSettings{}'s):
  double penalty = contact_default_of<double>("penalty");  ///< normal contact penalty p_n [stress]; 0: the loader's,
                                                           ///< 40 x largest young_modulus (seed eq. 17)
  double shear_normal_ratio = contact_default_of<double>("shear_normal_ratio");  ///< p_n / p_s of penalty shear springs [-]
  double search_factor = contact_default_of<double>("search_factor");  ///< search distance / (max_displacement_ratio w0) [-]
  double angle_tolerance = contact_default_of<double>("angle_tolerance");  ///< angle rule tolerance [deg]
  double penetration_ratio = contact_default_of<double>("penetration_ratio");  ///< allowed penetration / half model size [-]
  bool stick_keeps_force = false;      ///< a sliding contact that sticks keeps its friction force
                                       ///< (contact::ContactSettings::stick_keeps_force) [-];
                                       ///< the loader's default: true in a dynamic analysis
  /// `accept_unresolved_impacts`: the scene's author has checked (e.g. with `rheodda check
  /// --refine`) that dynamic steps above a tenth of the contacts' vibration period, where
  /// a joint set's restitution does not act as given, do not change the answer: no
  /// warning about it (scene_warnings) [-].
  bool accept_unresolved_impacts = false;
  /// `accept_other_gravity`: a gravity other than the Earth's is deliberate: no warning
  /// that |gravity| is not 9.81 m/s^2 within 2 % in the scene's units (scene_warnings) [-].
  bool accept_other_gravity = false;
  bool stick_keeps_force_given = false;  ///< the scene gave stick_keeps_force (else a dynamic settling
                                         ///< stage of a static analysis keeps the force, its static steps not)
  // The open-close iteration (contact::ContactSettings fields of the same names, declared
  // in contact/contact_settings_specs.hpp):
  double friction_tolerance = contact_default_of<double>("friction_tolerance");  ///< relative change of N that asks for one more iterate [-]
  double force_resolution = contact_default_of<double>("force_resolution");  ///< force resolution / largest normal force [-]
  int max_flips = contact_default_of<int>("max_flips");  ///< state changes per contact and step before only locking [-]
  int max_refinements = contact_default_of<int>("max_refinements");  ///< friction refinements per contact and step [-]
  double penalty_raise = contact_default_of<double>("penalty_raise");  ///< factor on the penalty when penetration exceeds its limit [-]
  double penalty_max_factor = contact_default_of<double>("penalty_max_factor");  ///< largest penalty / initial penalty [-]
  int open_close_limit = default_of<int>("open_close_limit");  ///< open-close iterations before a step is cut [-]
  double fixed_point_stiffness = default_of<double>("fixed_point_stiffness");  ///< fixed-point spring [force/length]; 0: automatic
  core::SolverKind solver = core::SolverKind::automatic;  ///< `solver`: the words are core::linear_solvers()'
  double solver_tolerance = default_of<double>("solver_tolerance");     ///< relative residual at which pcg and amg stop [-]
  double solver_iterate_tolerance = default_of<double>("solver_iterate_tolerance");  ///< the same in open-close iterates whose states still change [-]
  /// `contact_solver`: `open-close` (Shi's iteration, until no contact changes its
  /// state) or `newton` (the same iterates, accepted on the residual of the step's
  /// equations; docs/reference/contacts.md, "Contact solves")
  core::ContactSolver contact_solver = core::ContactSolver::open_close;
  /// `integrator`: `implicit` (Shi's step), `explicit` (dynamic steps in explicit cycles) or
  /// `automatic` (the one estimated cheaper on the initial state, resolved by build_scene through
  /// choose_integrator, integrator_choice.hpp); the words are core::integrators()'.
  core::Integrator integrator = core::Integrator::implicit;
  double explicit_safety = default_of<double>("explicit_safety");        ///< the explicit cycle / the stable one [-]; in (0, 1]
  double explicit_damping = default_of<double>("explicit_damping");       ///< damping ratio the explicit cycles give what has no damping
                                       ///< of its own (contacts, blocks' strain modes) [-]; in [0, 1]
  double stage_local_damping = default_of<double>("stage_local_damping");    ///< local damping of explicit cycles in the dynamic stages
                                       ///< of a static analysis [-]; in [0, 1)
  int stage_cycles = default_of<int>("stage_cycles");                ///< density scaling: the most explicit cycles per step of a
                                       ///< dynamic stage of a static analysis [-]; 0 = none
  double static_force_ratio = default_of<double>("static_force_ratio");     ///< static steps by explicit cycles until the unbalanced-force
                                       ///< ratio is at most this [-]; in [0, 1); 0 = static steps implicit
  int static_max_cycles = default_of<int>("static_max_cycles");      ///< the most cycles of a static step by cycles [-]; >= 1
  double static_local_damping = default_of<double>("static_local_damping");   ///< local damping of the static steps by cycles [-]; in (0, 1)
  /// `contact_residual_tolerance`: under `newton`, a step is accepted when the
  /// residual of its equations is at most this fraction of the contact forces [-]; in (0, 1)
  double contact_residual_tolerance = default_of<double>("contact_residual_tolerance");
  int solver_max_iterations = default_of<int>("solver_max_iterations");   ///< CG iteration limit per solve of pcg and amg [-]; >= 1
  double output_interval = 0.0;        ///< time between output times [time]; default duration / 100
  /// `output_times`: output times besides every output_interval [time]; strictly
  /// increasing, in (0, duration]; empty: none. A study adds its `times` here.
  std::vector<double> output_times;
  /// `history`: which steps history.csv has a row of (docs/reference/outputs.md, "history.csv").
  HistoryRows history = HistoryRows::outputs;
  /// `frames`: contacts.csv, bolts.csv and the VTK frames are written at the output
  /// times; false: history.csv, events.csv and summary.json only (a study's cases).
  bool frames = true;
  /// Run guard: the run stops when a block vertex has moved more than this times the
  /// model size (largest extent of the initial blocks) [-]; 0 = no limit.
  double max_travel_ratio = 10.0;
  /// Run guard: the run stops when its outputs (CSV files and frames) exceed this size [MB]; 0 = no limit.
  double max_output_size = 10000.0;
  Point gravity{0.0, 0.0};             ///< gravity acceleration (gx, gy) [length/time^2]; required
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

std::string_view analysis_type_name(AnalysisType t);
std::string_view plane_name(core::PlaneMode p);
std::string_view time_integration_name(TimeIntegration t);
std::string_view history_rows_name(HistoryRows h);

}  // namespace rheodda::scene
