// The DDA host engine (Shi 1988): blocks with six unknowns each, the block
// sub-matrices (elastic, initial stress, point loads, body force, inertia,
// fixed points), a sparse global system solved by CHOLMOD or PCG, and time
// stepping with the open-close iteration and step-size control.
//
// Contacts are not the engine's business: it drives a ContactModel
// (contact_model.hpp) through begin_step -> {assemble -> solve -> check}* ->
// end_step (or abandon_step when the step is cut) and gives it a SystemSink to
// add its 6x6 terms. A scene without contacts uses NullContactModel and does
// no contact work at all.
//
// Usage:
//   rheodda::core::Model m;
//   rheodda::core::BlockDef b;  b.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
//   m.blocks.push_back(b);
//   rheodda::core::Engine engine(m);          // or Engine(m, contacts)
//   engine.add_observer([](const Engine& e, const StepReport& r) { ... });
//   engine.run(100);
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/block_state.hpp"
#include "rheodda/core/contact_model.hpp"
#include "rheodda/core/energy.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/core/solver_state.hpp"

namespace rheodda::core {

/// What happened in one accepted step.
struct StepReport {
  int step = 0;               ///< index of the step (0-based)
  double time = 0.0;          ///< time at the end of the step [time]
  double dt = 0.0;            ///< step size used [time]
  int iterations = 0;         ///< open-close iterations of the accepted attempt (under
                              ///< Settings::step_tolerance: of its three solves) [-]
  int cuts = 0;               ///< times dt was cut before acceptance [-]
  int search_widenings = 0;   ///< times the step was redone with a wider contact search
                              ///< because a vertex moved beyond its reach (docs/reference/engine.md,
                              ///< "Contact search reach") [-]
  double max_displacement = 0.0;  ///< largest vertex displacement of the step [length]
  double max_penetration = 0.0;   ///< largest penetration reported by the contacts [length]
  double creep_error = 0.0;       ///< contacts' creep error estimate of the step, under
                                  ///< Settings::creep_tolerance only (else 0) [length]
  int rejections = 0;             ///< times the step was redone smaller because its error
                                  ///< estimate exceeded 2 x Settings::creep_tolerance (or
                                  ///< step_tolerance) [-]
  int creep_state_changes = 0;    ///< creeping contacts whose state changed in the step, under
                                  ///< Settings::creep_tolerance only (else 0) [-]
  bool collapse_stage = false;    ///< the step opened a collapse stage (SettleStage::collapse_dt):
                                  ///< its static attempt moved as a mechanism at collapse_dt [-]
  double step_error = 0.0;         ///< step-doubling error estimate max |y(dt/2, twice) - y(dt)| over
                                  ///< the block vertices, under Settings::step_tolerance only [length]
  bool extrapolated = false;      ///< under Settings::step_tolerance: the step was extrapolated
                                  ///< (2 y(dt/2) - y(dt)); false: y(dt/2) stands
  int cycles = 0;                 ///< explicit cycles of the accepted attempt (Settings::integrator;
                                  ///< 0: an implicit step) [-]
  double cycle_dt = 0.0;          ///< length of those cycles [time]
  int stable_block = -1;          ///< the block whose stable cycle set their length (-1: none) [-]
  double mass_scale = 1.0;        ///< the largest density scale of the blocks' masses in those
                                  ///< cycles (Settings::stage_cycles) [-]
  ContactChanges changes;         ///< what the contact checks changed, summed over every
                                  ///< open-close iterate of every attempt of the step [-]
  EnergyFlows energy;             ///< the step's energy flows and residual (energy.hpp) [force x length]
  double assembly_seconds = 0.0;  ///< wall time spent assembling K and F (all attempts) [s]
  double solve_seconds = 0.0;     ///< wall time spent in the linear solver (all attempts) [s]
};

/// One recorded sample of a measurement point.
struct MeasurementSample {
  int step = 0;                      ///< step index (-1 = initial state)
  double time = 0.0;                 ///< [time]
  Vec2 position = Vec2::Zero();      ///< current position [length]
  Vec2 displacement = Vec2::Zero();  ///< position minus initial position [length]
};

/// What kind of dynamic stage (docs/reference/engine.md, "Dynamic stages").
enum class StageKind {
  settling,   ///< the settling stage at the start of a static analysis (SettleStage::until)
  mechanism,  ///< a part a static step found without equilibrium, taken dynamically (SettleStage::collapse_dt)
};

/// Name used in outputs: "settling", "mechanism".
const char* stage_kind_name(StageKind k);

/// One dynamic stage of a static analysis, from its start to its end (the
/// events table, docs/reference/outputs.md).
struct StageEvent {
  StageKind kind = StageKind::settling;
  double start_time = 0.0;           ///< [time]
  double end_time = 0.0;             ///< [time]
  int start_step = 0;                ///< first step of the stage
  int steps = 0;                     ///< accepted steps in the stage [-]
  bool at_rest = false;              ///< ended because its kinetic energy had decayed
                                     ///< (SettleStage::rest_tolerance), not at its longest
  int blocks_involved = 0;           ///< blocks with a vertex that moved more than the stage's
                                     ///< step limit (settle.max_displacement_ratio w0) over the stage [-]
  double largest_displacement = 0.0; ///< largest vertex displacement over the stage [length]
  double kinetic_energy_peak = 0.0;  ///< largest kinetic energy after a step of the stage [force x length]
  double kinetic_energy_end = 0.0;   ///< kinetic energy left at its end (dropped by the next
                                     ///< static step) [force x length]
  double work = 0.0;                 ///< work of gravity and loads over the stage [force x length]
  double energy_dissipated = 0.0;    ///< dissipation over the stage's steps (friction, creep,
                                     ///< integration, dashpots, springs attached or detached) [force x length]
};

/// The dynamic stage in progress (docs/reference/engine.md, "Dynamic stages").
struct StageState {
  /// Latest end of the stage in progress or of the last one; the run is in a
  /// stage while time < until (0: none yet) [time].
  double until = 0.0;
  /// The stage does not end at rest before this time: the end of the static
  /// step that found the mechanism (that step's motion is the stage's to take) [time].
  double not_before = 0.0;
  bool open = false;              ///< a stage has started and its event is not yet recorded
  StageEvent event;               ///< the stage's figures so far
  /// Kinetic energy of the last step's motion, 1/2 sum (D/dt)^T M (D/dt) (the stage's rest
  /// test, docs/reference/engine.md, "Dynamic stages") [force x length].
  double motion_kinetic = 0.0;
  std::vector<std::vector<Vec2>> start_vertices;  ///< block vertices at its start [length]
};

/// Everything that evolves during a run: copy it to checkpoint, hand it back
/// to Engine::restore to resume (the ContactModel keeps its own state).
struct EngineState {
  int step = 0;              ///< steps accepted so far
  double time = 0.0;         ///< [time]
  double next_dt = 0.0;      ///< size of the next trial step [time]
  std::vector<BlockState> blocks;
  std::vector<std::vector<MeasurementSample>> measurements;  ///< per measurement point
  EnergyBalance energy;      ///< energy balance since t = 0 (energy.hpp)
  StageState stage;          ///< the dynamic stage in progress, or the last one
  std::vector<StageEvent> events;  ///< dynamic stages that have ended, in order
  /// Reach of the next step's contact search (StepContext::max_displacement;
  /// docs/reference/engine.md, "Contact search reach") [length].
  double search_displacement = 0.0;
  SolverState solver;        ///< the linear solver's memory between solves
  std::vector<BoltState> bolts;  ///< per Model::bolts (bolt.hpp); empty without bolts
};

/// Changes to the model between two steps: the actions of a scene's stage
/// (docs/reference/stages.md; model_edits.cpp). Engine::edit applies them in the order
/// of the fields. Points are in current coordinates (where they are at the
/// edit); block indices are those of Model::blocks, which never change.
struct ModelEdit {
  /// Fixed points to remove, indices into the current model().fixed_points.
  std::vector<int> remove_fixed_points;
  /// Point loads to remove, indices into the current model().point_loads.
  std::vector<int> remove_point_loads;
  /// Blocks to remove (excavation): each becomes inactive - no contacts (the
  /// contact model drops them and never pairs them again), no gravity, no
  /// velocity, no stress, its six unknowns held at zero, its geometry frozen
  /// where it was. The fixed points and point loads on it are removed with it.
  std::vector<int> remove_blocks;
  /// Fixed points to add: `point` is the held position now [length]; the
  /// material point of `block` standing there is held from now on. A moving
  /// block stops in the directions they hold (model_edits.cpp, "Velocities").
  std::vector<FixedPoint> add_fixed_points;
  /// Point loads to add: `point` is the load point now [length] (the material
  /// point standing there carries it); history times are run times [time].
  std::vector<PointLoad> add_point_loads;
  /// Bolts to install (bolt.hpp; docs/reference/stages.md): point_a on block_a and
  /// point_b on block_b (or fixed in space, block_b = -1) where they stand now
  /// [length]. Each is installed at the length between its ends now
  /// (Bolt::installed_length; a given one is replaced), carries its pretension from
  /// now on, and is appended to Model::bolts (indices after the bolts there).
  std::vector<Bolt> add_bolts;
  /// Joint sets to change (index, new values; same name): handed to the
  /// contact model (ContactModel::set_joint_set).
  std::vector<std::pair<int, contact::JointSet>> joint_sets;
  /// New Settings::dynamic_ratio (the share of velocity carried): 0 makes the
  /// analysis static, > 0 dynamic [-]; unset: unchanged.
  std::optional<double> dynamic_ratio;
  /// New water in the joints from now on (water.hpp): its surfaces' times are
  /// run times, and it must span the x-range of the blocks that stay, where they
  /// stand now; a Water without history drains the model; unset: unchanged.
  std::optional<Water> water;
  /// Replay (a resumed run, docs/reference/outputs.md "Interrupting and resuming"): the
  /// points of add_fixed_points (their material_point, which must be set), of
  /// add_point_loads and of add_bolts (with their installed_length) are material
  /// points already, as EditReport::replay gives them, and are not checked
  /// against where the blocks stand now.
  bool material_points = false;
  /// Velocities to give blocks (index, (u0, v0, r0, ex, ey, gxy) [length/time,
  /// 1/time]) after the other changes, in a dynamic analysis only; the velocity
  /// must leave the block's fixed points at rest in the directions they hold.
  /// The kinetic energy it adds is booked (EnergyFlows::dissipation_edits).
  std::vector<std::pair<int, Vec6>> set_velocities;
  /// Opens a settling stage from now (SettleStage::until long, with
  /// settle.dt, settle.max_displacement_ratio, settle.dynamic and settle.rest_tolerance; docs/reference/engine.md,
  /// "Dynamic stages"); a dynamic stage in progress ends here.
  bool settle = false;
};

/// What Engine::edit removed with the blocks (indices as they were before the edit).
struct EditReport {
  std::vector<int> fixed_points_removed;  ///< fixed points on removed blocks
  std::vector<int> point_loads_removed;   ///< point loads on removed blocks
  int contacts_dropped = 0;               ///< contacts of removed blocks [-]
  /// Kinetic energy the edit took (EnergyFlows::dissipation_edits) [force x length].
  double kinetic_energy_taken = 0.0;
  /// Bolts with an end on a removed block (indices into Model::bolts): removed with it,
  /// they carry nothing from now on (state `ruptured` at the edit's time; bolt.hpp).
  std::vector<int> bolts_removed;
  /// The edit with its added points resolved to material points
  /// (ModelEdit::material_points): applied to an engine built anew from the
  /// same model, then Engine::restore of a state saved after the edit, it
  /// resumes the run bit for bit.
  ModelEdit replay;
};

/// Asked within a step whether the run is to stop (Engine::set_stop_request).
using StopRequest = std::function<bool()>;

/// Thrown out of Engine::step, run and run_until when the stop request answered yes within a
/// step: the step was abandoned as a cut step is (the contacts and bolts back at its start), and
/// the engine is as it was after the last accepted step: a state saved now (save()) is that of
/// the last accepted step, from which the run goes on as if it had not been stopped.
class StepInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Called after every accepted step.
using StepObserver = std::function<void(const class Engine&, const StepReport&)>;

class Engine {
 public:
  /// Validates the model (throws ModelError naming the key) and builds the
  /// initial state; runs without contacts (NullContactModel).
  explicit Engine(Model model);
  /// As above, driving `contacts` (not owned; must outlive the engine).
  Engine(Model model, ContactModel& contacts);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  /// Advances one accepted step (cutting dt as needed). Throws
  /// std::runtime_error when the step still fails after Settings::max_cuts cuts.
  StepReport step();
  /// Advances `steps` accepted steps.
  void run(int steps);
  /// Advances until time() >= end_time (the last step is shortened to land on it;
  /// under an adaptive control the step after it takes up the size the control had
  /// reached: `rheodda run` ends a step on each output time this way).
  void run_until(double end_time);
  /// Advances until time() >= end_time, shortening a step only so as not to pass
  /// `horizon` (>= end_time): the steps taken do not depend on end_time; the run
  /// then passes end_time by up to one step.
  void run_until(double end_time, double horizon);
  /// Called after every accepted step, in the order added.
  void add_observer(StepObserver observer);
  /// A stop request the cycles of a step look at every kStopPollCycles cycles (the explicit
  /// step's and the static steps by cycles: thousands of cycles per step; docs/reference/
  /// explicit-step.md, "Stopping within a step"): when it answers true, the step is abandoned
  /// and StepInterrupted thrown. Looking changes no result, whether or not it answers true
  /// later. Empty (the default): the cycles never look. Steps not taken in cycles are not
  /// interrupted: the caller stops between steps (an observer).
  void set_stop_request(StopRequest asked);
  /// The cycles between two looks at the stop request [-].
  static constexpr int kStopPollCycles = 256;

