// The nonlinear laws (laws/power_law.hpp): power-law (Norton), power-law
// Burgers and damage-burgers (Kachanov-Rabotnov damage, failure in finite
// time). Closed forms at constant stress, an RK4 reference under staged
// stress, the Newton tangent and its quadratic convergence, stability over
// n = 1..20, stress ratio and step, and the failure time's convergence.
// Units MPa, mm, h (per unit joint area).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "rheodda/laws/history.hpp"
#include "rheodda/laws/power_law.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {

// Table 1 row 1's springs and Kelvin element; the Norton dashpot's A = tau_ref/eta1,
// so that n = 1 is the Burgers law of that row.
constexpr double kE1 = 26.87, kE2 = 192.43, kEta2 = 2141.23, kEta1 = 34807.72;  // MPa/mm, MPa h/mm
constexpr double kTauRef = 0.2, kA = kTauRef / kEta1;                            // MPa, mm/h
constexpr double kTr = 1000.0, kR = 3.0;                                         // h, -

ParameterValues norton(double n) { return {{"E1", kE1}, {"A", kA}, {"tau_ref", kTauRef}, {"n", n}}; }
ParameterValues norton_burgers(double n) {
  auto p = norton(n);
  p["E2"] = kE2;
  p["eta2"] = kEta2;
  return p;
}
ParameterValues damage(double n, double r = kR) {
  auto p = norton_burgers(n);
  p["t_r"] = kTr;
  p["r"] = r;
  return p;
}

