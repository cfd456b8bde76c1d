// The open-close check of a trial (docs/reference/contacts.md, "States and the
// open-close iteration"): each contact's state against the trial displacements
// (open, locked, sliding by Mohr-Coulomb), the stick and lock-at-touch rules,
// anti-chattering, friction refinements and the creep laws' Newton.
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

void ContactSystem::stick(std::span<const BlockView> blocks, size_t c) {
  // Sliding -> locked where the vertex stood at the step start p. By default
  // (Shi's rule) the shear spring restarts unstretched there. With
  // ContactSettings::stick_keeps_force it keeps the friction force F the
  // contact slid against, as an elastic-plastic joint keeps its elastic shear
  // displacement: the locking point P0 goes behind p by the stretch that
  // carries F, P0 = p - s t with s = d F / k_s (d the slide direction, t the
  // edge direction). The trade (docs/notes/contact-solves.md, "Why the iteration does
  // not settle"): far fewer iterates and cuts on walls and slopes at the
  // friction limit; a creeping slope at its limit takes other, step-dependent
  // paths.
  Contact& r = records_.work.contacts[c];
  Hot& h = step_.hot[c];
  const BlockView& eb = blocks[r.key.eblock];
  const Vec2 a = edge_start(eb, r.key.edge), b = edge_end(eb, r.key.edge);
  const double friction = mohr_coulomb_strength(h.normal_force, h.tan_phi, h.cohesion, r.length);
  const bool keep = step_.dynamic && settings_.stick_keeps_force_dynamic ? *settings_.stick_keeps_force_dynamic
                                                                          : settings_.stick_keeps_force;
  const double stretch = keep ? r.slide_direction * friction / shear_stiffness(c) : 0.0;
  r.locking_ratio = line_ratio(a, b, blocks[r.key.vblock].vertices[r.key.vertex]) -
                    stretch / (b - a).norm();
  r.state = ContactState::locked;
  prepare(blocks, r, h);
}

void ContactSystem::lock_at_touch(std::span<const BlockView> blocks, size_t c, double flight) {
  // The locking point moves along the entrance edge by the tangential motion
  // before the touch, so the spring's stretch counts from there.
  Contact& r = records_.work.contacts[c];
  const BlockView& eb = blocks[r.key.eblock];
  r.locking_ratio += flight / edge_length(eb, r.key.edge);
  prepare(blocks, r, step_.hot[c]);
}

double ContactSystem::force_resolution() const {
  // Forces below this are zero for the state decisions, so that contacts that carry
  // (almost) nothing - the vertical joints of a wall - do not flip on round-off. Its
  // scale is the largest normal force of the last iterate's closed contacts, but never
  // more than the stiffest contact spring carries at the allowed penetration
  // (penetration_ratio x w0; beyond it the penalty is raised, step_.force_cap): a force
  // beyond that is no contact state but an iterate that sent a block far (in a static
  // step a block its contacts no longer hold moves g dt^2/2, and the contacts it is
  // driven into carry 1e20 N/m). Judged at a resolution taken from such an iterate, no
  // open contact closed however deep it went, and the trial, with nothing left to
  // change, was accepted (docs/notes/rock-mass-steps.md, "A resolution taken from an
  // absurd iterate").
  return settings_.force_resolution * std::min(step_.force_scale, step_.force_cap);
}

