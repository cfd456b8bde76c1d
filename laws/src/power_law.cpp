#include "rheodda/laws/power_law.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "rheodda/laws/series_law.hpp"

namespace rheodda::laws {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

double at(const ParameterValues& p, const char* key) { return p.find(key)->second; }

// Largest fraction of the remaining life X_s a Newton tangent is taken at: a
// guess past failure (u >= 1) is tangent-linearized just before it, where the
// increment and its slope are still finite (the host then sees the failure in
// advance(); power_law.hpp).
constexpr double kTangentCap = 1.0 - 1e-9;

/// psi(u) = (1 - (1 - u)^p)/(p u) of (S), -ln(1 - u)/u at p = 0, 1 at u = 0,
/// through expm1/log1p so that u -> 0 keeps full precision [-].
double psi(double u, double p) {
  if (u == 0.0) return 1.0;
  const double l = std::log1p(-u);  // ln(1 - u)
  if (p == 0.0) return -l / u;
  return -std::expm1(p * l) / (p * u);
}
}  // namespace

PowerLawSeries::PowerLawSeries(std::string name, ParameterValues parameters, double E1,
                               std::optional<Kelvin> kelvin, double A, double tau_ref, double n,
                               std::optional<Damage> damage)
    : name_(std::move(name)),
      parameters_(std::move(parameters)),
      E1_(E1),
      kelvin_(kelvin),
      A_(A),
      tau_ref_(tau_ref),
      n_(n),
      damage_(damage) {}

double PowerLawSeries::norton_rate(double tau) const {
  return A_ * std::copysign(std::pow(std::abs(tau) / tau_ref_, n_), tau);
}

StepConstants PowerLawSeries::step_constants(double dt, Scheme scheme) const {
  // unit[0]: the Kelvin element's coefficients of (2) in contact_rheology.hpp,
  // as in SeriesLaw::step_constants (exact for the scheme's force). The Norton
  // dashpot needs only dt and the scheme (its step is (S), power_law.hpp).
  StepConstants k;
  k.dt = dt;
  k.scheme = scheme;
  k.count = internal_count();
  if (kelvin_) {
    auto& u = k.unit[0];
    const double r = dt * kelvin_->E / kelvin_->eta;
    u.b = kelvin_b(r);
    u.phi = kelvin_phi(r);
    u.per_q = -u.b;
    switch (scheme) {
      case Scheme::lagged: u.per_start = u.b / kelvin_->E; break;
      case Scheme::implicit: u.per_end = u.b / kelvin_->E; break;
      case Scheme::exponential_linear:
        u.per_start = (u.b - u.phi) / kelvin_->E;
        u.per_end = u.phi / kelvin_->E;
        break;
    }
  }
  auto& nu = k.unit[kelvin_ ? 1 : 0];
  nu.dt_over_eta = dt;  // the Norton dashpot's step: dt [time]
  return k;
}

