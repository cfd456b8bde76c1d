#include "rheodda/laws/series_law.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "rheodda/laws/parameters.hpp"

namespace rheodda::laws {

double kelvin_b(double r) { return -std::expm1(-r); }

double kelvin_phi(double r) {
  // phi = 1 - (1 - e^-r)/r = (r - 1 + e^-r)/r. Direct evaluation cancels for
  // small r (relative error ~ 2 eps / r), so below r = 0.5 use the alternating
  // Taylor series phi = r/2 - r^2/6 + r^3/24 - ... = sum_{j>=1} (-1)^(j+1) r^j/(j+1)!,
  // in nested form r/2 (1 - r/3 (1 - r/4 (1 - ...))) to the term r^16/17!: the
  // first omitted term, 0.5^17/18! < 1.2e-21, is far below round-off of
  // phi >= 0.2 there. Above 0.5 the direct form loses at most a few ulps.
  if (r < 0.5) {
    double nested = 1.0;
    for (int j = 17; j >= 3; --j) nested = 1.0 - r / j * nested;
    return 0.5 * r * nested;
  }
  if (r > 1e300) return 1.0;
  return 1.0 - kelvin_b(r) / r;
}

SeriesLaw::SeriesLaw(std::string name, ParameterValues parameters, std::optional<double> spring,
                     std::vector<CreepElement> elements)
    : name_(std::move(name)),
      parameters_(std::move(parameters)),
      spring_(spring),
      elements_(std::move(elements)) {
  assert(!elements_.empty() && elements_.size() <= static_cast<std::size_t>(kMaxInternal));
}

bool SeriesLaw::is_linear() const {
  for (const auto& e : elements_)
    if (e.kind == CreepElement::Kind::bingham) return false;
  return true;
}

double SeriesLaw::linear_limit() const {
  double lim = std::numeric_limits<double>::infinity();
  for (const auto& e : elements_)
    if (e.kind == CreepElement::Kind::bingham) lim = std::min(lim, e.threshold);
  return lim;
}

double SeriesLaw::lagged_step_limit(double k) const {
  // Lagged Kelvin step (the seed's eqs. 12-16): q' = q + b (F/E - q) with the
  // start force F = k (delta - q); an error is multiplied by 1 - b (k + E)/E per
  // step, b = 1 - exp(-dt E/eta): |1 - b (k + E)/E| < 1 <=> b < 2E/(k + E).
  // Lagged dashpot: q' = q + dt F/eta, error factor 1 - dt k/eta: dt < 2 eta/k.
  double lim = std::numeric_limits<double>::infinity();
  if (!(k > 0.0)) return lim;
  for (const auto& e : elements_) {
    if (e.kind == CreepElement::Kind::kelvin) {
      if (k > e.E && e.E > 0.0) lim = std::min(lim, -(e.eta / e.E) * std::log1p(-2.0 * e.E / (k + e.E)));
    } else {
      lim = std::min(lim, 2.0 * e.eta / k);
    }
  }
  return lim;
}

StepConstants SeriesLaw::step_constants(double dt, Scheme scheme) const {
  // The coefficients of (2) in contact_rheology.hpp, per element and scheme
  // (rheology.md, "three schemes"; docs/reference/laws.md, "Schemes"):
  //   Kelvin  eta q' + E q = F, exact over the step for the scheme's force:
  //           q' = a q + b F_s/E + (F_e - F_s) phi/E,  a = 1 - b  (exponential-linear)
  //           lagged: F = F_s throughout (the seed's eqs. 12-16 in state form,
  //           omega = F/E - q); implicit: F = F_e throughout.
  //   dashpot eta q' = F: rectangle rule at F_s (lagged) or F_e (implicit),
  //           trapezoid (exponential-linear).
  //   Bingham eta q' = g(F): as the dashpot, with g(F) = sign(F)<|F| - Fs>.
  StepConstants k;
  k.dt = dt;
  k.scheme = scheme;
  k.count = static_cast<int>(elements_.size());
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    const auto& e = elements_[i];
    auto& u = k.unit[i];
    u.dt_over_eta = dt / e.eta;
    if (e.kind == CreepElement::Kind::kelvin) {
      const double r = dt * e.E / e.eta;  // dt / retardation time
      u.b = kelvin_b(r);
      u.phi = kelvin_phi(r);
      u.per_q = -u.b;
      switch (scheme) {
        case Scheme::lagged: u.per_start = u.b / e.E; break;
        case Scheme::implicit: u.per_end = u.b / e.E; break;
        case Scheme::exponential_linear:
          u.per_start = (u.b - u.phi) / e.E;
          u.per_end = u.phi / e.E;
          break;
      }
    } else {
      u.bingham = e.kind == CreepElement::Kind::bingham;
      u.threshold = u.bingham ? e.threshold : 0.0;
      switch (scheme) {
        case Scheme::lagged: u.per_start = u.dt_over_eta; break;
        case Scheme::implicit: u.per_end = u.dt_over_eta; break;
        case Scheme::exponential_linear:
          u.per_start = 0.5 * u.dt_over_eta;
          u.per_end = 0.5 * u.dt_over_eta;
          break;
      }
    }
  }
  return k;
}

