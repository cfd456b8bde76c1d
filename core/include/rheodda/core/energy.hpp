// The energy balance of a run (docs/reference/engine.md, "Energy balance"): after every
// accepted step, the energy stored in the blocks (kinetic, elastic), the fixed
// points and the contact springs, the work of gravity and of the point loads,
// the energy dissipated by friction, by the creep dashpots, by the time
// integration and by contact springs attached or detached within a step, the
// energy the contact springs gain between steps, and the residual of the
// balance - per step and summed since t = 0.
//
// Every term has its own formula (energy.cpp, contact_energy.cpp); none is
// defined as "what is left", so the residual measures what the terms do not
// account for (docs/reference/engine.md lists the mechanisms).
//
// Energies are per unit thickness: [force x length], "force" per unit
// thickness as everywhere (J/m in SI).
//
// Usage:
//   rheodda::core::Engine engine(model, contacts);
//   engine.run(100);
//   const auto& e = engine.energy();
//   e.stored.kinetic, e.total.work_gravity, e.total.residual, e.relative_residual()
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "rheodda/core/block_state.hpp"
#include "rheodda/core/contact_model.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/core/polygon.hpp"

namespace rheodda::core {

/// Energies stored in a state [force x length].
struct StoredEnergy {
  double kinetic = 0.0;         ///< sum over blocks of v^T M v / 2, M = rho int T^T T dA
  double strain = 0.0;          ///< sum over blocks of S sigma^T E_e^-1 sigma / 2 (initial
                                ///< stresses included)
  double fixed = 0.0;           ///< sum over fixed points of p |S (x - x0)|^2 / 2, plus
                                ///< k_r (theta - theta_h)^2 / 2 for a held rotation [force x length]
  double contact_normal = 0.0;  ///< sum over closed contacts of p_n d_n^2 / 2
  double contact_shear = 0.0;   ///< sum over locked contacts of F^2 / (2 k_s), k_s elastic
  double bolt = 0.0;            ///< sum over intact bolts of N^2 / (2 k) (docs/reference/bolts.md, "Energy")
  double total() const { return kinetic + strain + fixed + contact_normal + contact_shear + bolt; }
};

/// Energy flows of one step, or their sums over steps [force x length].
/// Works are energy put into the model (> 0), dissipations energy taken out (> 0).
struct EnergyFlows {
  double work_gravity = 0.0;          ///< sum of rho S g . (centroid displacement)
  double work_loads = 0.0;            ///< sum of f(t_end) . (displacement of the load point), plus
                                      ///< the water pressure's load terms . D (water.hpp)
  double work_contact_restart = 0.0;  ///< energy the contact springs gained between steps
                                      ///< without work (ContactEnergy::restart)
  double dissipation_friction = 0.0;  ///< friction force x slip of sliding contacts (signed)
  double dissipation_creep = 0.0;     ///< end shear force x creep increment of locked contacts
  double dissipation_integration = 0.0;  ///< time integration: the end forces' work beyond
                                         ///< the stored energy change, k Delta^2 / 2 per linear
                                         ///< spring (blocks, fixed points, contacts), plus
                                         ///< integration_inertia
  double integration_inertia = 0.0;   ///< of dissipation_integration, the inertia term's share:
                                      ///< shi (1 - r^2) KE, trapezoidal (1 - r^2) KE +
                                      ///< D^T M (a' - r a) / 2, static D^T M D / (beta dt^2)
  double dissipation_contact_damping = 0.0;  ///< contact dashpots (JointSet::restitution, and the
                                             ///< explicit cycles' dashpots; ContactEnergy::damping)
  double dissipation_block_damping = 0.0;    ///< blocks' strain dashpots (Material::damping_ratio):
                                             ///< sum of (tau/dt) S eps^T E_e eps; in a step taken in
                                             ///< explicit cycles, the blocks' strain and local damping
                                             ///< booked cycle by cycle
  double dissipation_contact_closing = 0.0;  ///< contact springs attached during the step
                                             ///< (ContactEnergy::closing)
  double dissipation_contact_release = 0.0;  ///< contact springs detached during the step
                                             ///< (ContactEnergy::release)
  double dissipation_bolt = 0.0;  ///< bolts (docs/reference/bolts.md, "Energy"): their springs' integration
                                  ///< (N1 - N0)^2/(2k) and its axis's turn, plastic N_y Delta e_p,
                                  ///< creep N Delta e_c, and the stored energy of a bolt that ruptured
  /// Kinetic energy taken by edits between steps (Engine::edit; docs/reference/engine.md,
  /// "Energy balance"): by fixed points added to or removed from a moving block
  /// (Carnot's theorem, model_edits.cpp), less the kinetic energy a set velocity
  /// gave (ModelEdit::set_velocities; signed). Booked in the totals only: no step has it.
  double dissipation_edits = 0.0;
  double residual = 0.0;  ///< (change of the stored energy) - works + dissipations: > 0 is
                          ///< energy the terms do not account for that the model gained
  double scale = 0.0;     ///< |work_gravity| + |work_loads| (summed: of every step)

