// The contacts of a DDA model through a time step: detection, transfer of
// contact state from the last step, penalty springs, Mohr-Coulomb friction and
// the open-close iteration (Shi 1988; the seed's Section 3, eqs. 17-29).
//
// Data layout (after Box2D). Persistent ("cold") records, one per contact, live
// in a contiguous array sorted by ContactKey: identity, state, locking point,
// forces, accumulated shear, rheology slot. Per-step ("hot") data - the
// linearized gap and shear of each contact as 6-vectors per block - is computed
// once in begin_step from the step-start geometry and reused by every
// iteration. The committed records of the last accepted step are kept apart
// from the working records of the step being solved, so abandon_step restores
// the step-start states exactly (by discarding the working copy).
//
// Parts, one concern per header; ContactSystem composes them and runs the step's
// protocol over them: the records, committed and working, with their creep
// histories and increments (contact_records.hpp; one record: contact_record.hpp),
// the step's hot arrays (step_arrays.hpp), the energy book (energy_book.hpp), the
// creep error estimate and what a retraction restores (creep_error.hpp), the
// explicit cycles of the step (explicit_cycles.hpp), and the state between two steps
// that a resumed run restores (contact_system_state.hpp).
//
// Rheology (docs/reference/rheology-in-dda.md). A contact on a joint set with a law owns
// a slot in a separate array of laws::RheologyState (with its committed copy
// for rollback); other contacts have none (rheology == -1). Every locked
// contact on such a joint set creeps, edge-edge and point contacts alike. The
// law works per unit joint area: shear stress tau = F / l_t with l_t the
// contact's tributary length (Contact::tributary_length: the contact length of
// an edge-edge contact, point_tributary_length for a point contact; unit
// thickness). Its creep increment over the step, Delta d_c = h + c tau_e
// (laws/contact_rheology.hpp), enters the shear spring through ShearSeam: the
// locking point moves by Delta d_c along the entrance edge (the seed's eqs.
// 22-29), so F_e = k (d - h - (c/l) F_e), i.e. k_eff = k / (1 + k c/l) and the
// history term h goes to the load vector. The law's constants are computed
// once per joint set and step (begin_step); the states are advanced only in
// end_step from the committed ones, so repeated iterations and step cuts
// never count creep twice.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "rheodda/contact/broad_phase.hpp"
#include "rheodda/contact/check_result.hpp"
#include "rheodda/contact/contact_energy.hpp"
#include "rheodda/contact/contact_record.hpp"
#include "rheodda/contact/contact_records.hpp"
#include "rheodda/contact/contact_system_state.hpp"
#include "rheodda/contact/creep_error.hpp"
#include "rheodda/contact/detection.hpp"
#include "rheodda/contact/energy_book.hpp"
#include "rheodda/contact/explicit_cycles.hpp"
#include "rheodda/contact/joint_set.hpp"
#include "rheodda/contact/kinematics.hpp"
#include "rheodda/contact/step_arrays.hpp"
#include "rheodda/contact/step_context.hpp"
#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::contact {

/// Counters of the last begin_step (for benchmarks and logs).
struct DetectionStats {
  int candidate_pairs = 0;  ///< block pairs from the broad phase
  int contacts = 0;         ///< contacts after the narrow phase
  int transferred = 0;      ///< contacts that kept the identity of a last-step contact
  double search_distance = 0.0;  ///< d0 [length]
  /// Spring energy contacts start the step with beyond what their records
  /// stored at the end of the last step (the energy balance's
  /// work_contact_restart, docs/reference/engine.md), by cause: how many contacts, and
  /// the energy [force x length] (docs/notes/rock-mass-steps.md).
  struct Restart {
    int contacts = 0;
    double energy = 0.0;
    double largest = 0.0;             ///< the largest of one contact [force x length]
    std::uint64_t largest_id = 0;     ///< that contact's id (Contact::id)
  };
  Restart restart_new;   ///< new contacts that start closed, already overlapping
  Restart restart_edge;  ///< contacts moved to an adjacent edge of the same block
  Restart restart_kind;  ///< the same vertex and edge, another kind (point <-> edge-edge)
  Restart restart_same;  ///< the same vertex, edge and kind: the geometry moved
};

class ContactSystem {
 public:
  /// Throws std::invalid_argument when the penalty is not positive or a joint set
  /// has a negative friction angle, cohesion, tensile strength or stiffness.
  ContactSystem(std::vector<JointSet> joint_sets, ContactSettings settings);

