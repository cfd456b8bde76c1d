// The engine's internals, shared by the files that implement it (one concern
// each): engine.cpp (state, geometry, accepting a step, the public API),
// model_checks.cpp (validation of the model), block_assembly.cpp (the block
// sub-matrices), step_trial.cpp (one attempt at a step: contacts and the
// contact solve), integrator.cpp (which member takes a dynamic step's attempt),
// step_control.cpp (step size, cuts, adaptive creep stepping,
// settling and collapse stages), step_doubling.cpp (step doubling with
// Richardson extrapolation).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bolts.hpp"
#include "rheodda/core/block_system.hpp"
#include "rheodda/core/contact_solve.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/integrator.hpp"
#include "rheodda/core/polygon.hpp"
#include "rheodda/core/solver.hpp"

namespace rheodda::core {

using Clock = std::chrono::steady_clock;

/// The largest squared displacement of block b's vertices under its unknowns D [length^2]:
/// |T(v) D|^2 over its vertices v (contact/kinematics.hpp, displacement_matrix).
inline double largest_vertex_displacement_sq(const BlockState& b, const Vec6& D) {
  double worst = 0.0;
  for (const Vec2& v : b.vertices) worst = std::max(worst, (contact::displacement_matrix(b.centroid, v) * D).squaredNorm());
  return worst;
}

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Adaptive creep stepping rejects a step whose creep error estimate exceeds
/// this multiple of Settings::creep_tolerance [-] (docs/reference/step-controls.md).
constexpr double kRejectFactor = 2.0;
/// Adaptive creep stepping steps onto a damage law's failure when it is within
/// this many steps (docs/reference/rheology-in-dda.md, "Failure") [-].
constexpr double kFailureReach = 8.0;
/// The contact search of a large model (max_displacement_ratio w0 above this fraction of the median
/// block size) reaches only as far as the motion needs, not below this fraction
/// (docs/reference/engine.md, "Contact search reach") [-].
constexpr double kSearchFloor = 0.1;

/// Is p inside the polygon v or within tol of its boundary (model_checks.cpp)?
bool inside_or_near(std::span<const Vec2> v, const Vec2& p, double tol);

/// One attempt at a step (integrator.hpp): D (Engine::Impl::D) and contact states that agree,
/// or a failure the step control cuts dt for.
struct StepTrial {
  bool converged = false;
  int iterations = 0;
  double max_disp = 0.0;  // largest vertex displacement of the converged D [length]
  ContactCheck check;
  /// Set when a solve found the matrix not positive definite (the attempt is
  /// cut like one that did not converge: a shorter step stiffens the inertia
  /// terms 2M/dt^2; after max_cuts the error is thrown with this diagnosis).
  std::string singular;
  int singular_block = -1, singular_unknown = -1;
  /// Why a static step by cycles did not converge (explicit_static.cpp); empty for the
  /// contact solves, whose reason is the open-close iteration.
  std::string unsettled;
  /// A static step by cycles that ended short of rest at the step limit (explicit_static.cpp (3)).
  bool short_of_rest = false;
};

struct Engine::Impl {
  Model model;
  NullContactModel null_contacts;
  ContactModel* contacts = nullptr;

  EngineState st;
  std::vector<PolygonIntegrals> moments;  // central integrals of the step-start geometry
  std::vector<char> held;                 // block held by two or more fixed points (count_held)
  std::vector<char> removed;              // block removed by an edit (model_edits.cpp); empty: none
  bool is_removed(std::size_t k) const { return !removed.empty() && removed[k]; }
  /// Per block, 1 where the cycles leave it where it stands: held at two or more fixed points
  /// (or at one and in rotation; count_held) or removed.
  std::vector<char> frozen_blocks() const {
    std::vector<char> out(st.blocks.size(), 0);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = held[k] || is_removed(k);
    return out;
  }
  std::vector<contact::BlockView> views;
  std::vector<Eigen::Matrix3d> elastic;   // per material
  double w0 = 0.0;                        // half model size [length]
  /// The displacement per step the contact search covers (StepContext::
  /// max_displacement; contacts are looked for within search_factor x it):
  /// max_displacement_ratio w0 where that is below search_floor, else adapted to the motion
  /// (search_reach(), docs/reference/engine.md, "Contact search reach") [length].
  double search_disp = 0.0;
  /// The context of the step starting now, of size dt [time] (contact_model.hpp): its index,
  /// time and search distance; dynamic, inertia and creep_error_wanted at their defaults.
  StepContext step_context(double dt) const {
    StepContext ctx;
    ctx.step = st.step;
    ctx.time = st.time;
    ctx.dt = dt;
    ctx.max_displacement = search_disp;
    return ctx;
  }
  double search_floor = 0.0;  // kSearchFloor x the median block size [length]
  double search_reach(const Eigen::VectorXd& d) const;
  double fixed_k = 0.0;                   // fixed point penalty [force/length]
  /// Share of the velocity the step starting now carries: the analysis's
  /// dynamic_ratio, or 1 in a dynamic settling stage (SettleStage::dynamic).
  double ratio_now() const {
    return settling() && model.settings.settle.dynamic ? 1.0 : model.settings.dynamic_ratio;
  }
  /// The step starting now carries velocity (a dynamic step).
  bool dynamic_now() const { return ratio_now() > 0.0; }

