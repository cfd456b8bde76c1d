// What a ContactSystem (contact_system.hpp) computes once per step and reads at
// every iterate of it (after Box2D's "hot" contact data): each contact's
// linearized geometry on the step-start configuration with its springs and
// strength, the creep seam in its shear spring, the creep laws' step
// constants per joint set, and the step's values (creep time, inertia,
// dynamic or not, the last iterate's largest penetration and normal force).
// begin_step builds them, abandon_step and the commit drop the arrays.
#pragma once

#include <vector>

#include "rheodda/contact/contact_record.hpp"
#include "rheodda/contact/kinematics.hpp"
#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::contact {

/// Hook for the creep increment of the shear spring (zero without a law).
/// The spring's stretch is d + locking_shift with locking_shift = -h, and its
/// stiffness k / (1 + k compliance) with compliance = c / l.
struct ShearSeam {
  double locking_shift = 0.0;  ///< -h: minus the history part of the step's creep [length]
  double compliance = 0.0;     ///< step creep compliance c / l [length/(force/length)]
};

namespace step {

/// Linearized geometry of one contact on the step-start configuration:
/// d_n = dn0 + ni.D_i + nj.D_j (penetration, the seed's normal spring, Shi 1988)
/// d_t = dt0 + ti.D_i + tj.D_j (shear along the edge from the locking point, eqs. 23-27).
struct Hot {
  Vec6 ni = Vec6::Zero(), nj = Vec6::Zero();
  Vec6 ti = Vec6::Zero(), tj = Vec6::Zero();
  double dn0 = 0.0;  ///< [length]
  double dt0 = 0.0;  ///< [length]
  double pn = 0.0;   ///< normal spring [stress]
  double ps = 0.0;   ///< shear spring [stress]
  /// Contact dashpots (JointSet::restitution; 0 without): normal and shear
  /// [force time / length^2 per unit thickness]. Over a step of length dt they
  /// act as springs c/dt on the step's motion (implicit: the end-of-step rate).
  double cn = 0.0, cs = 0.0;
  /// Reduced mass m_i m_j / (m_i + m_j) of the two blocks [mass/length].
  double reduced_mass = 0.0;
  /// Penetration from which the normal dashpot counts the step's approach:
  /// d_n0 for a contact closed at the step start, max(d_n0, 0) for one open
  /// at the step start (from the touching point across a gap) [length].
  double dn_ref = 0.0;
  double tan_phi = 0.0;
  double cohesion = 0.0;          ///< [stress]
  double tensile_strength = 0.0;  ///< [stress]
  double normal_force = 0.0;      ///< N of the last iterate, drives friction [force/length]
  ContactState start_state = ContactState::open;
  double tau_start = 0.0;       ///< shear stress driving creep at the step start [stress]
  bool creep_from_rest = true;  ///< not locked at the step start: the step's creep uses
                                ///< the end force for the whole step (implicit constants)
  int flips = 0;        ///< state changes of this contact in this step
  ContactState undo_state = ContactState::open;  ///< state before its last change (diagnosis)
  int undo_direction = 0;                        ///< slide direction before its last change
  int refinements = 0;  ///< friction refinements of this contact in this step
  int newton = 0;       ///< Newton iterates a nonlinear law asked for in this step
  bool law_failed = false;  ///< its law failed in this step (damage 1): counted in end_step
  /// Creep of this step up to the failure, kept by end_step (fail_law) [length].
  double failure_creep = 0.0;
  double assembled_normal_force = 0.0;  ///< normal_force as the last solve's assembly used it
                                        ///< (set by check; energy balance) [force/length]
};

/// Step constants of one joint set: the scheme's and the implicit ones.
struct LawStep {
  bool active = false;  ///< the joint set has a law and dt > 0
  laws::Scheme scheme = laws::Scheme::implicit;
  laws::StepConstants main, from_rest;
};

/// The step being solved: its arrays, parallel to the working records (laws:
/// per joint set), and what begin_step and the iterates set for all contacts.
struct Data {
  std::vector<Hot> hot;
  std::vector<ShearSeam> seams;
  std::vector<LawStep> laws;  ///< per joint set, for the step being solved (kept for scheme_used)
  double dt = 0.0;       ///< creep time of the step [time]
  double inertia = 0.0;  ///< inertia stiffness per unit mass of the step, 1/(beta dt^2) [1/time^2]
  bool dynamic = true;   ///< the step carries velocity (StepContext::dynamic)
  double max_penetration = 0.0;  ///< largest penetration of the last iterate [length]
  double force_scale = 0.0;      ///< largest |N| of the last iterate [force/length]
  double force_cap = 0.0;        ///< the most force_scale counts for the force resolution: the
                                 ///< stiffest normal spring at the allowed penetration [force/length]

  /// Drops the contacts' arrays (the laws' constants stay for scheme_used, the
  /// values for the commit's creep error estimate).
  void clear() {
    hot.clear();
    seams.clear();
  }
};

}  // namespace step
}  // namespace rheodda::contact