  /// Detects contacts on the step-start geometry (search distance
  /// search_factor * context.max_displacement [length]) and carries states over;
  /// the creep laws integrate over context.dt (step_context.hpp).
  void begin_step(std::span<const BlockView> blocks, const StepContext& context);
  /// Springs and friction loads of the trial states (the seed's eqs. 28-29).
  void assemble(std::span<const BlockView> blocks, SystemSink& sink) const;
  /// Updates the trial states from the trial displacements D (6 per block).
  CheckResult check(std::span<const BlockView> blocks, const Eigen::VectorXd& D);
  /// Adds the forces the contacts exert on the blocks at the trial
  /// displacements D, in their current trial states, into f (6 per block;
  /// contact_springs.cpp): the normal spring and dashpot of a closed contact,
  /// the shear spring and dashpot of a locked one, and the friction of a
  /// sliding one from its normal force at D (not the last iterate's, as
  /// assemble takes it). A D that solves the assembled system with states that
  /// check finds consistent leaves F0 - K0 D - f near zero: the residual of
  /// the step's equations (docs/reference/contacts.md, "Contact solves").
  void contact_forces(const Eigen::VectorXd& D, Eigen::VectorXd& f) const;
  // Explicit cycles within a step (core's explicit step, docs/reference/explicit-step.md;
  // contact_cycles.cpp): between begin_step and end_step, instead of assemble and check,
  //   begin_cycles -> { cycle_forces }* -> end_cycles -> end_step.
  // Each cycle decides every contact's state on its own from the state at the cycle's
  // start (no iteration): a closed contact's normal spring, and the shear spring dragged
  // along by the slip whenever its force would exceed the Mohr-Coulomb strength (the
  // incremental elastic-plastic joint of explicit block codes, Cundall & Strack 1979).