  /// Newmark parameters of the current step. The trapezoidal rule needs the
  /// acceleration at the step start; the first step has none, so it uses Shi's
  /// scheme (exact for a constant acceleration), which yields it.
  struct Newmark {
    double beta, gamma;
  };
  Newmark newmark() const {
    if (model.settings.time_integration == TimeIntegration::trapezoidal && st.step > 0)
      return {0.25, 0.5};
    return {0.5, 1.0};
  }
  /// Newmark predictor Dp = v dt + (1/2 - beta) dt^2 a from the carried v, a.
  Vec6 predictor(const BlockState& b, double dt, const Newmark& nm) const {
    return ratio_now() * (dt * b.velocity + (0.5 - nm.beta) * dt * dt * b.acceleration);
  }

  BlockSystem system;
  std::unique_ptr<LinearSolver> solver;
  std::unique_ptr<ContactSolve> contact_solve;  // Settings::contact_solver (contact_solve.hpp)
  Eigen::VectorXd D;
  std::vector<Mat6> base_diag;  // block terms of the step being solved (scratch)
  Eigen::VectorXd base_rhs;
  std::vector<StepReport> reports;
  std::vector<StepObserver> observers;
  StopRequest stop_request;  ///< Engine::set_stop_request; empty: never asked
  /// Within the cycles of a step, at cycle `cycle`: every Engine::kStopPollCycles cycles, asks the
  /// stop request and throws StepInterrupted when it answers yes (the caller abandons the step).
  void poll_stop(long cycle) const {
    if (stop_request && cycle % Engine::kStopPollCycles == Engine::kStopPollCycles - 1 && stop_request())
      throw StepInterrupted("step " + std::to_string(st.step) + " at time " + std::to_string(st.time) +
                            ": stopped within its cycles on request; the step is not taken");
  }
  EnergyAccount energy;  // the balance itself is st.energy (energy.hpp)
  BoltSet bolt_set;      // the bolts' step terms (bolts.hpp); idle without Model::bolts
  EnergyInputs energy_inputs() const {
    return {model, st.blocks, moments, elastic, fixed_k, ratio_now()};
  }

