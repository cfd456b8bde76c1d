// The creep scheme of a law in series with a spring k when the user leaves it
// open (`scheme: automatic`): the joints' rule (contact/src/contact_creep.cpp) and
// the bolts' (core/src/bolt_step.cpp) are this one.
#pragma once

#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::laws {

/// Exponential-linear (second order) while dt (k + E_i) <= 2 eta_i for every creep
/// element i of a series law, where it neither diverges nor rings under the series
/// spring k; implicit (monotone at any dt) otherwise, and for a law that is not a
/// series of elements (docs/reference/rheology-in-dda.md, "Schemes"). k in the law's
/// stiffness unit (stress/length on joints, force/length on bolts), dt [time].
Scheme automatic_scheme(const ContactRheology& law, double k, double dt);

}  // namespace rheodda::laws