CheckResult ContactSystem::check(std::span<const BlockView> blocks, const Eigen::VectorXd& D) {
  assert(D.size() == 6 * static_cast<Eigen::Index>(blocks.size()));
  CheckResult res;
  const double f_res = force_resolution();
  double scale = 0.0;
  for (size_t c = 0; c < records_.work.contacts.size(); ++c) {
    Contact& r = records_.work.contacts[c];
    Hot& h = step_.hot[c];
    h.assembled_normal_force = h.normal_force;  // energy balance: the friction just solved with
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    const double slip = h.ti.dot(Di) + h.tj.dot(Dj);  // tangential motion this step [length]
    const double dt = h.dt0 + step_.seams[c].locking_shift + slip;
    // The states follow the springs alone (the overlap and the shear spring's
    // stretch), as in Cundall & Strack's spring-dashpot contact: a contact
    // dashpot (JointSet::restitution) adds its force c rate beside the spring
    // of a closed (normal) or locked (shear) contact, but neither opens, closes,
    // nor makes a contact slide, and friction is N tan(phi) of the spring's N.
    // Deciding on the total force instead, the dashpot's transient force at an
    // impact (c v, hundreds of times the block's weight) would lock the shear
    // spring with a stretch that the weight's friction cannot hold afterwards,
    // and where a block dropped on an incline stops would depend on the step
    // (docs/notes/contact-rules.md, "The total force deciding").
    const double N = h.pn * dn;
    r.penetration = dn;
    const ContactState before = r.state;
    const int direction_before = r.slide_direction;
    bool refine = false;  // friction force from a stale normal force
    switch (r.state) {
      case ContactState::open:
        if (N > f_res) {
          // Closes; Mohr-Coulomb decides at once whether it holds or slides (a
          // vertex arriving with tangential speed would otherwise be caught by
          // a fully stretched shear spring for one iterate). Across a gap g0 =
          // -d_n0 the vertex touches after the share f = g0 / (g0 + d_n) of the
          // step's approach (linear in the step); the tangential motion before
          // that, f slip, is flight, not stretch of the spring: the spring locks
          // where the vertex touches. Counting it (Shi's rule: the locking point
          // at the step-start projection) made the outcome of an impact depend
          // on where in its step the contact was reached (docs/reference/contacts.md,
          // "Contact damping": a block dropped on an incline slid at the impact
          // at some steps and not at others). Dynamic analysis only
          // (ContactSettings::lock_at_touch).
          const double gap = std::max(-h.dn0, 0.0);
          const double flight =
              (settings_.lock_at_touch && step_.dynamic && gap > 0.0) ? gap / (gap + dn) * slip : 0.0;
          const double S = shear_stiffness(c) * (dt - flight);
          if (beyond_strength(S, N, h.tan_phi, h.cohesion, r.length, f_res)) {
            r.state = ContactState::sliding;
            r.slide_direction = S >= 0.0 ? 1 : -1;
          } else {
            r.state = ContactState::locked;
            if (flight != 0.0) lock_at_touch(blocks, c, flight);
          }
        }
        break;
      case ContactState::locked:
      case ContactState::sliding:
        if (beyond_tensile_cutoff(N, h.tensile_strength, r.length, f_res)) {
          r.state = ContactState::open;
        } else if (r.state == ContactState::locked) {
          // Mohr-Coulomb (strength.hpp): slip when |F_T| > N tan(phi) + c l.
          const double S = shear_stiffness(c) * dt;
          if (beyond_strength(S, N, h.tan_phi, h.cohesion, r.length, f_res)) {
            r.state = ContactState::sliding;
            r.slide_direction = dt >= 0.0 ? 1 : -1;
          }
        } else if (reversal_stiffness(c) * slip * r.slide_direction < -f_res) {
          // The vertex moves against the friction direction assumed: it sticks
          // where it stood at the start of the step (stick). The test resolves
          // a backward slip of f_res / k with k the stiffness that holds the
          // vertex's tangential motion (reversal_stiffness).
          stick(blocks, c);
        } else {
          // The friction force N tan(phi) came from the last iterate's N.
          refine = std::abs(N - h.normal_force) >
                   std::max(settings_.friction_tolerance *
                                std::max(std::abs(N), std::abs(h.normal_force)),
                            f_res);
        }
        break;
    }
    if (r.state != before) {
      if (h.flips >= settings_.max_flips && r.state != ContactState::locked) {
        // Anti-chattering: a contact that already changed max_flips times in
        // this step (typically a vertex that stops within the step: sliding
        // reverses it, locking needs more than friction to stop it) may only
        // go to the most constrained state, locked, for the rest of the step.
        // The state it is held in may lie outside its Mohr-Coulomb envelope: the
        // commit projects it onto the envelope (end_step), so that no step starts
        // from a force its joint cannot carry.
        if (before == ContactState::locked) {
          r.state = before;
        } else {
          if (before == ContactState::sliding) stick(blocks, c);
          r.state = ContactState::locked;
        }
      }
      if (r.state != before) {
        // Diagnosis (ContactChanges::cycled): a change that undoes this contact's
        // last one in the step (A -> B -> A; for sliding, in the same direction).
        if (h.flips > 0 && r.state == h.undo_state &&
            (r.state != ContactState::sliding || r.slide_direction == h.undo_direction)) {
          ++res.changes.cycled;
          if (r.kind == ContactKind::vertex_vertex) ++res.changes.cycled_corners;
        }
        h.undo_state = before;
        h.undo_direction = direction_before;
        ++h.flips;
        ++res.state_changes;
        if (before == ContactState::open) ++res.changes.closed;
        else if (r.state == ContactState::open) ++res.changes.opened;
        else if (r.state == ContactState::sliding) ++res.changes.slipped;
        else ++res.changes.stuck;
      }
    } else if (refine && h.refinements < settings_.max_refinements) {
      ++h.refinements;
      ++res.state_changes;
      ++res.changes.refinements;
    }
    // The normal force that drives friction in the next iterate. A contact that
    // just closed has N from a trial without its spring (the whole free
    // approach of the step as penetration): start its friction from zero and
    // let the refinement above bring it to its own N.
    h.normal_force = (r.state == ContactState::open || before == ContactState::open) ? 0.0 : N;
    if (r.state != ContactState::open) {
      res.max_penetration = std::max(res.max_penetration, dn);
      scale = std::max(scale, std::abs(N));
    }
    // A piecewise-affine law (Nishihara's threshold): take the piece that holds
    // at this iterate's stress; a change asks for another iteration (bounded
    // by max_refinements, so the switch cannot chatter).
    if (r.state == ContactState::locked && r.rheology >= 0 && r.tributary_length > 0.0 &&
        step_.laws[r.joint_set].active && !r.creep_failed &&
        !joint_sets_[r.joint_set].law->is_linear()) {
      const double tau =
          shear_stiffness(c) * (h.dt0 + step_.seams[c].locking_shift + slip) / r.tributary_length;
      const laws::ContactRheology& law = *joint_sets_[r.joint_set].law;
      const laws::RheologyState& history = records_.work.rheology[r.rheology];
      if (law.failure_in_step(step_constants_of(c), history, h.tau_start, tau)) {
        // The law fails within the step at this stress (damage 1, docs/reference/rheology-in-dda.md,
        // "Failure"): the joint's creep strength is gone. It becomes a residual
        // frictional joint - elastic spring, no creep, no cohesion or tensile
        // strength - and the next iterate lets Mohr-Coulomb decide whether its
        // friction holds. The creep up to the failure (the law's advance at this
        // stress stops its damaging creep there) is this step's.
        laws::RheologyState at_failure;
        const laws::CallSiteScope at(law_call_site(r));
        fail_law(c, law.advance(step_constants_of(c), history, h.tau_start, tau, at_failure));
        ++res.state_changes;
        ++res.changes.slipped;
        continue;
      }
      if (relinearize_seam(c, tau, f_res)) {
        ++res.state_changes;
        ++res.changes.refinements;
      }
    }
  }
  step_.force_scale = scale;
  step_.max_penetration = res.max_penetration;
  return res;
}

