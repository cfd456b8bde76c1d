#include "rheodda/laws/series_law.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "rheodda/laws/parameters.hpp"

namespace rheodda::laws {

std::string_view scheme_name(Scheme s) {
  switch (s) {
    case Scheme::lagged: return "lagged";
    case Scheme::implicit: return "implicit";
    case Scheme::exponential_linear: return "exponential-linear";
  }
  return "?";
}

Scheme parse_scheme(std::string_view name) {
  if (name == "lagged") return Scheme::lagged;
  if (name == "implicit") return Scheme::implicit;
  if (name == "exponential-linear") return Scheme::exponential_linear;
  throw LawError("scheme", "unknown integration scheme '" + std::string(name) +
                               "'; use one of: lagged, implicit, exponential-linear");
}

double ContactRheology::displacement_closed_form(double force, double t) const {
  const auto e1 = instantaneous_stiffness();
  return (e1 ? force / *e1 : 0.0) + creep_closed_form(force, t);
}

std::optional<double> ContactRheology::relaxation_modulus(double) const { return std::nullopt; }

double ContactRheology::linear_limit() const { return std::numeric_limits<double>::infinity(); }

double kelvin_b(double r) { return -std::expm1(-r); }

double kelvin_phi(double r) {
  // phi = 1 - (1 - e^-r)/r = (r - 1 + e^-r)/r. Direct evaluation cancels for
  // small r; the Taylor series r/2 - r^2/6 + r^3/24 - r^4/120 is exact to
  // round-off below 1e-3 (next term r^5/720 < 1.4e-18 relative to r/2).
  if (r < 1e-3) return r * (0.5 - r * (1.0 / 6.0 - r * (1.0 / 24.0 - r / 120.0)));
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

StepConstants SeriesLaw::step_constants(double dt, Scheme scheme) const {
  StepConstants k;
  k.dt = dt;
  k.scheme = scheme;
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    const auto& e = elements_[i];
    auto& u = k.unit[i];
    u.dt_over_eta = dt / e.eta;
    if (e.kind == CreepElement::Kind::kelvin) {
      const double r = dt * e.E / e.eta;  // dt / retardation time
      u.b = kelvin_b(r);
      u.phi = kelvin_phi(r);
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
}  // namespace

Linearization SeriesLaw::element_step(int i, const StepConstants& k, double q, double fs,
                                      double fe_guess) const {
  const auto& e = elements_[static_cast<std::size_t>(i)];
  const auto& u = k.unit[static_cast<std::size_t>(i)];
  switch (e.kind) {
    case CreepElement::Kind::kelvin:
      // Exact exponential update of eta q' + E q = F over the step
      // (rheology.md; the seed's eqs. 12-16 in state form: omega = F/E - q):
      //   q' = a q + b F_s/E + (F_e - F_s) phi/E,   a = 1 - b.
      switch (k.scheme) {
        case Scheme::lagged: return {u.b * (fs / e.E - q), 0.0};
        case Scheme::implicit: return {-u.b * q, u.b / e.E};
        case Scheme::exponential_linear:
          return {-u.b * q + (u.b - u.phi) * fs / e.E, u.phi / e.E};
      }
      break;
    case CreepElement::Kind::dashpot:
      // q' = q + integral F dt / eta: rectangle (lagged, implicit) or trapezoid.
      switch (k.scheme) {
        case Scheme::lagged: return {fs * u.dt_over_eta, 0.0};
        case Scheme::implicit: return {0.0, u.dt_over_eta};
        case Scheme::exponential_linear: return {0.5 * fs * u.dt_over_eta, 0.5 * u.dt_over_eta};
      }
      break;
    case CreepElement::Kind::bingham: {
      // q' = q + integral g(F) dt / eta; the piece of g is chosen by the guess.
      auto piece = [&](double weight) -> Linearization {
        if (fe_guess > e.threshold) return {-weight * e.threshold, weight};
        if (fe_guess < -e.threshold) return {weight * e.threshold, weight};
        return {0.0, 0.0};
      };
      switch (k.scheme) {
        case Scheme::lagged: return {bingham_excess(fs, e.threshold) * u.dt_over_eta, 0.0};
        case Scheme::implicit: return piece(u.dt_over_eta);
        case Scheme::exponential_linear: {
          Linearization l = piece(0.5 * u.dt_over_eta);
          l.h += 0.5 * bingham_excess(fs, e.threshold) * u.dt_over_eta;
          return l;
        }
      }
      break;
    }
  }
  return {};
}

Linearization SeriesLaw::linearize(const StepConstants& k, const RheologyState& old, double fs,
                                   double fe_guess) const {
  Linearization sum;
  for (int i = 0; i < static_cast<int>(elements_.size()); ++i) {
    const Linearization l = element_step(i, k, old.q[static_cast<std::size_t>(i)], fs, fe_guess);
    sum.h += l.h;
    sum.c += l.c;
  }
  return sum;
}

double SeriesLaw::advance(const StepConstants& k, const RheologyState& old, double fs, double fe,
                          RheologyState& next) const {
  next = old;
  double total = 0.0;
  for (int i = 0; i < static_cast<int>(elements_.size()); ++i) {
    const auto idx = static_cast<std::size_t>(i);
    const Linearization l = element_step(i, k, old.q[idx], fs, fe);
    const double dq = l.h + l.c * fe;
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
