// Accepting a step (docs/reference/contacts.md; docs/reference/rheology-in-dda.md): the records
// of the step become the committed ones, with their forces, accumulated shear,
// locking points and the creep laws' histories advanced over the step.
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"
#include "rheodda/contact/strength.hpp"
#include "law_call_site.hpp"

namespace rheodda::contact {

namespace {

void follow_vertex(std::span<const BlockView> blocks, Contact& r, const Eigen::Ref<const Vec6>& Di,
                   const Eigen::Ref<const Vec6>& Dj) {
  // The locking point follows the vertex: its projection on the displaced edge.
  const BlockView& bi = blocks[r.key.vblock];
  const BlockView& bj = blocks[r.key.eblock];
  const Vec2& p = bi.vertices[r.key.vertex];
  const Vec2 a = edge_start(bj, r.key.edge), b = edge_end(bj, r.key.edge);
  r.locking_ratio = line_ratio(a + displacement_matrix(bj.centroid, a) * Dj, b + displacement_matrix(bj.centroid, b) * Dj,
                               p + displacement_matrix(bi.centroid, p) * Di);
}

}  // namespace

void ContactSystem::project_onto_envelope(std::span<const BlockView> blocks, size_t c) {
  // Admissible states at commit (docs/reference/contacts.md, "States and the open-close
  // iteration"): the open-close iteration's anti-chattering rule may end a step with a
  // contact held locked outside its Mohr-Coulomb envelope - pulled beyond its tensile
  // cut-off, or sheared beyond N tan(phi) + c l. Committed as it is, the next step would
  // start from a force the joint cannot carry, and its spring would store energy no force
  // put there. It is committed onto the envelope instead: beyond the cut-off open (both
  // springs released); beyond the strength locked at it, the spring slipping plastically
  // by (|F| - f) / k_s (a return mapping; its locking point moved that far, as a stick
  // with stick_keeps_force leaves it at the friction force). Committed sliding instead,
  // the next step's vertex, stopped, chatters between stick and slip again. The spring
  // energy this releases is booked with the springs detached in the step
  // (ContactEnergy::release; contact_energy.cpp).
  Contact& r = records_.work.contacts[c];
  const Hot& h = step_.hot[c];
  const double f_res = force_resolution();
  if (beyond_tensile_cutoff(r.normal_force, h.tensile_strength, r.length, f_res)) {
    r.state = ContactState::open;
    r.normal_force = r.shear_force = 0.0;
    r.intact = false;
    ++projections_;
  } else if (beyond_strength(r.shear_force, r.normal_force, h.tan_phi, h.cohesion, r.length, f_res)) {
    // Return mapping: the spring slips plastically by (|F| - f) / k_s along its stretch,
    // its locking point moved that far, and stays locked at the strength f.
    const double f = (r.shear_force >= 0.0 ? 1.0 : -1.0) *
                     mohr_coulomb_strength(r.normal_force, h.tan_phi, h.cohesion, r.length);
    const BlockView& eb = blocks[r.key.eblock];
    r.locking_ratio += (r.shear_force - f) / h.ps / edge_length(eb, r.key.edge);
    r.shear_force = f;
    r.intact = false;
    ++projections_;
  }
}

void ContactSystem::end_step(std::span<const BlockView> blocks, const Eigen::VectorXd& D) {
  assert(D.size() == 6 * static_cast<Eigen::Index>(blocks.size()));
  // A step that may be retracted (begin_step's creep_error_wanted) keeps what
  // this commit changes beside the records (contact_creep_error.cpp).
  start_.retractable = false;
  if (creep_error_wanted_) {
    start_.counters = records_.counters;
    start_.last_max_penetration = last_max_penetration_;
    start_.penalty = penalty_;
    start_.stored_before = energy_.stored_before;
  }
  double max_pen = 0.0;
  projections_ = 0;
  energy_.stored_before = EnergyBook::stored_energy(records_.committed.contacts, energy_.committed);
  energy_.step.resize(records_.work.contacts.size());
  for (size_t c = 0; c < records_.work.contacts.size(); ++c) {
    Contact& r = records_.work.contacts[c];
    const Hot& h = step_.hot[c];
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    const double slip = h.ti.dot(Di) + h.tj.dot(Dj);
    const double dt = h.dt0 + step_.seams[c].locking_shift + slip;
    r.penetration = dn;
    r.creep_state = r.rheology >= 0 ? CreepState::idle : CreepState::none;
    energy_.step[c] = {h.pn, h.ps, h.dn0, dn, h.dt0, slip, h.start_state,  // energy balance
                     r.slide_direction * mohr_coulomb_strength(h.assembled_normal_force, h.tan_phi, h.cohesion, r.length),
                     // (the dashpots of a step taken in cycles: booked cycle by cycle, contact_cycles.cpp)
                     !cycles_.active && r.state != ContactState::open ? normal_dashpot(c) * (dn - h.dn_ref) : 0.0,
                     !cycles_.active && r.state == ContactState::locked ? shear_dashpot(c) * slip : 0.0,
                     r.state, 0.0};
    switch (r.state) {
      case ContactState::open:
        if (h.law_failed) ++records_.counters[r.joint_set].failures;  // failed at an iterate (check)
        r.normal_force = r.shear_force = 0.0;
        if (h.start_state != ContactState::open) r.intact = false;
        break;
      case ContactState::locked: {
        r.normal_force = h.pn * dn;
        r.shear_force = shear_stiffness(c) * dt;
        r.shear_displacement += slip;
        max_pen = std::max(max_pen, dn);
        bool crept = false;  // this step's creep moves the locking point
        double creep = 0.0;  // [length]
        if (r.rheology >= 0 && r.tributary_length > 0.0 && step_.laws[r.joint_set].active &&
            !r.creep_failed) {
          // Advance the history from the step-start state with the step's end
          // stress tau = F / l_t, move the locking point by the creep increment
          // along the entrance edge (the seed's eqs. 22-29) and take the force
          // from the spring's remaining stretch.
          const laws::RheologyState old = records_.work.rheology[r.rheology];
          const laws::CallSiteScope at(law_call_site(r));
          creep = joint_sets_[r.joint_set].law->advance(step_constants_of(c), old, h.tau_start,
                                                        r.shear_force / r.tributary_length,
                                                        records_.work.rheology[r.rheology]);
          CreepCounters& counters = records_.counters[r.joint_set];
          counters.contact_time += step_.dt;
          if (!r.has_crept) ++counters.contacts;
          r.has_crept = true;
          r.creep_state = CreepState::creeping;
          if (records_.work.rheology[r.rheology].failed()) {
            // The law failed within the step at the converged stress although no
            // iterate saw it (e.g. anti-chattering): the joint becomes a
            // residual frictional joint now, with this step's creep up to the
            // failure (advance stops the damaging creep there); the next step's
            // Mohr-Coulomb check decides whether it holds.
            fail_law(c, creep);
            creep = h.failure_creep;
          }
          crept = true;
        } else if (h.law_failed) {
          // Failed at an iterate (check): the creep up to the failure, which the
          // solve already took as a shift of the locking point (fail_law).
          creep = h.failure_creep;
          crept = creep != 0.0;
        }
        if (crept) {
          const BlockView& eb = blocks[r.key.eblock];
          r.locking_ratio += creep / edge_length(eb, r.key.edge);
          r.shear_force = h.ps * (h.dt0 + slip - creep);
          records_.work.creep[c] = creep;
          r.creep_displacement += creep;
        }
        if (h.law_failed) ++records_.counters[r.joint_set].failures;
        energy_.step[c].solved_shear_force = r.shear_force;
        project_onto_envelope(blocks, c);
        break;
      }
      case ContactState::sliding: {
        if (h.law_failed) ++records_.counters[r.joint_set].failures;  // failed at an iterate (check)
        r.normal_force = h.pn * dn;
        r.shear_force = r.slide_direction * mohr_coulomb_strength(r.normal_force, h.tan_phi, h.cohesion, r.length);
        r.shear_displacement += slip;
        r.intact = false;
        max_pen = std::max(max_pen, dn);
        follow_vertex(blocks, r, Di, Dj);
        break;
      }
    }
  }
  last_max_penetration_ = max_pen;
  // Penetration control: raise the penalty for the next steps.
  if (max_pen > allowed_penetration_ &&
      penalty_ * settings_.penalty_raise <= settings_.penalty * settings_.penalty_max_factor)
    penalty_ *= settings_.penalty_raise;
  // History rules: an open or sliding contact loses its creep history (the
  // spring relocks unstretched, so the law restarts from rest).
  for (const Contact& r : records_.work.contacts)
    if (r.rheology >= 0 && r.state != ContactState::locked) records_.work.rheology[r.rheology] = {};
  records_.committed.swap(records_.work);
  energy_.committed.swap(energy_.step);  // energy balance
  energy_.cycle = cycles_.active ? std::optional<CycleWork>(cycles_.work) : std::nullopt;
  if (creep_error_wanted_) {
    // The step-start records (now in the working arrays) are the estimate's
    // start, and what retract_step swaps back.
    start_.records.swap(records_.work);
    start_.work.swap(energy_.step);
    creep_error_.estimate(start_.records.contacts, start_.records.rheology, records_.committed.contacts,
                          joint_sets_, step_.laws, step_.dt);
    start_.retractable = true;
  } else {
    creep_error_.skip();
  }
  records_.work.clear();
}

}  // namespace rheodda::contact