bool ContactSystem::relinearize_seam(size_t c, double tau, double f_res) {
  // A piecewise-affine law (Nishihara's threshold) takes the piece that holds at tau, a
  // nonlinear one its tangent there; another iterate is wanted when the seam changed,
  // bounded by max_refinements so that a switch cannot chatter.
  Hot& h = step_.hot[c];
  const ShearSeam before_seam = step_.seams[c];
  linearize(c, tau);
  const Contact& r = records_.work.contacts[c];
  if (joint_sets_[r.joint_set].law->linearity() == laws::Linearity::nonlinear) {
    // Newton (docs/reference/rheology-in-dda.md, "Nonlinear laws"): the iterate was
    // solved with the tangent at the last stress; the law's increment at
    // this stress, Delta d_c(tau) = h + c tau of the new tangent, differs
    // from that model by e [length], which moves the stress by about
    // k_eff e / l_t. Another iterate while that exceeds the tolerance.
    const double lt = r.tributary_length;
    const double model = -before_seam.locking_shift + before_seam.compliance * lt * tau;
    const double actual = -step_.seams[c].locking_shift + step_.seams[c].compliance * lt * tau;
    const double stress_error = shear_stiffness(c) * std::abs(actual - model) / lt;
    if (stress_error > settings_.creep_newton_tolerance * std::max(std::abs(tau), f_res / lt) &&
        h.newton < settings_.max_creep_newton) {
      ++h.newton;
      return true;
    }
    return false;
  }
  const ShearSeam& seam = step_.seams[c];
  if ((seam.compliance != before_seam.compliance || seam.locking_shift != before_seam.locking_shift) &&
      h.refinements < settings_.max_refinements) {
    ++h.refinements;
    return true;
  }
  return false;
}

}  // namespace rheodda::contact