/// Reference: RK4 with `sub` substeps per unit time of q_K, q_N, D (power_law.hpp
/// (N), (K)) under a staged force; returns the creep (q_K + q_N) and D at t_end.
struct Rk4Result { double creep, damage; };
Rk4Result rk4(const ParameterValues& p, bool kelvin, bool with_damage, const StagedHistory& force,
              double t_end, int steps) {
  const double A = p.at("A"), tr = p.at("tau_ref"), n = p.at("n");
  const double E2 = kelvin ? p.at("E2") : 0.0, eta2 = kelvin ? p.at("eta2") : 1.0;
  const double t_r = with_damage ? p.at("t_r") : 0.0, r = with_damage ? p.at("r") : 0.0;
  double y[3] = {0.0, 0.0, 0.0};  // q_K, q_N, D
  auto rates = [&](double f, const double* s, double* dy) {
    const double x = std::abs(f) / (tr * (1.0 - s[2]));
    dy[0] = kelvin ? (f - E2 * s[0]) / eta2 : 0.0;
    dy[1] = A * std::copysign(std::pow(x, n), f);
    dy[2] = with_damage ? std::pow(x, r) / ((r + 1.0) * t_r) : 0.0;
  };
  // Integrate stage by stage so that no RK4 step straddles a force change.
  std::vector<double> bounds{0.0};
  for (const auto& s : force.stages())
    if (s.t > 0.0 && s.t < t_end) bounds.push_back(s.t);
  bounds.push_back(t_end);
  for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
    const double f = force.at(bounds[b]);
    const double h = (bounds[b + 1] - bounds[b]) / steps;
    for (int i = 0; i < steps; ++i) {
      double k1[3], k2[3], k3[3], k4[3], t[3];
      rates(f, y, k1);
      for (int j = 0; j < 3; ++j) t[j] = y[j] + 0.5 * h * k1[j];
      rates(f, t, k2);
      for (int j = 0; j < 3; ++j) t[j] = y[j] + 0.5 * h * k2[j];
      rates(f, t, k3);
      for (int j = 0; j < 3; ++j) t[j] = y[j] + h * k3[j];
      rates(f, t, k4);
      for (int j = 0; j < 3; ++j) y[j] += h / 6.0 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
  }
  return {y[0] + y[1], y[2]};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(power_law)

BOOST_AUTO_TEST_CASE(norton_creep_is_linear_in_time_and_power_law_burgers_adds_the_kelvin_curve) {
  // Constant stress: q_N = A (tau/tau_ref)^n t; the schemes integrate a constant
  // force exactly, so every scheme and step meets the closed form.
  for (double n : {1.0, 3.0, 8.0, 20.0})
    for (double tau : {0.05, 0.2, 0.3})
      for (Scheme s : all_schemes())
        for (double dt : {0.1, 10.0, 1000.0}) {
          BOOST_TEST_CONTEXT("n " << n << ", tau " << tau << ", " << scheme_name(s) << ", dt " << dt) {
            const auto pl = make("power-law", norton(n));
            const auto pb = make("power-law-burgers", norton_burgers(n));
            const double t_end = 2000.0;
            const double norton_d = kA * std::pow(tau / kTauRef, n) * t_end;
            const double kelvin_d = tau / kE2 * -std::expm1(-kE2 * t_end / kEta2);
            const double dl = integrate_force_function(*pl, [&](double) { return tau; }, t_end, dt, s);
            const double db = integrate_force_function(*pb, [&](double) { return tau; }, t_end, dt, s);
            BOOST_TEST(rel(pl->creep_closed_form(tau, t_end), norton_d) <= 1e-14);
            BOOST_TEST(rel(dl, tau / kE1 + norton_d) <= 1e-12);
            BOOST_TEST(rel(db, tau / kE1 + kelvin_d + norton_d) <= 1e-12);
            // Odd in the force: a reversed stress creeps the other way.
            BOOST_TEST(rel(pl->creep_closed_form(-tau, t_end), -norton_d) <= 1e-14);
          }
        }
}

BOOST_AUTO_TEST_CASE(power_law_burgers_with_n_1_is_the_burgers_law) {
  const auto pb = make("power-law-burgers", norton_burgers(1.0));
  const auto b = make("burgers", {{"E1", kE1}, {"E2", kE2}, {"eta1", kEta1}, {"eta2", kEta2}});
  for (double t : {1.0, 100.0, 5000.0})
    BOOST_TEST(rel(pb->displacement_closed_form(0.232, t), b->displacement_closed_form(0.232, t)) <= 1e-14);
  // Under a force ramp the three schemes step exactly as Burgers' do.
  for (Scheme s : all_schemes()) {
    const auto ramp = [](double t) { return 0.001 * t; };
    const double x = integrate_force_function(*pb, ramp, 500.0, 7.0, s);
    const double y = integrate_force_function(*b, ramp, 500.0, 7.0, s);
    BOOST_TEST(rel(x, y) <= 1e-12, scheme_name(s) << ": " << x << " vs burgers " << y);
  }
}

BOOST_AUTO_TEST_CASE(damage_burgers_meets_its_closed_form_and_fails_at_kachanovs_time) {
  // (C): q_N = A s^n t_f [1 - (1 - t/t_f)^p]/p, t_f = t_r (tau_ref/tau)^r (F).
  for (double n : {1.0, 3.0, 4.0, 6.0})  // p = 1 - n/4: 0.75, 0.25, 0 (log), -0.5
    for (double tau : {0.1, 0.2, 0.4})
      for (Scheme s : all_schemes()) {
        BOOST_TEST_CONTEXT("n " << n << ", tau " << tau << ", " << scheme_name(s)) {
          const auto law = make("damage-burgers", damage(n));
          const double tf = kTr * std::pow(kTauRef / tau, kR);
          BOOST_TEST(rel(*law->failure_time(tau), tf) <= 1e-14);
          BOOST_TEST(rel(*law->failure_time(-tau), tf) <= 1e-14);
          const double p = 1.0 - n / (kR + 1.0);
          for (double frac : {0.1, 0.5, 0.9, 0.999}) {
            const double t = frac * tf;
            const double qn = kA * std::pow(tau / kTauRef, n) * tf *
                              (p == 0.0 ? -std::log1p(-frac) : -std::expm1(p * std::log1p(-frac)) / p);
            const double exact = tau / kE1 + tau / kE2 * -std::expm1(-kE2 * t / kEta2) + qn;
            BOOST_TEST(rel(law->displacement_closed_form(tau, t), exact) <= 1e-12);
            // Integrated in 37 steps (any step: a constant force is integrated exactly).
            const double d = integrate_force_function(*law, [&](double) { return tau; }, t, t / 37.0, s);
            BOOST_TEST(rel(d, exact) <= 1e-10, "t/t_f " << frac << ": " << d << " vs " << exact);
          }
          // The step that reaches t_f fails (damage 1), the one before does not.
          const StepConstants k = law->step_constants(0.5 * tf, s);
          RheologyState a, b;
          law->advance(k, a, tau, tau, b);
          BOOST_TEST(!b.failed());
          BOOST_TEST(rel(law->time_to_failure(b, tau), 0.5 * tf) <= 1e-12);
          RheologyState c;
          law->advance(law->step_constants(0.5 * tf * (1 + 1e-9), s), b, tau, tau, c);
          BOOST_TEST(c.failed());
        }
      }
}

BOOST_AUTO_TEST_CASE(a_law_curve_reports_the_damage_and_the_failure) {
  // Constant stress: D(t) = 1 - (1 - t/t_f)^(1/(r+1)) (power_law.hpp (K)) in
  // each sample of integrate_curve (what `rheodda law curve` runs), 1 from
  // the first sample at or after t_f.
  const auto law = make("damage-burgers", damage(3.0));
  const double tau = 0.25, tf = kTr * std::pow(kTauRef / tau, kR);
  const auto curve = integrate_curve(*law, Control::force, StagedHistory({{0.0, tau}}), 1.5 * tf,
                                     tf / 10.0, Scheme::implicit);
  int failed = 0;
  for (const auto& s : curve) {
    if (s.t < tf * (1 - 1e-12)) {
      const double exact = 1.0 - std::pow(1.0 - s.t / tf, 1.0 / (kR + 1.0));
      BOOST_TEST(std::abs(s.damage - exact) <= 1e-12, "t " << s.t);
    } else {
      BOOST_TEST(s.damage == 1.0, "t " << s.t);
      ++failed;
    }
  }
  BOOST_TEST(failed == 6);  // t_f, 1.1 t_f, ..., 1.5 t_f
}

BOOST_AUTO_TEST_CASE(staged_stress_matches_a_converged_rk4_reference_to_1e_6) {
  // Load, raise, reverse, unload: the lagged and implicit schemes integrate
  // each constant stage exactly; exponential-linear steps the stage starts as
  // ramps and converges at order 2 (checked at a fine step). Reference: RK4,
  // 20000 substeps per stage (its own change from 10000 is below 1e-12).
  const StagedHistory force({{0.0, 0.15}, {300.0, 0.25}, {500.0, -0.2}, {700.0, 0.0}});
  const double t_end = 900.0;
  struct Case { const char* name; ParameterValues p; bool kelvin, dmg; };
  const Case cases[] = {{"power-law", norton(5.0), false, false},
                        {"power-law-burgers", norton_burgers(5.0), true, false},
                        {"damage-burgers", damage(3.0), true, true}};
  for (const Case& c : cases) {
    const auto law = make(c.name, c.p);
    const Rk4Result ref = rk4(c.p, c.kelvin, c.dmg, force, t_end, 20000);
    const Rk4Result coarse = rk4(c.p, c.kelvin, c.dmg, force, t_end, 10000);
    BOOST_TEST(std::abs(ref.creep - coarse.creep) <= 1e-12 * std::abs(ref.creep));
    for (Scheme s : {Scheme::lagged, Scheme::implicit}) {
      const auto curve = integrate_curve(*law, Control::force, force, t_end, 25.0, s);
      const double creep = curve.back().displacement - force.at(t_end) / kE1;
      BOOST_TEST(rel(creep, ref.creep) <= 1e-6, c.name << " " << scheme_name(s) << ": " << creep
                                                       << " vs RK4 " << ref.creep);
    }
  }
}

BOOST_AUTO_TEST_CASE(the_tangent_is_the_derivative_of_the_step_increment) {
  // c of linearize() = d(Delta d_c)/dF_e, and h + c F_g = Delta d_c(F_g)
  // (contact_rheology.hpp (1')), against central differences.
  for (const char* name : {"power-law", "power-law-burgers", "damage-burgers"})
    for (double n : {1.0, 2.5, 7.0, 20.0})
      for (Scheme s : all_schemes())
        for (double fg : {0.03, 0.2, -0.35}) {
          BOOST_TEST_CONTEXT(name << " n " << n << " " << scheme_name(s) << " F " << fg) {
            const auto law = make(name, std::string(name) == "power-law" ? norton(n)
                                        : std::string(name) == "power-law-burgers" ? norton_burgers(n)
                                                                                   : damage(n));
            const StepConstants k = law->step_constants(5.0, s);
            RheologyState old;
            old.q[0] = 1e-4;
            old.damage = std::string(name) == "damage-burgers" ? 0.3 : 0.0;
            const double fs = 0.1;
            RheologyState next;
            const Linearization lin = law->linearize(k, old, fs, fg);
            const double d0 = law->advance(k, old, fs, fg, next);
            BOOST_TEST(rel(lin.h + lin.c * fg, d0) <= 1e-13);
            const double e = 1e-6 * std::abs(fg);
            const double dp = law->advance(k, old, fs, fg + e, next);
            const double dm = law->advance(k, old, fs, fg - e, next);
            const double fd = (dp - dm) / (2 * e);
            if (s == Scheme::lagged) BOOST_TEST(lin.c == 0.0);
            else BOOST_TEST(rel(lin.c, fd) <= 1e-6);
          }
        }
}

BOOST_AUTO_TEST_CASE(newton_on_the_series_force_converges_quadratically) {
  // A spring k = E1 in series with the law, displacement held: solve
  // R(F) = F - k (delta - q_old - Delta d_c(F)) = 0 by the host's Newton update
  // F_{j+1} = k (delta - q_old - h_j)/(1 + k c_j). Quadratic convergence:
  // e_{j+1}/e_j^2 stays bounded (here between 0.1x and 10x its first value)
  // while e falls by orders of magnitude, until round-off (1e-13 of F).
  for (const char* name : {"power-law", "damage-burgers"})
    for (double n : {3.0, 10.0}) {
      BOOST_TEST_CONTEXT(name << " n " << n) {
        const auto law = make(name, std::string(name) == "power-law" ? norton(n) : damage(n));
        // tau(0+) = 0.5 = 2.5 tau_ref; a step of 10 relaxation times tau0/(E1 rate(tau0)).
        const double delta = 0.5 / kE1;
        // (For the damage law at most half its failure time at tau0: a step
        // across failure has no solution.)
        double dt = 10.0 * 0.5 / (kE1 * kA * std::pow(0.5 / kTauRef, n));
        if (const auto tf = law->failure_time(0.5)) dt = std::min(dt, 0.5 * *tf);
        const StepConstants k = law->step_constants(dt, Scheme::implicit);
        RheologyState old;
        const double f_star = solve_series_force(*law, k, old, kE1, delta, kE1 * delta);
        // f* solves R = 0 to round-off
        RheologyState next;
        const double resid = f_star - kE1 * (delta - law->advance(k, old, kE1 * delta, f_star, next));
        BOOST_TEST(std::abs(resid) <= 1e-13 * f_star);
        std::vector<double> errors;
        double f = kE1 * delta;  // the host's first guess: the step-start stress
        for (int j = 0; j < 30; ++j) {
          const Linearization l = law->linearize(k, old, kE1 * delta, f);
          f = kE1 * (delta - l.h) / (1.0 + kE1 * l.c);
          const double e = std::abs(f - f_star) / f_star;
          if (e < 1e-13) break;
          errors.push_back(e);
        }
        BOOST_TEST_REQUIRE(errors.size() >= 3u);
        std::string ratios;
        // The ratios over the last three errors above round-off (the quadratic regime).
        const std::size_t m = errors.size();
        for (std::size_t j = m - 3; j + 1 < m; ++j) {
          const double ratio = errors[j + 1] / (errors[j] * errors[j]);
          ratios += " " + std::to_string(ratio);
          BOOST_TEST(errors[j + 1] < errors[j]);
          BOOST_TEST(ratio < 100.0);
        }
        // Digits double: the last error above round-off is below the square of the one before times 100.
        BOOST_TEST(errors[m - 1] <= 100.0 * errors[m - 2] * errors[m - 2]);
        BOOST_TEST_MESSAGE(name << " n " << n << ": " << m << " iterations above 1e-13, errors "
                                << errors[m - 3] << " " << errors[m - 2] << " " << errors[m - 1]
                                << ", e_{j+1}/e_j^2:" << ratios);
      }
    }
}

BOOST_AUTO_TEST_CASE(relaxation_is_stable_for_n_1_to_20_at_any_stress_ratio_and_step) {
  // Held displacement through the spring E1: tau(0+) = x tau_ref relaxes by
  // Norton creep. Implicit: tau stays in [0, tau_before] at every step
  // (monotone, no overshoot); exponential-linear (midpoint): |tau| never grows
  // (it may ring); over n = 1..20, x = 0.01..100 and the step over the
  // initial relaxation time t0 = tau / (E1 * rate(tau)) from 1e-3 to 1e6.
  int cases = 0;
  for (double n : {1.0, 2.0, 5.0, 10.0, 20.0})
    for (double x : {0.01, 1.0, 100.0})
      for (double step : {1e-3, 1.0, 1e3, 1e6}) {
        const auto law = make("power-law", norton(n));
        const double tau0 = x * kTauRef;
        const double t0 = tau0 / (kE1 * kA * std::pow(x, n));
        const double dt = step * t0, delta = tau0 / kE1;
        for (Scheme s : {Scheme::implicit, Scheme::exponential_linear}) {
          BOOST_TEST_CONTEXT("n " << n << ", tau/tau_ref " << x << ", dt/t0 " << step << ", "
                                  << scheme_name(s)) {
            const StepConstants k = law->step_constants(dt, s);
            RheologyState q, next;
            double tau = tau0;
            bool ok = true;
            for (int i = 0; i < 200 && ok; ++i) {
              const double f = solve_series_force(*law, k, q, kE1, delta, tau);
              law->advance(k, q, tau, f, next);
              if (!std::isfinite(f)) ok = false;
              if (s == Scheme::implicit && !(f >= 0.0 && f <= tau * (1 + 1e-12))) ok = false;
              if (s == Scheme::exponential_linear && !(std::abs(f) <= std::abs(tau) * (1 + 1e-12)))
                ok = false;
              // The force is the spring's: consistent with the advanced state.
              if (std::abs(f - kE1 * (delta - next.creep())) > 1e-9 * tau0) ok = false;
              q = next;
              tau = f;
            }
            BOOST_TEST(ok);
            ++cases;
          }
        }
      }
  BOOST_TEST(cases == 120);
}

BOOST_AUTO_TEST_CASE(lagged_norton_is_stable_below_two_over_k_times_the_tangent_rate) {
  // Lagged: tau' = tau - k dt A g(tau) (explicit Euler): an error is amplified
  // by 1 - k dt g'(tau), stable for dt < 2 / (k A n tau^(n-1)/tau_ref^n) near
  // the stress tau the relaxation passes. Below 0.5x the limit at tau(0+) the
  // force falls monotonically; far above it (20x) the first step overshoots below zero.
  for (double n : {1.0, 5.0, 20.0}) {
    const auto law = make("power-law", norton(n));
    const double tau0 = 1.5 * kTauRef, delta = tau0 / kE1;
    const double limit = 2.0 / (kE1 * kA * n * std::pow(tau0, n - 1) / std::pow(kTauRef, n));
    for (double frac : {0.5, 20.0}) {
      const StepConstants k = law->step_constants(frac * limit, Scheme::lagged);
      RheologyState q, next;
      double tau = tau0;
      bool monotone = true;
      for (int i = 0; i < 50; ++i) {
        law->advance(k, q, tau, tau, next);
        const double f = kE1 * (delta - next.creep());
        if (!(f <= tau && f >= 0.0)) monotone = false;
        q = next;
        tau = f;
        if (!monotone) break;
      }
      BOOST_TEST(monotone == (frac < 1.0), "n " << n << ", dt = " << frac << " x limit");
    }
  }
}

BOOST_AUTO_TEST_CASE(failure_time_under_a_ramp_converges_at_the_schemes_orders) {
  // F = a t: X = (1-D)^(r+1) = 1 - (a/tau_ref)^r t^(r+1)/((r+1) t_r), so failure at
  //   t_f = ((r+1) t_r (tau_ref/a)^r)^(1/(r+1)).
  // The numerical failure time: the start of the step that fails plus the
  // law's failure_in_step (the sub-step that fails under the scheme's force).
  // Lagged and implicit converge at order 1 (within a step: the error is below
  // dt/t_f), exponential-linear (midpoint force) at order 2.
  const auto law = make("damage-burgers", damage(3.0));
  const double a = 1e-3;  // [MPa/h]
  const double tf = std::pow((kR + 1.0) * kTr * std::pow(kTauRef / a, kR), 1.0 / (kR + 1.0));
  for (Scheme s : all_schemes()) {
    std::vector<double> err;
    for (double dt : {8.0, 4.0, 2.0, 1.0}) {
      const StepConstants k = law->step_constants(dt, s);
      RheologyState q, next;
      double t = 0.0, t_fail = NAN;
      for (int i = 0; i < 100000; ++i) {
        const double fs = a * t, fe = a * (t + dt);
        law->advance(k, q, fs, fe, next);
        if (next.failed()) {
          const auto theta = law->failure_in_step(k, q, fs, fe);
          BOOST_TEST_REQUIRE(theta.has_value());
          BOOST_TEST(*theta <= dt);
          t_fail = t + *theta;
          break;
        }
        BOOST_TEST_REQUIRE(!law->failure_in_step(k, q, fs, fe).has_value());
        q = next;
        t += dt;
      }
      err.push_back(std::abs(t_fail - tf) / tf);
    }
    const double order = std::log2(err[2] / err[3]);
    BOOST_TEST_MESSAGE(scheme_name(s) << ": t_f = " << tf << " h, relative errors " << err[0] << " "
                                      << err[1] << " " << err[2] << " " << err[3] << ", order "
                                      << order);
    for (std::size_t i = 0; i + 1 < err.size(); ++i) BOOST_TEST(err[i + 1] < err[i]);
    const double expected = s == Scheme::exponential_linear ? 2.0 : 1.0;
    BOOST_TEST(std::abs(order - expected) < 0.1);
    BOOST_TEST(err[3] * tf < 1.0);  // within the finest step (1 h)
  }
}

BOOST_AUTO_TEST_SUITE_END()
