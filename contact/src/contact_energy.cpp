// The contacts' terms of the energy balance (EnergyBook, energy_book.hpp;
// contact_energy.hpp; docs/reference/engine.md, "Energy balance"), from the
// records of the last accepted step and what end_step recorded of it
// (StepWork: springs, start and end stretches, slip, state at the step start).
//
// Springs (Shi 1988; the seed's eqs. 17-18, 23-29), per contact:
//   normal  p_n, stretch d_n (penetration): d_n0 on the step-start geometry,
//           d_n = d_n0 + n_i.D_i + n_j.D_j at the end, force N = p_n d_n;
//   dashpots (JointSet::restitution) beside the normal spring of a closed
//           contact and the shear spring of a locked one: their end forces
//           times the step's approach d_n - d_n0 and slip (`damping`);
//   shear   k_s (elastic: p_s, or the joint's k l, or the law's E1 l), stretch
//           s0 = dt0 from the locking point at the step start and
//           s1 = dt0 + slip - Delta d_c at the end, force F = k_s s1 (end_step).
// The end forces act on the blocks over the whole step (implicit assembly), so
// the work the blocks do on a spring attached through the step is
//   F1 (s1 - s0) + F1 Delta d_c = [k s1^2/2 - k s0^2/2] + k (s1 - s0)^2/2 + F1 Delta d_c
//   (stored)                       (integration)          (creep, dashpots)
// and on a sliding contact's friction force F (signed along the slide
// direction; the one the final solve assembled, from the N of the iterate
// before it) F slip. A spring attached during the step has no start energy:
// its k (s1 - s0)^2/2 - k s0^2/2 is `closing`; a spring detached during the
// step does no work and loses k s0^2/2: `release`.
//
// A step taken in explicit cycles (contact_cycles.cpp) applies each cycle's spring forces
// over that cycle's motion only, so none of the end-force terms above holds for it: its
// springs lose nothing to integration (the cycles' own discrete error is O(h) per cycle,
// left to the residual), a spring attached during the step takes from the blocks only the
// work after it touched, and one that slid or detached did so at some cycle, with the
// force and stretch of that cycle. For such a step the book keeps the stored energies at
// its ends and the creep term, and takes friction, release and attachment from what the
// cycles summed (CycleWork: friction T x drag of the locking point at each cycle; release,
// the springs' energy at the cycle they detached; attachment, the energy springs gained
// without work, booked as a negative `closing`).
#include <span>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/contact/energy_book.hpp"

namespace rheodda::contact {

double EnergyBook::stored_energy(std::span<const Contact> records, std::span<const StepWork> work) {
  double e = 0.0;
  for (size_t c = 0; c < records.size() && c < work.size(); ++c) {
    const Contact& r = records[c];
    if (r.state != ContactState::open) e += 0.5 * work[c].pn * r.penetration * r.penetration;
    if (r.state == ContactState::locked) e += 0.5 * r.shear_force * r.shear_force / work[c].ps;
  }
  return e;
}

ContactEnergy EnergyBook::energy(std::span<const Contact> records, std::span<const double> creep) const {
  ContactEnergy e;
  double start = 0.0;  // springs attached at the step start: sum of k s0^2/2
  for (size_t c = 0; c < records.size() && c < committed.size(); ++c) {
    const Contact& r = records[c];
    const StepWork& w = committed[c];
    // The springs' work follows the state the solve ended with (w.solved_state); what is
    // stored follows the committed one. They differ where the commit projected a locked
    // contact onto its Mohr-Coulomb envelope (end_step): the spring energy that released
    // is booked with the springs detached (`release`).
    // Normal spring: attached while the contact is closed.
    const bool n_start = w.start_state != ContactState::open;
    const bool n_end = w.solved_state != ContactState::open;
    const double un0 = 0.5 * w.pn * w.dn0 * w.dn0;
    if (n_start) start += un0;
    if (cycle) {
      if (n_end) e.normal += 0.5 * w.pn * r.penetration * r.penetration;
    } else if (n_end) {
      const double d = w.dn - w.dn0;
      const double un1 = 0.5 * w.pn * r.penetration * r.penetration;
      if (r.state != ContactState::open)
        e.normal += un1;
      else
        e.release += un1;  // projected open at the commit
      // The normal dashpot (JointSet::restitution): its end force times the
      // approach of the step.
      e.damping += w.normal_damping * d;
      if (n_start)
        e.integration += 0.5 * w.pn * d * d;
      else
        e.closing += 0.5 * w.pn * d * d - un0;
    } else if (n_start) {
      e.release += un0;
    }
    // Shear spring: attached while the contact is locked.
    const bool s_start = w.start_state == ContactState::locked;
    const bool s_end = w.solved_state == ContactState::locked;
    const double us0 = 0.5 * w.ps * w.st0 * w.st0;
    if (s_start) start += us0;
    if (cycle) {
      if (s_end) {
        e.shear += 0.5 * r.shear_force * r.shear_force / w.ps;
        e.creep += r.shear_force * (c < creep.size() ? creep[c] : 0.0);
      }
      continue;  // friction and dashpots: the cycles' (below)
    }
    if (s_end) {
      const double F1 = w.solved_shear_force;
      const double s1 = F1 / w.ps;
      const double d = s1 - w.st0;  // slip - Delta d_c
      // Committed: F1 itself, or (projected) nothing when open, the strength when locked.
      const double us1 = r.state == ContactState::locked ? 0.5 * r.shear_force * r.shear_force / w.ps : 0.0;
      e.shear += us1;
      e.release += 0.5 * F1 * s1 - us1;
      e.creep += F1 * (c < creep.size() ? creep[c] : 0.0);
      if (s_start)
        e.integration += 0.5 * w.ps * d * d;
      else
        e.closing += 0.5 * w.ps * d * d - us0;
    } else if (s_start) {
      e.release += us0;
    }
    // Friction: the force the final solve assembled (from the N of the iterate
    // before it; the record's shear_force takes the final N) times the slip,
    // both signed along the edge: > 0 when the vertex slides the way friction
    // resists.
    if (w.solved_state == ContactState::sliding) e.friction += w.friction * w.slip;
    // Shear dashpot (locked; JointSet::restitution): its end force over the slip.
    e.damping += w.shear_damping * w.slip;
  }
  if (cycle) {
    e.damping += cycle->damping;
    e.friction += cycle->friction;
    e.release += cycle->release;
    e.closing -= cycle->attach;
  }
  e.restart = start - stored_before;
  return e;
}

ContactEnergy ContactSystem::energy() const {
  return energy_.energy(records_.committed.contacts, records_.committed.creep);
}

}  // namespace rheodda::contact
