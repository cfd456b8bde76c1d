// The interface through which the DDA host runs contacts. The host owns it;
// core/ adapts the contact layer's ContactSystem to it, and a scene without
// contacts uses NullContactModel (no contact work at all).
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "rheodda/contact/check_result.hpp"
#include "rheodda/contact/contact_energy.hpp"
#include "rheodda/contact/joint_set.hpp"
#include "rheodda/contact/kinematics.hpp"
#include "rheodda/contact/step_context.hpp"

namespace rheodda::core {

using Mat6 = contact::Mat6;

/// The contacts' terms of the energy balance (stored energies after the last
/// accepted step and its flows; docs/reference/engine.md, "Energy balance").
using ContactEnergy = contact::ContactEnergy;

/// Facts of the step being solved: what the contacts need of it (the step size,
/// the search distance, dynamic or static, the Newmark inertia 1/(beta dt^2) of
/// Settings::time_integration, whether the creep error is wanted; stated once, in
/// contact/step_context.hpp) and which step it is. ContactAdapter hands it to
/// contact::ContactSystem::begin_step as it is.
struct StepContext : contact::StepContext {
  int step = 0;       ///< index of the step being solved (0-based)
  double time = 0.0;  ///< time at the start of the step [time]
};

/// What the open-close iteration changed, by kind, and the result of one check
/// of trial displacements: the contact layer's types (contact/check_result.hpp),
/// which ContactSystem produces and a ContactModel returns as they are.
using ContactChanges = contact::ContactChanges;
using ContactCheck = contact::CheckResult;

/// An opaque copy of a contact model's state after an accepted step, taken by
/// ContactModel::snapshot for step doubling (Settings::step_tolerance).
class ContactSnapshot {
 public:
  virtual ~ContactSnapshot() = default;
};

/// How the host drives contacts through a step:
///   begin_step -> { assemble -> solve -> check }* -> end_step   (converged)
///   begin_step -> ... -> abandon_step                            (step cut, redone)
class ContactModel {
 public:
  virtual ~ContactModel() = default;
  /// Detect contacts on the step-start geometry; carry states over from the last step.
  virtual void begin_step(std::span<const contact::BlockView> blocks, const StepContext& ctx) = 0;
  /// Add springs and friction loads for the current trial states.
  virtual void assemble(std::span<const contact::BlockView> blocks, contact::SystemSink& sink) = 0;
  /// Check the trial displacements D (6 per block) and update the trial states.
  virtual ContactCheck check(std::span<const contact::BlockView> blocks,
                             const Eigen::VectorXd& D) = 0;
  /// Adds the contacts' forces on the blocks at the trial displacements D, in
  /// their current trial states, into f (6 per block) and returns true; false
  /// (f untouched) for a model that cannot (contact solves that need the
  /// residual of the step's equations then fall back; contact_solve.hpp).
  virtual bool contact_forces(const Eigen::VectorXd& /*D*/, Eigen::VectorXd& /*f*/) const { return false; }
  // Explicit cycles (the explicit step, docs/reference/explicit-step.md): between begin_step
  // and end_step, begin_cycles -> { cycle_forces }* -> end_cycles instead of the
  // assemble/check iteration. A model that cannot returns false from begin_cycles.

