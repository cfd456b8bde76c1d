// Relaxation (displacement held): the closed-form relaxation moduli agree with
// independent references (initial value and slope, the creep-relaxation
// interconversion, a fine RK4 solution of the elements' ODEs), and the three
// schemes converge to exact_force at their expected order.
#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "rheodda/laws/history.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
// Classical RK4 on a spring E1 in series with linear creep elements (the
// law's elements written out here): state q = element displacements, the
// force is F = E1 (d0 - sum q). Kelvin: eta q' = F - E q; dashpot: E = 0.
struct Element { double E, eta; };
double rk4_force(double e1, const std::vector<Element>& els, double d0, double t_end, double h) {
  const std::size_t m = els.size();
  std::vector<double> q(m, 0.0), k1(m), k2(m), k3(m), k4(m), tmp(m);
  auto rate = [&](const std::vector<double>& x, std::vector<double>& out) {
    double sum = 0.0;
    for (double v : x) sum += v;
    const double f = e1 * (d0 - sum);
    for (std::size_t i = 0; i < m; ++i) out[i] = (f - els[i].E * x[i]) / els[i].eta;
  };
  const auto n = static_cast<long>(std::llround(t_end / h));
  for (long s = 0; s < n; ++s) {
    rate(q, k1);
    for (std::size_t i = 0; i < m; ++i) tmp[i] = q[i] + 0.5 * h * k1[i];
    rate(tmp, k2);
    for (std::size_t i = 0; i < m; ++i) tmp[i] = q[i] + 0.5 * h * k2[i];
    rate(tmp, k3);
    for (std::size_t i = 0; i < m; ++i) tmp[i] = q[i] + h * k3[i];
    rate(tmp, k4);
    for (std::size_t i = 0; i < m; ++i) q[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  double sum = 0.0;
  for (double v : q) sum += v;
  return e1 * (d0 - sum);
}

struct Case {
  const char* name;
  std::function<std::unique_ptr<ContactRheology>(const Table1Row&)> make;
  std::function<std::vector<Element>(const Table1Row&)> elements;
};
const std::vector<Case>& cases() {
  static const std::vector<Case> c = {
      {"maxwell", [](const Table1Row& r) { return maxwell(r); },
       [](const Table1Row& r) { return std::vector<Element>{{0.0, r.eta1}}; }},
      {"burgers", [](const Table1Row& r) { return burgers(r); },
       [](const Table1Row& r) { return std::vector<Element>{{r.E2, r.eta2}, {0.0, r.eta1}}; }},
      // Below its threshold (E1 d0 < Fs) Nishihara is spring + Kelvin.
      {"nishihara", [](const Table1Row& r) { return nishihara(r, 10.0 * r.tau); },
       [](const Table1Row& r) { return std::vector<Element>{{r.E2, r.eta2}}; }},
      {"generalized-kelvin", [](const Table1Row& r) { return generalized_kelvin(r); },
       [](const Table1Row& r) {
         return std::vector<Element>{{r.E2, r.eta2}, {0.5 * r.E2, r.eta1}};
       }}};
  return c;
}
// Displacement held from t = 0 so that the initial force is the row's tau.
double held(const Table1Row& r) { return r.tau / r.E1; }
}  // namespace

BOOST_AUTO_TEST_SUITE(relaxation)

BOOST_AUTO_TEST_CASE(relaxation_modulus_starts_at_E1_with_the_elements_initial_slope) {
  // G(0) = E1: only the spring responds at once. G'(0) = -E1^2 sum 1/eta_i: at
  // t = 0+ every element creeps at F/eta_i (Kelvin springs still unloaded).
  for (const auto& r : table1()) {
    for (const auto& c : cases()) {
      const auto law = c.make(r);
      BOOST_TEST(rel(*law->relaxation_modulus(0.0), r.E1) <= 1e-13, c.name);
      double inv_eta = 0.0;
      for (const auto& e : c.elements(r)) inv_eta += 1.0 / e.eta;
      const double h = 1e-4;  // central difference about h/2 ... one-sided 2nd order:
      const double slope = (-3 * *law->relaxation_modulus(0.0) + 4 * *law->relaxation_modulus(h) -
                             *law->relaxation_modulus(2 * h)) / (2 * h);
      BOOST_TEST(rel(slope, -r.E1 * r.E1 * inv_eta) <= 1e-6, c.name << " slope " << slope);
    }
  }
}

BOOST_AUTO_TEST_CASE(burgers_relaxation_modulus_and_creep_compliance_interconvert) {
  // The convolution of the relaxation modulus with the creep compliance is t:
  // integral_0^t G(s) J(t - s) ds = t, J(t) = 1/E1 + (1 - exp(-E2 t/eta2))/E2 + t/eta1.
  // Composite Simpson with 2e4 panels (smooth integrand, panel <= 0.25 h against
  // a fastest time constant of about 10 h): quadrature error well below 1e-9.
  for (const auto& r : table1()) {
    const auto law = burgers(r);
    auto j = [&](double t) { return 1 / r.E1 - std::expm1(-r.E2 * t / r.eta2) / r.E2 + t / r.eta1; };
    for (double t : {10.0, 300.0, 5000.0}) {
      const int n = 20000;
      const double h = t / n;
      double sum = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double s = i * h;
        const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * *law->relaxation_modulus(s) * j(t - s);
      }
      BOOST_TEST(rel(sum * h / 3.0, t) <= 1e-9, "t " << t << ": " << sum * h / 3.0);
    }
    // Burgers has steady creep, so a held displacement relaxes to zero force.
    BOOST_TEST(std::abs(*law->relaxation_modulus(1e8)) <= 1e-12 * r.E1);
  }
}

