// Force varying within steps: under a ramp F = F0 + rho t the exponential-
// linear scheme is exact (its force is linear over each step), lagged and
// implicit converge at order 1; under a quadratic force exponential-linear
// converges at order 2. Exact responses are integrated by hand here, element
// by element, not taken from the library.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "rheodda/laws/history.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
// Force F(t) = F0 + rho t + kappa t^2 from t = 0 (a jump to F0 at t = 0).
struct Force { double f0, rho, kappa; double at(double t) const { return f0 + rho * t + kappa * t * t; } };

// Creep element response to that force, from eta q' + E q = F(t), q(0) = 0:
//   Kelvin (tau = eta/E, b = 1 - exp(-t/tau)):
//     E q = F0 b + rho (t - tau b) + kappa (t^2 - 2 tau t + 2 tau^2 b)
//   dashpot: eta q = F0 t + rho t^2/2 + kappa t^3/3
//   Bingham with F > Fs throughout: the dashpot of F - Fs.
struct Element { double E, eta, fs; bool bingham; };
double element_exact(const Element& e, const Force& f, double t) {
  if (e.E > 0.0) {
    const double tau = e.eta / e.E, b = -std::expm1(-t / tau);
    return (f.f0 * b + f.rho * (t - tau * b) + f.kappa * (t * t - 2 * tau * t + 2 * tau * tau * b)) / e.E;
  }
  const double f0 = e.bingham ? f.f0 - e.fs : f.f0;
  return (f0 * t + f.rho * t * t / 2 + f.kappa * t * t * t / 3) / e.eta;
}

struct Case {
  std::unique_ptr<ContactRheology> law;
  double e1;  // 0: no spring
  std::vector<Element> elements;
};
std::vector<Case> cases(const Table1Row& r) {
  std::vector<Case> c;
  c.push_back({burgers(r), r.E1, {{r.E2, r.eta2, 0, false}, {0, r.eta1, 0, false}}});
  c.push_back({maxwell(r), r.E1, {{0, r.eta1, 0, false}}});
  c.push_back({kelvin(r), 0.0, {{r.E2, r.eta2, 0, false}}});
  // Fs below F0, so the increasing force stays above the threshold.
  c.push_back({nishihara(r, 0.5 * r.tau), r.E1, {{r.E2, r.eta2, 0, false}, {0, r.eta1, 0.5 * r.tau, true}}});
  c.push_back({generalized_kelvin(r), r.E1, {{r.E2, r.eta2, 0, false}, {0.5 * r.E2, r.eta1, 0, false}}});
  return c;
}

double exact_total(const Case& c, const Force& f, double t) {
  double d = c.e1 > 0 ? f.at(t) / c.e1 : 0.0;
  for (const auto& e : c.elements) d += element_exact(e, f, t);
  return d;
}

// Relative error at t_end = 200 h for dt = 8, 4, 2, 1, 0.5 h.
std::vector<double> errors(const Case& c, const Force& f, Scheme scheme) {
  const double t_end = 200.0, exact = exact_total(c, f, t_end);
  std::vector<double> err;
  for (double dt : {8.0, 4.0, 2.0, 1.0, 0.5})
    err.push_back(rel(integrate_force_function(*c.law, [&](double t) { return f.at(t); }, t_end, dt, scheme), exact));
  return err;
}

// The observed order log2(e(dt)/e(dt/2)) over each halving.
void check_order(const std::vector<double>& err, double expected, const std::string& what) {
  for (std::size_t i = 1; i < err.size(); ++i) {
    const double order = std::log2(err[i - 1] / err[i]);
    BOOST_TEST(std::abs(order - expected) <= 0.1,
               what << ": order " << order << " from errors " << err[i - 1] << ", " << err[i]);
  }
}
}  // namespace

BOOST_AUTO_TEST_SUITE(convergence)

BOOST_AUTO_TEST_CASE(ramp_lagged_and_implicit_converge_at_first_order) {
  for (const auto& r : table1()) {
    const Force ramp{r.tau, r.tau / 200.0, 0.0};  // doubles over 200 h
    for (const auto& c : cases(r)) {
      check_order(errors(c, ramp, Scheme::lagged), 1.0, std::string(c.law->name()) + " lagged");
      check_order(errors(c, ramp, Scheme::implicit), 1.0, std::string(c.law->name()) + " implicit");
    }
  }
}

BOOST_AUTO_TEST_CASE(ramp_exponential_linear_is_exact_to_round_off) {
  // The scheme integrates a force linear over the step exactly (exact
  // exponential for Kelvin units, trapezoid for dashpots), so a ramp leaves
  // only round-off at any step.
  for (const auto& r : table1()) {
    const Force ramp{r.tau, r.tau / 200.0, 0.0};
    for (const auto& c : cases(r))
      for (double e : errors(c, ramp, Scheme::exponential_linear))
        BOOST_TEST(e <= 1e-13, c.law->name() << ": " << e);
  }
}

BOOST_AUTO_TEST_CASE(quadratic_force_exponential_linear_converges_at_second_order) {
  for (const auto& r : table1()) {
    const Force quadratic{r.tau, r.tau / 200.0, r.tau / (200.0 * 200.0)};  // triples over 200 h
    for (const auto& c : cases(r)) {
      check_order(errors(c, quadratic, Scheme::exponential_linear), 2.0,
                  std::string(c.law->name()) + " exponential-linear");
      check_order(errors(c, quadratic, Scheme::implicit), 1.0, std::string(c.law->name()) + " implicit");
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
