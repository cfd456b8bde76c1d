// The stability map's model (docs/notes/step-controls.md, "Stability map"), shared by
// bench/stability_map.cpp and the tests that check it: a spring k in series with a
// law, held at a displacement delta from t = 0, the force of each step solved by
// laws::solve_series_force (the contact's k_eff algebra, contact_rheology.hpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "rheodda/laws/history.hpp"  // solve_series_force

namespace rheodda::models {

/// The growth of the held spring's force over `steps` steps: the largest |F| over the
/// second half of the steps / (k delta) (the force at t = 0+); INFINITY once a force is
/// not finite. `first`: the constants of the first step (the step a DDA contact closes
/// in is implicit whatever the scheme), `ks` those of the others; `end_ratio`: the
/// last step's F / (k delta).
inline double held_spring_growth(const laws::ContactRheology& law, const laws::StepConstants& first,
                                 const laws::StepConstants& ks, double k, double delta, int steps,
                                 double* end_ratio = nullptr) {
  laws::RheologyState q, next;
  double force = k * delta, worst = 0.0;
  for (int n = 1; n <= steps; ++n) {
    const laws::StepConstants& c = n == 1 ? first : ks;
    const double f = laws::solve_series_force(law, c, q, k, delta, force);
    law.advance(c, q, force, f, next);
    q = next;
    force = f;
    if (!std::isfinite(f)) return INFINITY;
    if (n > steps / 2) worst = std::max(worst, std::abs(f));
  }
  if (end_ratio) *end_ratio = force / (k * delta);
  return worst / (k * delta);
}

}  // namespace rheodda::models