double PowerLawSeries::norton_step(double dt, double f, double d, double* derivative,
                                   double* d_end) const {
  // (S) in power_law.hpp: the Norton dashpot (N) along the damage (K) at a
  // constant force f over dt, from damage d. X = (1 - D)^(r+1), m = n/(r+1),
  // p = 1 - m, kappa = s^r/t_r, u = kappa dt/X_s.
  const double s = std::abs(f) / tau_ref_;
  const double sn = std::pow(s, n_);  // (|f|/tau_ref)^n
  // d(sn)/df / sign(f) = n s^(n-1)/tau_ref; n >= 1, and at f = 0 only n = 1 has a slope.
  const double dsn = s > 0.0 ? n_ * sn / std::abs(f) : (n_ == 1.0 ? 1.0 / tau_ref_ : 0.0);
  if (!damage_) {
    if (derivative) *derivative = A_ * dt * dsn;
    if (d_end) *d_end = 0.0;
    return A_ * dt * std::copysign(sn, f);
  }
  const double r = damage_->r, r1 = r + 1.0;
  const double m = n_ / r1, p = 1.0 - m;
  const double xs = std::pow(1.0 - d, r1);
  const double kappa = std::pow(s, r) / damage_->t_r;
  const double u = xs > 0.0 ? kappa * dt / xs : kInf;
  if (u >= 1.0) {
    // Failure within the step: D reaches 1 after X_s/kappa. The creep up to it
    // is A g(f) X_s^p/(kappa p) for p > 0 and infinite for p <= 0.
    if (d_end) *d_end = 1.0;
    if (derivative) {
      // Newton tangent just before failure (kTangentCap): finite, steep.
      const double uc = kTangentCap;
      const double scale = A_ * dt * std::pow(xs, -m);
      *derivative = scale * dsn / n_ * ((n_ - r) * psi(uc, p) + r * std::pow(1.0 - uc, p - 1.0));
      // The value the tangent goes through is the one at the cap.
      return scale * std::copysign(sn, f) * psi(uc, p);
    }
    if (!(p > 0.0) || xs <= 0.0) return std::copysign(kInf, f);
    return A_ * std::copysign(sn, f) * std::pow(xs, p) / (kappa * p);
  }
  if (d_end) *d_end = 1.0 - std::pow(xs - kappa * dt, 1.0 / r1);  // X_e = X_s - kappa dt
  const double scale = A_ * dt * std::pow(xs, -m);
  const double ps = psi(u, p);
  if (derivative) {
    // d/df [A g(f) dt X_s^-m psi(u)] with du/df = u r/f:
    // A dt X_s^-m (|f|/tau_ref)^n/|f| [(n - r) psi + r (1 - u)^(p-1)]
    // (u psi'(u) = (1 - u)^(p-1) - psi); dsn/n = (|f|/tau_ref)^n/|f|.
    *derivative = scale * dsn / n_ * ((n_ - r) * ps + r * std::pow(1.0 - u, p - 1.0));
  }
  return scale * std::copysign(sn, f) * ps;
}

Linearization PowerLawSeries::linearize(const StepConstants& k, const RheologyState& old,
                                        double fs, double fe_guess) const {
  // Tangent (1') of Delta d_c(F_e) = Kelvin part (affine, (2)) + Norton part
  // Delta q_N(F_bar(F_e)), F_bar = F_s, F_e or (F_s + F_e)/2 by scheme.
  Linearization lin;
  if (kelvin_) {
    const auto& u = k.unit[0];
    lin.h += u.per_q * old.q[0] + u.per_start * fs;
    lin.c += u.per_end;
  }
  double weight = 0.0, f_bar = fs;  // dF_bar/dF_e and F_bar at the guess
  switch (k.scheme) {
    case Scheme::lagged: weight = 0.0; f_bar = fs; break;
    case Scheme::implicit: weight = 1.0; f_bar = fe_guess; break;
    case Scheme::exponential_linear: weight = 0.5; f_bar = 0.5 * (fs + fe_guess); break;
  }
  double slope = 0.0;
  const double dq = norton_step(k.dt, f_bar, old.damage, &slope, nullptr);
  const double c = weight * slope;
  lin.h += dq - c * fe_guess;
  lin.c += c;
  return lin;
}

double PowerLawSeries::advance(const StepConstants& k, const RheologyState& old, double fs,
                               double fe, RheologyState& next) const {
  next = old;
  double total = 0.0;
  int slot = 0;
  if (kelvin_) {
    const auto& u = k.unit[0];
    const double dq = u.per_q * old.q[0] + u.per_start * fs + u.per_end * fe;
    next.q[0] = old.q[0] + dq;
    total += dq;
    slot = 1;
  }
  double f_bar = fs;
  switch (k.scheme) {
    case Scheme::lagged: f_bar = fs; break;
    case Scheme::implicit: f_bar = fe; break;
    case Scheme::exponential_linear: f_bar = 0.5 * (fs + fe); break;
  }
  double d_end = 0.0;
  const double dq = norton_step(k.dt, f_bar, old.damage, nullptr, &d_end);
  next.q[static_cast<std::size_t>(slot)] = old.q[static_cast<std::size_t>(slot)] + dq;
  next.damage = damage_ ? d_end : 0.0;
  return total + dq;
}

