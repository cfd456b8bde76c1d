// Nonlinear laws: power-law (Norton) creep of the joint shear, alone or in
// series with a Kelvin element, and with Kachanov-Rabotnov damage that makes
// creep accelerate to failure in finite time (docs/reference/laws.md, "power-law",
// "power-law-burgers", "damage-burgers").
//
// Why one class. The three laws are the same series: a spring E1, an optional
// Kelvin element (E2, eta2) and a Norton dashpot whose rate is
//     q_N' = A sign(tau) (|tau| / (tau_ref (1 - D)))^n                    (N)
// with the damage D of Kachanov (1958) and Rabotnov (1969), evolving as
//     D' = (|tau| / (tau_ref (1 - D)))^r / ((r + 1) t_r)                  (K)
// (Lemaitre & Chaboche, "Mechanics of Solid Materials", 1990, sec. 7.3;
// "power-law" and "power-law-burgers" have no damage, D = 0). Under a
// constant stress (K) integrates in closed form: X = (1 - D)^(r+1) decreases
// linearly, X(t) = 1 - t/t_f, and the law fails (D = 1) at
//     t_f = t_r (tau_ref / |tau|)^r                                       (F)
// (Kachanov's rupture time). The creep of (N) is then
//     q_N(t) = A s^n t_f [1 - (1 - t/t_f)^p] / p,  s = |tau|/tau_ref,
//     p = 1 - n/(r + 1)   (-A s^n t_f ln(1 - t/t_f) when p = 0),          (C)
// and without damage (t_r = infinity) Norton's q_N = A s^n t, linear in time.
//
// Schemes. The Kelvin element integrates as in SeriesLaw (exact for the
// scheme's force). The Norton dashpot and the damage integrate exactly under a
// force held constant over the step at F_bar = F_s (lagged), F_e (implicit) or
// (F_s + F_e)/2 (exponential-linear: the midpoint rule, 2nd order): with
// kappa = s^r / t_r, X_e = X_s - kappa dt and
//     Delta q_N = A g(F_bar) dt X_s^(-m) psi(u),  m = n/(r + 1),
//     u = kappa dt / X_s,  psi(u) = (1 - (1 - u)^p) / (p u)              (S)
// (psi = -ln(1 - u)/u at p = 0, psi = 1 without damage), the integral of (N)
// along (K). A staged (piecewise-constant) force history is therefore
// integrated exactly by the lagged and implicit schemes at any step.
#pragma once

#include <optional>
#include <string>

#include "rheodda/laws/contact_rheology.hpp"
#include "rheodda/laws/registry.hpp"

namespace rheodda::laws {

/// Spring E1 + optional Kelvin (E2, eta2) + Norton dashpot (A, tau_ref, n) with
/// optional Kachanov-Rabotnov damage (t_r, r). State: q[0] Kelvin (if any),
/// next slot the Norton dashpot, RheologyState::damage the damage D.
class PowerLawSeries : public ContactRheology {
 public:
  struct Kelvin {
    double E = 0.0;    ///< [stress/length]
    double eta = 0.0;  ///< [stress*time/length]
  };
  struct Damage {
    double t_r = 0.0;  ///< failure time at tau = tau_ref [time]
    double r = 0.0;    ///< damage exponent [-]
  };
  PowerLawSeries(std::string name, ParameterValues parameters, double E1,
                 std::optional<Kelvin> kelvin, double A, double tau_ref, double n,
                 std::optional<Damage> damage);

  std::string_view name() const override { return name_; }
  const ParameterValues& parameters() const override { return parameters_; }
  int internal_count() const override { return kelvin_ ? 2 : 1; }
  std::optional<double> instantaneous_stiffness() const override { return E1_; }
  bool is_linear() const override { return false; }
  Linearity linearity() const override { return Linearity::nonlinear; }

  StepConstants step_constants(double dt, Scheme scheme) const override;
  /// Tangent (1') of the increment at force_end_guess (contact_rheology.hpp).
  Linearization linearize(const StepConstants& k, const RheologyState& old, double force_start,
                          double force_end_guess) const override;
  /// Advances q and D by (S). If D reaches 1 within the step, next.damage = 1
  /// and the Norton increment is the creep up to failure (infinite when p <= 0).
  double advance(const StepConstants& k, const RheologyState& old, double force_start,
                 double force_end, RheologyState& next) const override;
  /// (C) plus the Kelvin creep; at and after t_f: the creep at failure (infinite when p <= 0).
  double creep_closed_form(double force, double t) const override;
  std::optional<double> failure_time(double force) const override;
  double time_to_failure(const RheologyState& s, double force) const override;
  /// Lagged, implicit: X_s/kappa(F_bar). Exponential-linear: the sub-step theta
  /// whose own midpoint force F_s + (F_e - F_s) theta/(2 dt) fails at its end,
  /// kappa theta = X_s (bisection to round-off).
  std::optional<double> failure_in_step(const StepConstants& k, const RheologyState& old,
                                        double force_start, double force_end) const override;

  /// Norton dashpot rate at stress tau on an intact joint: A sign(tau) (|tau|/tau_ref)^n [length/time].
  double norton_rate(double tau) const;

 private:
  /// Delta q_N over a step dt at constant force f from damage d (S), and its
  /// derivative d(Delta q_N)/df [length/force]; sets the damage at the step end.
  double norton_step(double dt, double f, double d, double* derivative, double* d_end) const;

  std::string name_;
  ParameterValues parameters_;
  double E1_;
  std::optional<Kelvin> kelvin_;
  double A_, tau_ref_, n_;
  std::optional<Damage> damage_;
};

/// "power-law": spring E1 in series with a Norton dashpot, rate A (tau/tau_ref)^n.
class PowerLaw final : public PowerLawSeries {
 public:
  explicit PowerLaw(const ParameterValues& p);
  static LawInfo info();
};

/// "power-law-burgers": spring E1 + Kelvin (E2, eta2) + Norton dashpot (A, tau_ref, n).
class PowerLawBurgers final : public PowerLawSeries {
 public:
  explicit PowerLawBurgers(const ParameterValues& p);
  static LawInfo info();
};

/// "damage-burgers": power-law Burgers whose Norton dashpot carries Kachanov-Rabotnov
/// damage (t_r, r): tertiary creep and failure at t_f = t_r (tau_ref/|tau|)^r.
class DamageBurgers final : public PowerLawSeries {
 public:
  explicit DamageBurgers(const ParameterValues& p);
  static LawInfo info();
};

}  // namespace rheodda::laws