  /// Starts the cycles of the step begun by begin_step: each contact's cycle state from
  /// its trial record, the list of contacts by block (`blocks`, the step-start views) the forces are
  /// gathered through, and `threads` OpenMP threads for the cycles (0: OpenMP's default).
  void begin_cycles(std::span<const BlockView> blocks, int threads);
  /// Adds to K (one 6x6 matrix per block) a bound of the contacts' stiffness on each block,
  /// 2 (p_n n n^T + k_s t t^T) per contact and side (a spring between two blocks stores
  /// k (n_i.D_i + n_j.D_j)^2 / 2 <= k ((n_i.D_i)^2 + (n_j.D_j)^2); 1 x where the other block
  /// does not move), open contacts included (they may close within the step); for the
  /// stable cycle.
  void cycle_stiffness(std::vector<Mat6>& K) const;
  /// The cycles' dashpots: a contact whose joint set has a restitution keeps its own
  /// (c = 2 zeta sqrt(k m), JointSet::restitution); the others take c = tau k beside each
  /// spring (stiffness-proportional, tau [time]; 0: none). Adds their bound to C as
  /// cycle_stiffness adds the springs'.
  void cycle_damping(double tau, std::vector<Mat6>& C);
  /// The contacts' forces on the blocks at the displacements D since the step start and
  /// the rates V (6 per block each), after each contact's state is decided at D: f (6 per
  /// block, set) is the force the contacts resist with (the residual of a block is its
  /// load minus f). Summed per block over its contacts in a fixed order, so the result is
  /// the same bits whatever the number of threads. The dashpots' work is booked per contact
  /// for the energy balance (energy()): each cycle's dashpot force times kick (its rate +
  /// the rate at the next cycle)/2, kick the length of the kick the forces make [time] (the
  /// cycle, half of it at a step's first and last): the scheme's discrete work.
  void cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, Eigen::VectorXd& f);
  /// At a state of rest D of the cycles: each locked contact whose law is not linear takes
  /// the seam of the stress its spring carries at D (as check does for an iterate of the
  /// implicit step), its cycle spring with it. Returns how many changed.
  int cycle_relinearize(const Eigen::VectorXd& D);
  /// After the last cycle, at the step's D: the trial records take the cycles' states
  /// (the locking point dragged by the slip, the slide direction, intact or not, the
  /// normal force), ready for end_step; the last cycle's dashpot work completed at the rates
  /// V its kick led to [length/time]. Returns the changes from the step-start states.
  CheckResult end_cycles(std::span<const BlockView> blocks, const Eigen::VectorXd& D, const Eigen::VectorXd& V);

  /// Accepts the step: locking points, forces, accumulated shear; may raise the penalty.
  void end_step(std::span<const BlockView> blocks, const Eigen::VectorXd& D);
  /// Rejects the step: the records of the last accepted step stay as they were.
  void abandon_step();
  /// Largest local creep error estimate of the last accepted step over the
  /// contacts locked with a law at both ends of the step [length]
  /// (contact_creep_error.cpp); 0 unless begin_step was asked for it. For a
  /// joint set stepped with the lagged or implicit scheme: |Delta d_c(scheme) -
  /// Delta d_c(exponential-linear)| from the same history and start and end
  /// stresses (exponential-linear is exact for a force linear over the step).
  /// For exponential-linear: |tau''| dt^2/12 c, tau'' from the stresses at the
  /// last three step boundaries and c the implicit step compliance (~ dt/eta).
  /// Zero under a constant force.
  double creep_error_estimate() const { return creep_error_.error(); }
  /// Contacts on joint sets with a law whose state changed in the last
  /// accepted step (locked <-> sliding or open, appeared closed, vanished
  /// locked); 0 unless begin_step was asked for the creep error [-].
  int creep_state_changes() const { return creep_error_.state_changes(); }
  /// Undoes the last end_step (only right after it, and only when its
  /// begin_step was asked for the creep error): back to the step-start
  /// records, as after abandon_step. Returns false when it cannot.
  bool retract_step();
  /// Richardson extrapolation for step doubling (docs/reference/step-controls.md, "Step
  /// doubling"): this system holds the records after two steps of dt/2 and
  /// `coarse` those after one step of dt from the same records. Every
  /// continuous quantity x of the committed records (locking point, forces,
  /// accumulated shear, penetration, rheology histories) becomes 2 x - x_coarse,
  /// and the creep increment that of the extrapolated history. Returns false
  /// and changes nothing unless both hold the same contacts (keys, joint sets)
  /// in the same states (sliding direction, intact) under the same penalty.
  bool extrapolate(const ContactSystem& coarse);

  /// Records of the last accepted step, sorted by key.
  std::span<const Contact> contacts() const { return records_.committed.contacts; }
  /// Working records of the step being solved (trial states).
  std::span<const Contact> trial_contacts() const { return records_.work.contacts; }
  /// Rheology histories of the last accepted step (indexed by Contact::rheology).
  std::span<const laws::RheologyState> rheology_states() const { return records_.committed.rheology; }
  /// Creep seams of the step being solved, parallel to trial_contacts().
  std::span<ShearSeam> shear_seams() { return step_.seams; }

  /// Scheme used by joint set js in the step being solved (or the last one);
  /// nullopt when the joint set has no law or the step has no creep (dt = 0).
  std::optional<laws::Scheme> scheme_used(int js) const;
  /// Creep increment Delta d_c of each contact in the last accepted step
  /// (parallel to contacts(); 0 without a law) [length].
  std::span<const double> creep_increments() const { return records_.committed.creep; }
  /// Per joint set (indexed like joint_sets()): how many contacts carried creep
  /// and for how long, over the accepted steps since construction. All zero
  /// for a joint set without a law.
  std::span<const CreepCounters> creep_counters() const { return records_.counters; }
  /// Smallest time left before a damage law fails (ContactRheology::time_to_failure)
  /// over the locked contacts of the last accepted step, at their stress
  /// tau = F / l_t held constant [time]; infinity when no law can fail.
  double time_to_failure() const;
  /// The contacts' terms of the energy balance: stored energies of the records
  /// of the last accepted step and the flows of that step (contact_energy.cpp;
  /// docs/reference/engine.md, "Energy balance").
  ContactEnergy energy() const;

  const std::vector<JointSet>& joint_sets() const { return joint_sets_; }
  const ContactSettings& settings() const { return settings_; }
  double penalty() const { return penalty_; }  ///< current normal penalty [stress]
  double allowed_penetration() const { return allowed_penetration_; }  ///< [length]
  double last_max_penetration() const { return last_max_penetration_; }  ///< of the last accepted step [length]
  /// Contacts the last accepted step's commit projected onto their Mohr-Coulomb envelope
  /// (held locked outside it by the open-close iteration's anti-chattering rule) [-].
  std::size_t last_projections() const { return projections_; }
  const DetectionStats& stats() const { return stats_; }

  /// What the energy balance needs of one contact's last accepted step (energy_book.hpp).
  using StepWork = contact::StepWork;

  /// The system's state between two steps (contact_system_state.hpp).
  using State = ContactSystemState;

  /// Model edits between two steps (stages, docs/reference/stages.md; contact_edits.cpp).
  /// Removes the blocks whose flags are set (indexed like the views; blocks
  /// already removed stay removed): their contacts are dropped from the
  /// committed records with their creep histories, and begin_step never pairs
  /// them again. The stored energy the next step's balance starts from is that
  /// of the records left. Costs nothing while no block was removed.
  void remove_blocks(std::span<const char> removed);
  /// Replaces joint set `index` by `joint_set` (same name), checked as the
  /// constructor checks it. The records keep their states, forces and creep
  /// histories; the next begin_step takes the new friction, cohesion, strength
  /// and stiffness values and the law's new constants. A law can change its
  /// parameters, not be added, removed or replaced by another law (the
  /// histories' meaning). Throws std::invalid_argument.
  void set_joint_set(int index, JointSet joint_set);
  /// Blocks removed so far (empty while none was).
  std::span<const char> removed_blocks() const { return removed_; }
  /// The state between two steps (not within one: no trial records).
  State state() const;
  /// Takes up a state saved from a system with the same joint sets. Throws
  /// std::invalid_argument when it cannot be one (sizes, indices out of range).
  void restore(const State& state);

 private:
  using Hot = step::Hot;
  using LawStep = step::LawStep;
  void prepare(std::span<const BlockView> blocks, const Contact& c, Hot& h) const;
  double shear_stiffness(size_t c) const;
  /// The dashpots as springs on the step's motion, c / dt [stress] (0 without).
  double normal_dashpot(size_t c) const;
  double shear_dashpot(size_t c) const;
  /// Stiffness that resolves a sliding contact's backward slip: the slip
  /// f_res / k counts as a reversal [stress].
  double reversal_stiffness(size_t c) const;
  /// Sliding -> locked where the vertex stood at the step start: the shear
  /// spring unstretched, or carrying the friction force under
  /// ContactSettings::stick_keeps_force.
  void stick(std::span<const BlockView> blocks, size_t c);
  /// Open -> locked across a gap: the locking point moves along the edge by
  /// `flight`, the tangential motion of the step before the vertex touched [length].
  void lock_at_touch(std::span<const BlockView> blocks, size_t c, double flight);
  const laws::StepConstants& step_constants_of(size_t c) const;
  /// Law constants of the step being solved, once per joint set (never per
  /// contact), and each creeping contact's seam at its start stress
  /// (contact_creep.cpp; called by begin_step).
  void start_laws(double dt);
  /// Sets step_.seams[c] from the law's affine form at a guessed end stress [stress].
  void linearize(size_t c, double tau_guess);
  /// Contact c (locked, its law not linear) takes the seam at the stress tau it carries
  /// [stress]; true when that asks for another iterate (the seam changed, within the bounds
  /// max_refinements and max_creep_newton). f_res: the force resolution [force/length].
  bool relinearize_seam(size_t c, double tau, double f_res);
  /// The force resolution of the open-close decisions and of the commit's projection
  /// (contact_check.cpp) [force/length].
  double force_resolution() const;
  /// Contact c's damage law failed: residual frictional joint (no creep, cohesion, tension)
  /// from now on; `creep` [length], the law's creep of this step up to the failure, still
  /// moves its locking point in this step (0 where it is not finite).
  void fail_law(size_t c, double creep);
  /// Commits contact c of the working records, locked by the solve, onto its Mohr-Coulomb
  /// envelope when it lies outside (contact_commit.cpp): open beyond the tensile cut-off,
  /// locked at the strength beyond it (its locking point moved by the plastic slip).
  void project_onto_envelope(std::span<const BlockView> blocks, size_t c);

  std::vector<JointSet> joint_sets_;
  ContactSettings settings_;
  double penalty_ = 0.0;
  double allowed_penetration_ = 0.0;
  double last_max_penetration_ = 0.0;
  std::size_t projections_ = 0;  ///< last_projections()

  ContactRecords records_;  ///< committed and working records (contact_records.hpp)
  EnergyBook energy_;  ///< energy terms of the last accepted step (energy_book.hpp)
  step::Data step_;  ///< the step being solved: its hot arrays and values (step_arrays.hpp)
  // Adaptive creep stepping (creep_error.hpp, contact_creep_error.cpp).
  bool creep_error_wanted_ = false;  ///< set by begin_step for the step being solved
  CreepErrorEstimate creep_error_;   ///< the estimate of the last accepted step
  StepStart start_;                  ///< what its commit replaced, for retract_step
  std::vector<ContactKey> previous_keys_;
  ExplicitCycles cycles_;  ///< the explicit cycles of the step being solved (explicit_cycles.hpp)
  std::vector<char> removed_;  ///< remove_blocks: 1 for a removed block (empty: none removed)
  std::vector<Box> boxes_;
  BroadPhase broad_;
  DetectionStats stats_;
};

}  // namespace rheodda::contact