  const Model& model() const;
  int block_count() const;
  int step_count() const;
  double time() const;        ///< [time]
  double half_model_size() const;  ///< w0: half the larger side of the initial bounding box [length]
  double allowed_displacement() const;  ///< max_displacement_ratio * w0 [length]

  const BlockState& block(int b) const;
  std::span<const Vec2> vertices(int b) const;  ///< [length]
  Vec2 centroid(int b) const;                   ///< [length]
  double area(int b) const;                     ///< current area [length^2]
  Vec3 stress(int b) const;                     ///< [stress]
  Vec6 velocity(int b) const;                   ///< [length/time, 1/time]
  /// Current position of the material point whose initial position was p0 [length].
  Vec2 point_position(int b, const Vec2& p0) const;
  /// Total displacement of the material point whose initial position was p0 [length].
  Vec2 point_displacement(int b, const Vec2& p0) const;

  /// Views of the step-start geometry, as handed to the contact model.
  std::span<const contact::BlockView> views() const;
  /// Displacements D (6 per block) of the last accepted step.
  const Eigen::VectorXd& last_displacements() const;
  /// Reports of the accepted steps since the engine was built or restored.
  const std::vector<StepReport>& reports() const;
  /// Samples per measurement point (first sample = initial state, step -1).
  const std::vector<std::vector<MeasurementSample>>& measurements() const;
  const SolverStats& solver_stats() const;
  /// Energy balance: stored energies, the last step's flows and the sums since
  /// t = 0 (docs/reference/engine.md, "Energy balance").
  const EnergyBalance& energy() const;
  /// Dynamic stages that have ended (docs/reference/engine.md, "Dynamic stages").
  const std::vector<StageEvent>& events() const;
  /// The run is in a dynamic stage (the next step is dynamic).
  bool in_stage() const;
  /// States of the bolts after the last accepted step, per Model::bolts (docs/reference/bolts.md).
  const std::vector<BoltState>& bolts() const;