  /// works - dissipations: what the stored energy should have gained.
  double net_input() const;
  EnergyFlows& operator+=(const EnergyFlows& o);
};

/// The share of a step's work of gravity and loads that its inertia term took,
/// integration_inertia / scale [-] (0 when the step did no such work). In a static
/// analysis (docs/reference/engine.md, "Mechanisms in static analysis") a part that stands
/// takes its load in springs: the share is about (2M/dt^2) d / F_g, far below 1 %.
/// A part that moves as a mechanism is held by nothing but the inertia term
/// 2M/dt^2 of the step: the term takes the unbalanced force's work (about half of
/// the work on the Goodman slope while it settles), and how far the part moves is
/// set by dt and the displacement limit, not by the model.
double inertia_share(const EnergyFlows& f);

/// A static step moved as a mechanism when its inertia_share exceeds this [-].
inline constexpr double kMechanismStepShare = 0.1;
/// A static run's displacements depend on its step controls when its inertia
/// terms took more than this share of all the work of gravity and loads [-].
inline constexpr double kMechanismRunShare = 0.01;

/// The energy balance of a run.
struct EnergyBalance {
  StoredEnergy initial;  ///< at t = 0 (the contacts store nothing before the first step)
  StoredEnergy stored;   ///< after the last accepted step
  EnergyFlows step;      ///< of the last accepted step
  EnergyFlows total;     ///< since t = 0
  double max_relative_residual = 0.0;  ///< largest relative_residual() after any step [-]

  /// |total.residual| / (initial.total() + total.scale): the residual relative to
  /// the energy put into play (initial energy plus the work of gravity and loads,
  /// step by step in absolute value) [-]; 0 while that is 0.
  double relative_residual() const;
};

/// The engine's data the account reads (references valid during the call).
struct EnergyInputs {
  const Model& model;
  const std::vector<BlockState>& blocks;         ///< current block states
  const std::vector<PolygonIntegrals>& moments;  ///< central integrals of their geometry
  const std::vector<Eigen::Matrix3d>& elastic;   ///< E_e per material [stress]
  double fixed_k = 0.0;                          ///< fixed-point spring [force/length]
  double ratio = 0.0;  ///< share of the velocity the step carries (0: a static step) [-]
};

/// Computes the balance of each accepted step (called by the engine from
/// Engine::Impl::accept and, for step doubling, Engine::Impl::doubling_step).
class EnergyAccount {
 public:
  /// The balance at t = 0: the stored energies of the initial state.
  static EnergyBalance start(const EnergyInputs& in);
  /// Energies stored in the blocks and fixed points of the current state.
  static StoredEnergy stored_in_blocks(const EnergyInputs& in);

  /// Before the blocks move by D (step-start geometry and velocities): the
  /// flows that need them. beta, gamma: the Newmark parameters of the step;
  /// t_end: its end time (the gravity of a ramp, Settings::gravity_at).
  void begin(const EnergyInputs& in, const Eigen::VectorXd& D, double dt, double beta,
             double gamma, double t_end);
  /// After begin, for a step taken in explicit cycles: the work its blocks' damping (strain
  /// damping, local damping) took, booked cycle by cycle (explicit_step.cpp) [force x length].
  void add_block_damping(double work) { flows_.dissipation_block_damping += work; }
  /// After the blocks moved and the geometry was refreshed, and after the
  /// contacts' end_step: the stored energies, the load work, the contact terms
  /// and the residual; adds the step to `balance`.
  void end(const EnergyInputs& in, double t_end, const ContactEnergy& contacts,
           EnergyBalance& balance);
  /// Before end(), in a model with bolts: their stored energy after the step and
  /// the step's bolt dissipation [force x length] (core/src/bolts.hpp, BoltEnergy).
  void set_bolts(double stored, double dissipation) {
    bolt_stored_ = stored;
    bolt_dissipation_ = dissipation;
  }
  /// Step doubling (docs/reference/step-controls.md, "Step doubling"): `balance` went from
  /// `start` through the two half steps. Makes it one step: the flows of the two
  /// halves summed or, when the step was extrapolated, every flow extrapolated as
  /// the states are, 2 (sum of the halves) - (the single step's `coarse`), and the
  /// stored energies those of the extrapolated state (`bolts`: the bolts' then).
  static void finish_doubling(const EnergyInputs& in, const EnergyBalance& start,
                              const EnergyFlows& coarse, bool extrapolated,
                              const ContactEnergy& contacts, EnergyBalance& balance, double bolts = 0.0);

  /// A static trial step D of dt, before it is taken: the work its inertia term
  /// D^T M D/(beta dt^2) absorbs over the work of gravity and of the point loads
  /// (at t_end, over the displacement T D of their points), as inertia_share
  /// would find it after the step (docs/reference/engine.md, "Collapse stages") [-].
  static double static_trial_share(const EnergyInputs& in, const Eigen::VectorXd& D, double dt,
                                   double beta, double t_end);

 private:
  EnergyFlows flows_;             ///< of the step in progress
  std::vector<Vec2> load_start_;  ///< load points at the step start [length]
  double bolt_stored_ = 0.0;       ///< set_bolts [force x length]
  double bolt_dissipation_ = 0.0;  ///< set_bolts [force x length]
};

}  // namespace rheodda::core