std::optional<double> PowerLawSeries::failure_time(double force) const {
  // (F): t_f = t_r (tau_ref/|tau|)^r.
  if (!damage_ || force == 0.0) return std::nullopt;
  return damage_->t_r * std::pow(tau_ref_ / std::abs(force), damage_->r);
}

double PowerLawSeries::time_to_failure(const RheologyState& s, double force) const {
  // X decreases at kappa = s^r/t_r: X_s/kappa left (K).
  if (!damage_) return kInf;
  if (s.failed()) return 0.0;
  const double kappa = std::pow(std::abs(force) / tau_ref_, damage_->r) / damage_->t_r;
  if (!(kappa > 0.0)) return kInf;
  return std::pow(1.0 - s.damage, damage_->r + 1.0) / kappa;
}

std::optional<double> PowerLawSeries::failure_in_step(const StepConstants& k,
                                                      const RheologyState& old, double fs,
                                                      double fe) const {
  if (!damage_) return std::nullopt;
  if (old.failed()) return 0.0;
  const double xs = std::pow(1.0 - old.damage, damage_->r + 1.0);
  // kappa(F) theta - X_s: the damage of a sub-step theta at force F (K).
  auto excess = [&](double f, double theta) {
    return std::pow(std::abs(f) / tau_ref_, damage_->r) / damage_->t_r * theta - xs;
  };
  if (k.scheme != Scheme::exponential_linear) {
    const double f = k.scheme == Scheme::lagged ? fs : fe;
    const double ttf = time_to_failure(old, f);
    if (ttf <= k.dt) return ttf;
    return std::nullopt;
  }
  auto mid = [&](double theta) { return fs + 0.5 * (fe - fs) * theta / k.dt; };
  if (excess(mid(k.dt), k.dt) < 0.0) return std::nullopt;
  double lo = 0.0, hi = k.dt;  // excess(lo) < 0 <= excess(hi)
  for (int i = 0; i < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * hi; ++i) {
    const double m = 0.5 * (lo + hi);
    (excess(mid(m), m) < 0.0 ? lo : hi) = m;
  }
  return hi;
}

double PowerLawSeries::creep_closed_form(double force, double t) const {
  double d = 0.0;
  if (kelvin_) d += force / kelvin_->E * kelvin_b(kelvin_->E * t / kelvin_->eta);
  if (!damage_ || force == 0.0) return d + norton_rate(force) * t;  // Norton: linear in t
  // (C): q_N = A s^n t_f [1 - (1 - t/t_f)^p]/p = A g(F) t psi(t/t_f) (S with X_s = 1, u = t/t_f).
  const double tf = *failure_time(force);
  const double p = 1.0 - n_ / (damage_->r + 1.0);
  if (t >= tf) return d + (p > 0.0 ? norton_rate(force) * tf / p : std::copysign(kInf, force));
  return d + norton_rate(force) * t * psi(t / tf, p);
}