  void validate();
  /// Checks an edit whole (model_edit_checks.cpp): throws ModelError; returns, per block,
  /// whether it is removed once the edit is applied.
  std::vector<char> check_edit(const ModelEdit& e) const;
  void initialise();
  void refresh_geometry();
  void count_held();  // held[k]: two fixed points hold block k in x and y, or one and its rotation
  /// The block sub-matrices of a step of dt ending at t_end (block_assembly.cpp); without
  /// `inertia`, those of the explicit step's cycles: no inertia and no block damping terms.
  void assemble_blocks(double dt, double t_end, std::vector<Mat6>& diag, Eigen::VectorXd& rhs,
                       bool inertia = true) const;
  double max_vertex_displacement(const Eigen::VectorXd& d) const;
  /// End of the stage the run is in or was last in: the settling stage or a
  /// collapse stage (EngineState::stage; dynamic_stages.cpp) [time].
  double stage_end() const { return st.stage.until; }
  /// In the settling stage (SettleStage::until; docs/reference/engine.md, "Settling
  /// stage") or in a collapse stage.
  bool settling() const {
    const double end = stage_end();
    return end > 0.0 && st.time < end - 1e-12 * std::max(1.0, std::abs(end));
  }
  /// Opens a dynamic stage of `kind` from now, at most `length` long and, when
  /// it may end at rest, at least `shortest` (dynamic_stages.cpp).
  void start_stage(StageKind kind, double length, double shortest = 0.0);
  /// After an accepted step: the stage's figures, and its end at rest
  /// (SettleStage::rest_tolerance) or at its longest, recorded as an event.
  void update_stage(const StepReport& rep);
  /// A static step of dt whose trial D moves as a mechanism (collapse stages).
  bool collapses(double dt) const {
    return EnergyAccount::static_trial_share(energy_inputs(), D, dt, newmark().beta, st.time + dt) >
           kMechanismStepShare;
  }
  /// The displacement limit (max_displacement_ratio) in force now: settle.max_displacement_ratio in the settling stage.
  double max_displacement_ratio_now() const { return settling() ? model.settings.settle.max_displacement_ratio : model.settings.max_displacement_ratio; }
  void accept(const Eigen::VectorXd& d, double dt, int step_index, double t_end);
  void record_measurements(int step_index);
  /// One accepted step (step_control.cpp). On StepInterrupted from within it, what the step's
  /// attempts changed of the engine (the contact search's reach, a collapse stage it opened;
  /// the contacts are abandoned where the attempt fails, the blocks move only on acceptance) is
  /// set back before the exception goes on.
  StepReport step(double dt_cap);
  /// What step() sets back on StepInterrupted: the engine's members its attempts change.
  struct StepStart {
    double search_disp = 0.0;
    std::optional<StageState> stage;  ///< kept before a collapse stage is opened
  };
  StepReport step_attempts(double dt_cap, StepStart& start);
  /// After a static trial of dt that moved as a mechanism (docs/reference/engine.md,
  /// "Collapse stages"): cuts dt towards collapse_dt and returns false, or, at
  /// collapse_dt, opens a collapse stage from the step's start, sets dt to the
  /// stage's first step and returns true.
  bool open_collapse_stage(double& dt, StepReport& rep);