  /// Starts the cycles of the step begun (on the step-start `blocks`, `threads` OpenMP threads,
  /// 0: OpenMP's default); false when the model has no explicit cycles.
  virtual bool begin_cycles(std::span<const contact::BlockView> /*blocks*/, int /*threads*/) { return false; }
  /// Adds to K (6x6 per block) a bound of the contacts' stiffness on each block (for the
  /// stable cycle).
  virtual void cycle_stiffness(std::vector<Mat6>& /*K*/) const {}
  /// The cycles' dashpots: contacts without their own take c = tau k beside each spring
  /// [tau: time]; adds a bound of all the dashpots on each block to C.
  virtual void cycle_damping(double /*tau*/, std::vector<Mat6>& /*C*/) {}
  /// The contacts' resisting forces f (6 per block, set) at the displacements D since the
  /// step start and rates V, each contact's state decided at D; kick: the length of the kick
  /// these forces make [time] (the cycle, half of it at the step's first and last), for the
  /// dashpots' work: each force times kick (its rate + the rate after the kick)/2, the
  /// scheme's discrete work.
  virtual void cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, Eigen::VectorXd& f) {
    (void)V, (void)kick;
    f = Eigen::VectorXd::Zero(D.size());
  }
  /// Between cycles at a state of rest D (the static steps by cycles): each contact whose
  /// creep law is not linear takes the linearization of the stress it carries at D, as an
  /// iterate of the implicit step does; returns how many changed (0: the cycles' state is
  /// consistent with its laws).
  virtual int cycle_relinearize(const Eigen::VectorXd& /*D*/) { return 0; }
  /// After the last cycle, at D with the rates V its kick led to [length/time]: the trial
  /// states take the cycles' states, ready for end_step.
  virtual ContactCheck end_cycles(std::span<const contact::BlockView> /*blocks*/, const Eigen::VectorXd& /*D*/,
                                  const Eigen::VectorXd& /*V*/) {
    return {};
  }
  /// Accept the step: commit states, locking points, forces and rheology history.
  virtual void end_step(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) = 0;
  /// Reject the step (it will be redone with a smaller dt): restore the step-start states.
  virtual void abandon_step() = 0;
  /// Estimate of the creep error of the last accepted step [length] (asked only when
  /// StepContext::creep_error_wanted was set); 0 without creep.
  virtual double creep_error_estimate() const { return 0.0; }
  /// Undo the last end_step (asked only when StepContext::creep_error_wanted was
  /// set, before any other call): back to the step-start states, as after
  /// abandon_step; the step will be redone with a smaller dt. Returns false when
  /// the model cannot, and the step then stands.
  virtual bool retract_step() { return false; }
  /// Contacts on joint sets with a creep law whose state changed in the last
  /// accepted step (locked <-> sliding or open, appeared closed or vanished
  /// locked) (asked only when StepContext::creep_error_wanted was set) [-].
  virtual int creep_state_changes() const { return 0; }
  /// Time left [time] before a creep law of a contact fails at its present stress
  /// (damage laws; docs/reference/rheology-in-dda.md, "Failure"); infinity when none can.
  /// Adaptive creep stepping ends a step there, so it does not step over a failure.
  virtual double time_to_failure() const { return std::numeric_limits<double>::infinity(); }
  /// Step doubling (Settings::step_tolerance; asked between steps only): a copy of
  /// the state after the last accepted step, or nullptr when the model cannot copy it.
  virtual std::unique_ptr<ContactSnapshot> snapshot() const { return nullptr; }
  /// Back to the state of a snapshot this model took.
  virtual void restore(const ContactSnapshot&) {}
  /// Richardson extrapolation: this model holds the state after two steps of
  /// dt/2 and `coarse` the state after one step of dt from the same start;
  /// replace every continuous quantity x by 2 x - x_coarse. Returns false, and
  /// changes nothing, when the two differ in their discrete parts (which
  /// contacts exist, their states).
  virtual bool extrapolate(const ContactSnapshot& /*coarse*/) { return false; }
  /// Energy balance (docs/reference/engine.md, "Energy balance"; asked after end_step and
  /// after extrapolate): the energy the contact springs store after the last
  /// accepted step and the work the blocks did on them in it [force x length];
  /// all zero for a model that does not account for it.
  virtual ContactEnergy energy() const { return {}; }
  /// Model edits between two steps (Engine::edit; docs/reference/stages.md). Blocks whose
  /// flag is set are removed: their contacts are dropped and never detected
  /// again; returns how many were dropped. The default refuses (throws
  /// std::logic_error): a model that cannot must not ignore it.
  virtual int remove_blocks(std::span<const char> removed);
  /// Joint set `index` takes new values (contact::ContactSystem::set_joint_set).
  /// The default refuses (throws std::logic_error).
  virtual void set_joint_set(int index, const contact::JointSet& joint_set);
};

/// No contacts: every call does nothing.
class NullContactModel final : public ContactModel {
 public:
  void begin_step(std::span<const contact::BlockView>, const StepContext&) override {}
  void assemble(std::span<const contact::BlockView>, contact::SystemSink&) override {}
  ContactCheck check(std::span<const contact::BlockView>, const Eigen::VectorXd&) override {
    return {};
  }
  void end_step(std::span<const contact::BlockView>, const Eigen::VectorXd&) override {}
  bool contact_forces(const Eigen::VectorXd&, Eigen::VectorXd&) const override { return true; }
  bool begin_cycles(std::span<const contact::BlockView>, int) override { return true; }  // no contacts: no force at any cycle
  void abandon_step() override {}
  std::unique_ptr<ContactSnapshot> snapshot() const override {
    return std::make_unique<ContactSnapshot>();
  }
  bool extrapolate(const ContactSnapshot&) override { return true; }
  int remove_blocks(std::span<const char>) override { return 0; }  // no contacts to drop
};

}  // namespace rheodda::core
