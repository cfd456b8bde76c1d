// The Mohr-Coulomb strength of a contact, written once (docs/reference/contacts.md,
// "Friction, cohesion, tension (Mohr-Coulomb)"): the implicit step's springs and
// commit, the explicit step's cycles and the outputs all take it from here.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rheodda/contact/joint_set.hpp"

namespace rheodda::contact {

/// tan of an angle given in degrees [-].
inline double tan_deg(double degrees) { return std::tan(degrees * std::numbers::pi / 180.0); }

/// The Mohr-Coulomb shear strength N tan(phi) + c l of a contact [force/length]: N the
/// normal force [force/length] (compression > 0), tan(phi) [-], c the cohesion [stress], l
/// the contact length [length]. The linear envelope holds in tension too (N < 0, down to the
/// tensile cut-off N = -T l, where the contact opens), as in UDEC's Coulomb slip joint model
/// (Itasca, UDEC Constitutive Models: tau_max = c + sigma_n tan(phi)); beyond the envelope's
/// apex (c l + N tan(phi) < 0) the strength is nil, never negative.
/// The same with the cohesion force C = c l given [force/length] (the explicit cycles take
/// it once per step).
inline double mohr_coulomb_strength(double normal_force, double tan_phi, double cohesion_force) {
  return std::max(normal_force * tan_phi + cohesion_force, 0.0);
}

inline double mohr_coulomb_strength(double normal_force, double tan_phi, double cohesion, double length) {
  return mohr_coulomb_strength(normal_force, tan_phi, cohesion * length);
}

/// The strength of a contact of joint set `js` [force/length], peak while it is intact and
/// residual once not (JointSet::friction_angle_of, cohesion_of).
inline double mohr_coulomb_strength(const JointSet& js, double normal_force, double length, bool intact) {
  return mohr_coulomb_strength(normal_force, tan_deg(js.friction_angle_of(intact)), js.cohesion_of(intact), length);
}

/// Whether a closed contact's normal force N [force/length] is beyond its tensile cut-off
/// -T l (T the tensile strength [stress], l the contact length): it opens. f_res is the
/// force resolution [force/length] (ContactSettings::force_resolution).
inline bool beyond_tensile_cutoff(double normal_force, double tensile_strength, double length, double f_res) {
  return normal_force < -tensile_strength * length - f_res;
}

/// Whether a shear force S [force/length] exceeds the Mohr-Coulomb strength of a contact of
/// normal force N (mohr_coulomb_strength) by more than f_res: a locked contact slides.
inline bool beyond_strength(double shear_force, double normal_force, double tan_phi, double cohesion,
                            double length, double f_res) {
  return std::abs(shear_force) > mohr_coulomb_strength(normal_force, tan_phi, cohesion, length) + f_res;
}

}  // namespace rheodda::contact