BOOST_AUTO_TEST_CASE(relaxation_modulus_matches_fine_rk4_solution_of_the_element_odes) {
  for (const auto& r : table1()) {
    for (const auto& c : cases()) {
      const auto law = c.make(r);
      for (double t : {20.0, 400.0, 3000.0}) {
        const double reference = rk4_force(r.E1, c.elements(r), held(r), t, 0.05);
        const double exact = *exact_force(*law, StagedHistory({{0.0, held(r)}}), t);
        BOOST_TEST(rel(exact, reference) <= 1e-10, c.name << " t " << t << ": " << exact << " vs " << reference);
        BOOST_TEST(rel(*law->relaxation_modulus(t) * held(r), reference) <= 1e-10);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(schemes_converge_to_exact_relaxation_at_order_1_and_2) {
  // Error at t = 40 h (the fast relaxation times are 10-30 h) for dt = 2 ... 0.125 h; the observed order is
  // log2(e(dt)/e(dt/2)). Lagged and implicit are first order, exponential-linear
  // (trapezoid for dashpots, exact exponential for Kelvin units) second order.
  for (const auto& r : table1()) {
    for (const auto& c : cases()) {
      const auto law = c.make(r);
      const StagedHistory d({{0.0, held(r)}});
      const double exact = *exact_force(*law, d, 40.0);
      for (Scheme scheme : all_schemes()) {
        std::vector<double> err;
        for (double dt : {2.0, 1.0, 0.5, 0.25, 0.125}) {
          const auto s = integrate_curve(*law, Control::displacement, d, 40.0, dt, scheme);
          err.push_back(std::abs(s.back().force - exact) / std::abs(exact));
        }
        const double expected = scheme == Scheme::exponential_linear ? 2.0 : 1.0;
        for (std::size_t i = 1; i < err.size(); ++i) {
          const double order = std::log2(err[i - 1] / err[i]);
          BOOST_TEST(std::abs(order - expected) <= 0.1,
                     c.name << " " << scheme_name(scheme) << " order " << order << " errors "
                            << err[i - 1] << " " << err[i]);
        }
        BOOST_TEST(err.back() <= (expected == 2.0 ? 1e-6 : 1e-3));
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(nishihara_relaxation_above_threshold_converges_to_rk4_at_scheme_order) {
  // Held displacement with E1 d0 = 0.3 MPa above Fs: the Bingham element flows
  // while F > Fs, so the host's piecewise solve (solve_series_force) is used at
  // every step. Reference: RK4 with h = 1e-4 h on
  //   eta2 qK' = F - E2 qK,  eta3 qB' = <F - Fs>,  F = E1 (d0 - qK - qB).
  // Case "above": F stays above Fs to t = 40 h; case "crossing": the Kelvin
  // unit pulls F below Fs, where the Bingham element stops (a kink in time).
  const auto& r = table1()[0];
  const double d0 = 0.3 / r.E1, t_end = 40.0;
  struct Case { const char* what; double eta3, fs; bool all_halvings; };
  for (const Case& c : {Case{"above", r.eta1 / 100.0, 0.15, true}, Case{"crossing", r.eta1 / 1000.0, 0.27, false}}) {
    const auto law = make("nishihara", {{"E1", r.E1}, {"E2", r.E2}, {"eta2", r.eta2}, {"eta3", c.eta3}, {"Fs", c.fs}});
    double qk = 0.0, qb = 0.0;
    auto rate = [&](double k, double b, double* rk, double* rb) {
      const double f = r.E1 * (d0 - k - b);
      *rk = (f - r.E2 * k) / r.eta2;
      *rb = (f > c.fs ? f - c.fs : 0.0) / c.eta3;
    };
    const double h = 1e-4;
    for (long n = 0; n < std::lround(t_end / h); ++n) {
      double a1, b1, a2, b2, a3, b3, a4, b4;
      rate(qk, qb, &a1, &b1);
      rate(qk + h / 2 * a1, qb + h / 2 * b1, &a2, &b2);
      rate(qk + h / 2 * a2, qb + h / 2 * b2, &a3, &b3);
      rate(qk + h * a3, qb + h * b3, &a4, &b4);
      qk += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
      qb += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
    }
    const double reference = r.E1 * (d0 - qk - qb);
    BOOST_TEST((c.all_halvings ? reference > c.fs : reference < c.fs), c.what);
    for (Scheme scheme : all_schemes()) {
      std::vector<double> err;
      for (double dt : {2.0, 1.0, 0.5, 0.25, 0.125}) {
        const auto s = integrate_curve(*law, Control::displacement, StagedHistory({{0.0, d0}}), t_end, dt, scheme);
        for (std::size_t i = 1; i < s.size(); ++i)  // relaxes monotonically at these steps
          BOOST_TEST(s[i].force <= s[i - 1].force, c.what << " " << scheme_name(scheme) << " dt " << dt);
        err.push_back(rel(s.back().force, reference));
      }
      // The kink makes the first halvings pre-asymptotic in the crossing case:
      // there only the last halving is held to the order.
      const double expected = scheme == Scheme::exponential_linear ? 2.0 : 1.0;
      for (std::size_t i = c.all_halvings ? 1 : err.size() - 1; i < err.size(); ++i) {
        const double order = std::log2(err[i - 1] / err[i]);
        BOOST_TEST(std::abs(order - expected) <= 0.1,
                   c.what << " " << scheme_name(scheme) << " order " << order);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
