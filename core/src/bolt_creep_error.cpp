// The creep error estimate of the bolts for adaptive creep stepping
// (Settings::creep_tolerance; docs/reference/step-controls.md, "Adaptive creep
// stepping"): the estimate the contacts make for a joint's creep
// (contact/src/contact_creep_error.cpp), made for a bolt's creep elongation
// under its axial force.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bolts.hpp"

namespace rheodda::core {

double BoltSet::creep_error_estimate() const {
  double worst = 0.0;
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    const Trial& t = trials_[k];
    const Bolt& bolt = model_->bolts[k];
    if (!t.active || !bolt.law) continue;
    const BoltState& s = start_[k];
    // The end force of the step as commit() will take it: the yield force, or
    // (2) of bolts.hpp at the last iterate (the exact elongation).
    const double force_end =
        t.sign != 0 ? t.sign * bolt.yield_force
                    : std::clamp(t.at.N, -bolt.yield_force, bolt.yield_force);
    const double dt = t.constants.dt;
    laws::RheologyState next;
    double err = 0.0;
    if (t.constants.scheme != laws::Scheme::exponential_linear) {
      // First-order scheme: its increment minus the exponential-linear one (the
      // exact increment for a force linear over the step) is its local error.
      const laws::StepConstants other = bolt.law->step_constants(dt, laws::Scheme::exponential_linear);
      err = std::abs(bolt.law->advance(t.constants, s.rheology, t.force_start, force_end, next) -
                     bolt.law->advance(other, s.rheology, t.force_start, force_end, next));
    } else {
      // Exponential-linear is exact for a force linear over the step; its local
      // error is the creep of the force's departure from linear, |N''| dt^2/12
      // times the step compliance c of the implicit scheme (Delta e_c = h + c N,
      // laws/contact_rheology.hpp eq. 1; c ~ dt/eta for dt << eta/E, where the
      // exponential-linear scheme's own c, the end force's weight, is half of it):
      // the trapezoid-rule remainder dt^3 |N''| / (12 eta), with N'' from the
      // forces at the start of the last step, at the start and at the end of this
      // one. Without the last step (the first step, or after Engine::restore)
      // there is none.
      const Previous& p = k < previous_.size() ? previous_[k] : Previous{};
      if (!p.valid || !(p.dt > 0.0) || p.force_end != s.force || p.elongation_end != s.elongation) continue;
      const double h1 = p.dt, h2 = dt;
      const double curvature = 2.0 * ((force_end - t.force_start) / h2 - (t.force_start - p.force_start) / h1) / (h1 + h2);
      const laws::StepConstants implicit = bolt.law->step_constants(dt, laws::Scheme::implicit);
      const laws::Linearization lin = bolt.law->linearize(implicit, s.rheology, t.force_start, force_end);
      err = std::abs(curvature) * h2 * h2 / 12.0 * lin.c;
    }
    if (std::isnan(err)) err = std::numeric_limits<double>::infinity();
    worst = std::max(worst, err);
  }
  return worst;
}

}  // namespace rheodda::core
