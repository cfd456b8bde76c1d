// The energy book of a ContactSystem (contact_system.hpp; docs/reference/engine.md,
// "Energy balance"): what end_step records of each contact's accepted step
// (StepWork) and the stored energy before it, from which energy() gives the
// contacts' terms of the balance (contact_energy.hpp, contact_energy.cpp).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "rheodda/contact/contact_energy.hpp"
#include "rheodda/contact/contact_record.hpp"

namespace rheodda::contact {

/// What the energy balance needs of one contact's last accepted step,
/// recorded by end_step (parallel to the committed records; contact_energy.cpp).
struct StepWork {
  double pn = 0.0, ps = 0.0;   ///< normal and elastic shear springs of the step [stress]
  double dn0 = 0.0, dn = 0.0;  ///< penetration on the step-start geometry and at the end [length]
  double st0 = 0.0;            ///< stretch of the shear spring at the step start (dt0) [length]
  double slip = 0.0;           ///< tangential relative motion of the step [length]
  ContactState start_state = ContactState::open;
  double friction = 0.0;       ///< friction force of the final solve, signed along the edge
                               ///< (sliding; from the N that solve assembled) [force/length]
  double normal_damping = 0.0;  ///< normal dashpot force at the end (closed; JointSet::restitution) [force/length]
  double shear_damping = 0.0;   ///< shear dashpot force at the end, along the edge (locked) [force/length]
  /// State the step's solve ended with; the committed one differs where that was a
  /// locked state outside the Mohr-Coulomb envelope (held by anti-chattering), which
  /// the commit projects onto it (end_step, "Admissible states at commit").
  ContactState solved_state = ContactState::open;
  double solved_shear_force = 0.0;  ///< the shear spring's end force of the solve (locked) [force/length]
};

/// What the explicit cycles of a step did to the contacts' springs, summed over its cycles
/// and contacts (contact_cycles.cpp), in place of what the step's end forces over its end
/// motion give for a step solved at once [force x length per unit thickness].
struct CycleWork {
  double damping = 0.0;   ///< the dashpots' work: each cycle's force times kick (v_before + v_after)/2
  double friction = 0.0;  ///< the shear force times the locking point's drag, cycle by cycle
  double release = 0.0;   ///< springs' energy where they detached: at the cycle a contact
                          ///< opened, and a sliding contact's shear spring at the step's end
                          ///< (the committed sliding state stores none)
  double attach = 0.0;    ///< springs' energy where they attached without work: the normal
                          ///< spring's overlap at the cycle a contact closed, and a contact
                          ///< sliding at the step start, whose shear spring starts stretched
                          ///< by its friction force
};

/// The energy terms of the last accepted step, kept beside the records.
struct EnergyBook {
  std::vector<StepWork> committed;  ///< of the last accepted step, parallel to its records
  std::vector<StepWork> step;       ///< of the step being committed (end_step)
  double stored_before = 0.0;       ///< stored energy before the last accepted step [force x length]
  /// What the cycles did, when the last accepted step was taken in cycles: its springs'
  /// flows are then these, and the springs attached through it lose nothing to
  /// integration (contact_energy.cpp); empty for a step solved at once.
  std::optional<CycleWork> cycle;

  /// Sum of p_n d_n^2/2 + F^2/(2 k_s) over records with their springs [force x length].
  static double stored_energy(std::span<const Contact> records, std::span<const StepWork> work);
  /// The contacts' terms of the energy balance: stored energies of `records` (the
  /// last accepted step's) and the flows of that step, `creep` its creep increments
  /// parallel to them [length].
  ContactEnergy energy(std::span<const Contact> records, std::span<const double> creep) const;
};

}  // namespace rheodda::contact