  /// The explicit step's cycle (docs/reference/explicit-step.md) on the current state, before
  /// its rounding to whole cycles of a step: explicit_safety x the stable cycle, with the
  /// contacts found as a step of Settings::dt would find them and the true masses (no density
  /// scaling), and the block that sets it
  /// (cycle infinite and block -1 when nothing stiff holds any block).
  struct StableCycle {
    double cycle = std::numeric_limits<double>::infinity();  ///< [time]
    int block = -1;
  };
  StableCycle stable_cycle();
  /// The explicit step's cycle of each block on the current state, found as stable_cycle()
  /// finds the scene's: explicit_safety x the block's stable cycle, its true mass, its contacts
  /// as a step of Settings::dt would find them, the contacts' dashpots of the whole scene.
  /// Infinite for a block held or removed, or on which nothing stiff acts. Its smallest value is
  /// stable_cycle().cycle, at stable_cycle().block (docs/reference/explicit-step.md, "The
  /// cycle") [time].
  std::vector<double> block_cycles();

  /// Applies `edit` between two steps (model_edits.cpp; docs/reference/stages.md).
  /// Validates it first and throws ModelError naming the field ("remove_blocks[0]",
  /// ...) with the model unchanged when it is invalid: an index out of range,
  /// a block already removed, every block removed, no fixed point left where
  /// the model had some, a settling stage without SettleStage::until.
  EditReport edit(const ModelEdit& edit);
  /// Block b was removed by an edit.
  bool removed(int b) const;
  /// Blocks removed so far (1 per removed block; empty while none was).
  std::span<const char> removed_blocks() const;

  /// Copy of everything that evolves.
  EngineState save() const;
  /// Resumes from a saved state of an engine built from the same model: the
  /// steps after it are those the saved engine would have taken, bit for bit
  /// (with the contact model restored to its own state of that moment).
  /// reports() starts again from empty.
  void restore(const EngineState& state);

  /// The engine's internals (core/src/engine_impl.hpp), complete only inside core/. Named here
  /// so that the integrators' rows (integrator.hpp) can point at the member that takes a step.
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace rheodda::core