// ---- The registered laws ------------------------------------------------------
namespace {
ParameterSpec spec(std::string name, std::string unit, std::string meaning, double min = 0.0,
                   bool exclusive = true, double max = std::numeric_limits<double>::max()) {
  ParameterSpec s{std::move(name), std::move(unit), std::move(meaning), min, exclusive};
  s.max = max;
  return s;
}
std::vector<ParameterSpec> norton_specs() {
  return {spec("A", "length/time", "Norton creep rate at tau = tau_ref"),
          spec("tau_ref", "stress", "reference shear stress of the Norton law"),
          spec("n", "-", "Norton stress exponent (1: a linear dashpot of viscosity tau_ref/A)", 1.0,
               false, 100.0)};
}
/// The Burgers-like laws' parameters: the spring E1 and the Kelvin element (E2, eta2),
/// then the Norton dashpot's.
std::vector<ParameterSpec> burgers_norton_specs() {
  auto specs = norton_specs();
  specs.insert(specs.begin(),
               {spec("E1", "stress/length", "instantaneous (elastic) shear stiffness"),
                spec("E2", "stress/length", "delayed-elastic (Kelvin) shear stiffness"),
                spec("eta2", "stress*time/length", "viscosity of the Kelvin dashpot")});
  return specs;
}
template <class Law>
LawInfo info_of(std::string name, std::string summary, std::string equation,
                std::vector<ParameterSpec> specs) {
  LawInfo info{std::move(name), std::move(summary), std::move(equation), std::move(specs), {}};
  info.make = [](const ParameterValues& p) -> std::unique_ptr<ContactRheology> {
    return std::make_unique<Law>(p);
  };
  // rheodda fit's models are the linear series laws'; A and tau_ref would also
  // enter a fit only as A/tau_ref^n (docs/reference/laws.md).
  info.fittable = false;
  return info;
}
}  // namespace

PowerLaw::PowerLaw(const ParameterValues& p)
    : PowerLawSeries("power-law", p, at(p, "E1"), std::nullopt, at(p, "A"), at(p, "tau_ref"),
                     at(p, "n"), std::nullopt) {}

LawInfo PowerLaw::info() {
  auto specs = norton_specs();
  specs.insert(specs.begin(),
               spec("E1", "stress/length", "instantaneous (elastic) shear stiffness"));
  return info_of<PowerLaw>("power-law",
                           "spring E1 in series with a Norton dashpot: rate A*(F/tau_ref)^n",
                           "d(t) = F/E1 + A*(F/tau_ref)^n*t", std::move(specs));
}

PowerLawBurgers::PowerLawBurgers(const ParameterValues& p)
    : PowerLawSeries("power-law-burgers", p, at(p, "E1"), Kelvin{at(p, "E2"), at(p, "eta2")},
                     at(p, "A"), at(p, "tau_ref"), at(p, "n"), std::nullopt) {}

LawInfo PowerLawBurgers::info() {
  auto specs = burgers_norton_specs();
  return info_of<PowerLawBurgers>(
      "power-law-burgers",
      "spring E1 + Kelvin (E2 || eta2) + Norton dashpot (rate A*(F/tau_ref)^n) in series",
      "d(t) = F/E1 + F/E2*(1 - exp(-E2*t/eta2)) + A*(F/tau_ref)^n*t", std::move(specs));
}

DamageBurgers::DamageBurgers(const ParameterValues& p)
    : PowerLawSeries("damage-burgers", p, at(p, "E1"), Kelvin{at(p, "E2"), at(p, "eta2")},
                     at(p, "A"), at(p, "tau_ref"), at(p, "n"), Damage{at(p, "t_r"), at(p, "r")}) {}

LawInfo DamageBurgers::info() {
  auto specs = burgers_norton_specs();
  specs.push_back(spec("t_r", "time", "failure (rupture) time under tau = tau_ref"));
  specs.push_back(spec("r", "-", "Kachanov damage exponent: t_f = t_r*(tau_ref/F)^r", 0.0, true,
                       100.0));
  return info_of<DamageBurgers>(
      "damage-burgers",
      "power-law Burgers whose Norton dashpot carries Kachanov-Rabotnov damage D "
      "(rate A*(F/(tau_ref*(1-D)))^n, D' = (F/(tau_ref*(1-D)))^r/((r+1)*t_r))",
      "d(t) = F/E1 + F/E2*(1 - exp(-E2*t/eta2)) + A*(F/tau_ref)^n*t_f*(1 - (1 - t/t_f)^p)/p, "
      "p = 1 - n/(r+1), failure at t_f = t_r*(tau_ref/F)^r",
      std::move(specs));
}

}  // namespace rheodda::laws