namespace {
// Bingham flow function g(F) = sign(F) <|F| - Fs> [force].
inline double bingham_excess(double f, double threshold) {
  if (f > threshold) return f - threshold;
  if (f < -threshold) return f + threshold;
  return 0.0;
}
// g(F) of an element: F itself for Kelvin and dashpot, the excess for Bingham.
inline double flow(const UnitStepConstants& u, double f) {
  return u.bingham ? bingham_excess(f, u.threshold) : f;
}
}  // namespace

Linearization SeriesLaw::linearize(const StepConstants& k, const RheologyState& old, double fs,
                                   double fe_guess) const {
  // Delta d_c = sum_i per_q q_i + per_start g(F_s) + per_end g(F_e) = h + c F_e,
  // where a Bingham g(F_e) is replaced by its affine piece at the guess.
  Linearization sum;
  for (int i = 0; i < k.count; ++i) {
    const auto idx = static_cast<std::size_t>(i);
    const auto& u = k.unit[idx];
    sum.h += u.per_q * old.q[idx] + u.per_start * flow(u, fs);
    if (!u.bingham) {
      sum.c += u.per_end;
    } else if (fe_guess > u.threshold) {
      sum.h -= u.per_end * u.threshold;
      sum.c += u.per_end;
    } else if (fe_guess < -u.threshold) {
      sum.h += u.per_end * u.threshold;
      sum.c += u.per_end;
    }
  }
  return sum;
}

double SeriesLaw::advance(const StepConstants& k, const RheologyState& old, double fs, double fe,
                          RheologyState& next) const {
  // The hot path (one call per contact and step): a few multiply-adds per
  // element from constants computed once per step by step_constants().
  double total = 0.0;
  for (int i = 0; i < kMaxInternal; ++i) {
    const auto idx = static_cast<std::size_t>(i);
    if (i >= k.count) {
      next.q[idx] = old.q[idx];
      continue;
    }
    const auto& u = k.unit[idx];
    const double dq = u.per_q * old.q[idx] + u.per_start * flow(u, fs) + u.per_end * flow(u, fe);
    next.q[idx] = old.q[idx] + dq;
    total += dq;
  }
  return total;
}

double SeriesLaw::creep_closed_form(double force, double t) const {
  double d = 0.0;
  for (const auto& e : elements_) {
    switch (e.kind) {
      case CreepElement::Kind::kelvin: d += force / e.E * kelvin_b(e.E * t / e.eta); break;
      case CreepElement::Kind::dashpot: d += force * t / e.eta; break;
      case CreepElement::Kind::bingham: d += bingham_excess(force, e.threshold) * t / e.eta; break;
    }
  }
  return d;
}

}  // namespace rheodda::laws