  using Trial = StepTrial;
  /// One attempt at a step of dt from the current state: begin_step, then the
  /// trial of the step's integrator (trial_now). The contacts are left in their
  /// trial states: the caller ends or abandons the step (step_trial.cpp).
  Trial solve_trial(double dt, bool creep_error_wanted, StepReport& rep);
  /// The member that takes a step's trial after begin_step (integrator.hpp).
  using TrialMember = StepTrial (Impl::*)(double dt, StepReport& rep);
  /// The trial of the step starting now, from its integrator's row (Settings::integrator): its
  /// dynamic trial for a dynamic step; for a static one its static trial where the scene asks
  /// for it (Settings::static_force_ratio), else Shi's implicit step, which every integrator
  /// takes (a static step carries no inertia to integrate; docs/reference/explicit-step.md).
  TrialMember trial_now() const {
    const IntegratorEntry& row = integrator_entry(model.settings.integrator);
    if (dynamic_now()) return row.dynamic_trial;
    if (row.static_trial != nullptr && model.settings.static_force_ratio > 0.0) return row.static_trial;
    return &Impl::implicit_trial;
  }
  /// Shi's implicit step's trial of a step of dt: the block terms assembled, then the contact
  /// solve (Settings::contact_solver) finds D and the contact states (step_trial.cpp).
  Trial implicit_trial(double dt, StepReport& rep);
  /// The step starting now is taken in explicit cycles (cycle_trial), which leave its end
  /// velocities and mass scales for accept (cycle_velocity, cycle_scale).
  bool explicit_now() const { return trial_now() == &Impl::cycle_trial; }
  /// The explicit step's attempt at a step of dt, after begin_step (explicit_step.cpp): D by
  /// central-difference cycles, the end velocities in cycle_velocity, the contacts left in
  /// their cycles' states.
  Trial cycle_trial(double dt, StepReport& rep);
  /// A static step of dt by cycles from rest to equilibrium, after begin_step
  /// (explicit_static.cpp): D where the unbalanced-force ratio fell to static_force_ratio,
  /// the contacts left in their cycles' states; not converged (and the contacts to be
  /// abandoned) when it did not within static_max_cycles.
  Trial relax_trial(double dt, StepReport& rep);
  /// What the explicit step's cycles of a step of dt need of the blocks, after begin_step and
  /// begin_cycles (explicit_step.cpp): stiffness, inverse masses, strain damping, loads, the
  /// stable cycle and the block that sets it; the contacts' dashpots set for the step.
  struct CycleBlocks {
    std::vector<Mat6> K, M_inv;         ///< per block [stress ...], [1/mass ...]
    std::vector<Mat6> L;                ///< lower Cholesky factor of each block's mass [mass^(1/2) ...]
    std::vector<Eigen::Matrix3d> C;     ///< strain damping per block [stress x time]
    std::vector<char> frozen;           ///< held at two or more fixed points, or removed
    Eigen::VectorXd F0, dF;             ///< loads at the step's start, and their change over it [force]
    bool loads_change = false;
    std::vector<double> scale;          ///< density scale of each block's mass (6) [-]
    double h_stable = std::numeric_limits<double>::infinity();  ///< [time]
    int stable_block = -1;
    double tau = 0.0;                   ///< the dashpots' c = tau k of (5) [time]
  };
  /// unscaled: the stable cycle of the true masses, whatever the stage (Engine::stable_cycle).
  CycleBlocks cycle_blocks(double dt, bool unscaled = false) const;
  /// One pass of cycle_blocks at the masses scaled by out.scale: M_inv, C, the stable cycle of
  /// each block (h) and of the step; the contacts' dashpots set for it.
  void cycle_block_pass(const std::vector<Mat6>& bound, CycleBlocks& out, std::vector<double>& h) const;
  /// The step starting now scales its blocks' masses (Settings::stage_cycles): an explicit
  /// step in a dynamic stage of a static analysis.
  bool density_scaling_now() const {
    return model.settings.stage_cycles > 0 && settling() && model.settings.dynamic_ratio == 0.0;
  }
  /// Local damping of the explicit cycles of the step starting now (Settings::stage_local_damping):
  /// in a dynamic stage of a static analysis, else 0 [-].
  double local_damping_now() const {
    return settling() && model.settings.dynamic_ratio == 0.0 ? model.settings.stage_local_damping : 0.0;
  }
  std::vector<double> cycle_scale;   ///< density scales of the last explicit attempt (6)
  /// The unbalanced-force ratio at the end of the last explicit attempt (explicit_step.cpp (8)) [-].
  double cycle_force_ratio = 0.0;
  /// Kinetic energy of the last accepted step's motion, 1/2 sum (D/dt)^T s M (D/dt) over the
  /// blocks (D the step's displacement, s M the mass it moved with): the rest test of a
  /// dynamic stage (dynamic_stages.cpp) [force x length].
  double step_motion_kinetic = 0.0;
  double cycle_block_damping = 0.0;  ///< work the blocks' damping took in its cycles [force x length]
  /// Engine::stable_cycle (explicit_step.cpp).
  StableCycle stable_cycle();
  /// Engine::block_cycles (explicit_step.cpp).
  std::vector<double> block_cycles();
  std::vector<Vec6> cycle_velocity;  ///< block velocities at the end of the last explicit attempt
  class Problem;  ///< the StepProblem of a trial (step_trial.cpp)
  /// Cuts dt after a failed attempt (dt *= dt_cut), or throws after max_cuts cuts.
  void cut(double& dt, const Trial& trial, StepReport& rep) const;
  /// Attempts a step of dt and accepts it (contacts end_step, blocks move) when
  /// it converges within max_displacement_ratio w0; otherwise abandons it. No creep estimate.
  bool take(double dt, StepReport& rep, Trial& trial);
  /// A step under Settings::step_tolerance: step doubling with local extrapolation.
  StepReport doubling_step(double dt_cap);
  /// First point-load sample time after the current time (inf if none) [time].
  double next_load_break() const;
  /// Next step of an adaptive control from the error estimate err of a step dt [time].
  double next_adaptive_dt(double dt, double tolerance, double err, double load_break) const;
  /// Next step of an adaptive control after a step the caller's end time shortened
  /// from `proposed`, whose own estimate asks for `next` [time] (step_control.cpp).
  double landed_next_dt(double next, double proposed, const StepReport& rep, double load_break) const;
};

}  // namespace rheodda::core
