// Relaxation of a spring k in series with the creep (displacement control, as
// in a DDA contact): the lagged scheme is explicit and diverges beyond
// dt = 2 eta1/k for a dashpot and beyond b(r) (1 + k/E2) = 2 for a Kelvin unit
// (r = dt E2/eta2, b = 1 - exp(-r); approximately dt < 2 eta2/(k + E2),
// rheology.md), while implicit stays monotone and exponential-linear stays
// stable at any step.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "rheodda/laws/history.hpp"
#include "rheodda/laws/series_law.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
// Deviation of the force from its long-time value after each of 40 steps.
std::vector<double> deviations(const ContactRheology& law, Scheme scheme, double dt, double d0,
                               double f_inf) {
  const auto s = integrate_curve(law, Control::displacement, StagedHistory({{0.0, d0}}), 40 * dt, dt, scheme);
  std::vector<double> dev;
  for (const auto& x : s) dev.push_back(x.force - f_inf);
  return dev;
}
bool magnitude_grows(const std::vector<double>& d) {
  for (std::size_t i = 1; i < d.size(); ++i)
    if (!(std::abs(d[i]) > std::abs(d[i - 1]))) return false;
  return true;
}
// Once a deviation is within round-off of the long-time value (1e-12 of the
// initial deviation) it counts as converged: its sign is then noise.
bool converged(const std::vector<double>& d, std::size_t i) { return std::abs(d[i]) <= 1e-12 * std::abs(d[0]); }
bool magnitude_shrinks(const std::vector<double>& d) {
  for (std::size_t i = 1; i < d.size(); ++i)
    if (!(std::abs(d[i]) <= std::abs(d[i - 1]) || converged(d, i))) return false;
  return true;
}
bool alternates(const std::vector<double>& d) {
  for (std::size_t i = 1; i < d.size(); ++i)
    if (!(d[i] * d[i - 1] < 0.0)) return false;
  return true;
}
// Monotone decay towards the long-time value, from above, without crossing it.
bool monotone(const std::vector<double>& d) {
  for (std::size_t i = 1; i < d.size(); ++i)
    if (!((d[i] >= 0.0 && d[i] <= d[i - 1]) || converged(d, i))) return false;
  return true;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(stability)

BOOST_AUTO_TEST_CASE(lagged_dashpot_diverges_beyond_2_eta1_over_k_and_not_below) {
  for (const auto& r : table1()) {
    const auto law = maxwell(r);  // spring k = E1 in series with eta1; F_inf = 0
    const double limit = 2.0 * r.eta1 / r.E1, d0 = r.tau / r.E1;
    // Lagged: F_{n+1} = (1 - k dt/eta1) F_n.
    const auto above = deviations(*law, Scheme::lagged, 1.1 * limit, d0, 0.0);
    BOOST_TEST(magnitude_grows(above));
    BOOST_TEST(alternates(above));
    BOOST_TEST(magnitude_shrinks(deviations(*law, Scheme::lagged, 0.9 * limit, d0, 0.0)));
    BOOST_TEST(monotone(deviations(*law, Scheme::lagged, 0.45 * limit, d0, 0.0)));
    for (double factor : {1.1, 10.0, 1e4}) {
      BOOST_TEST(monotone(deviations(*law, Scheme::implicit, factor * limit, d0, 0.0)), factor);
      // Exponential-linear (trapezoid for the dashpot) is A-stable, not
      // L-stable: beyond 2 eta1/k it rings with decaying amplitude.
      const auto el = deviations(*law, Scheme::exponential_linear, factor * limit, d0, 0.0);
      BOOST_TEST(magnitude_shrinks(el), factor);
    }
    BOOST_TEST(monotone(deviations(*law, Scheme::exponential_linear, 0.9 * limit, d0, 0.0)));
  }
}

BOOST_AUTO_TEST_CASE(lagged_kelvin_with_stiff_spring_diverges_beyond_its_limit_and_not_below) {
  for (const auto& r : table1()) {
    // A stiff series spring k = 100 E2, as a DDA penalty spring would be;
    // Nishihara below its threshold is exactly spring + Kelvin.
    const double k = 100.0 * r.E2;
    const auto law = make("nishihara", {{"E1", k}, {"E2", r.E2}, {"eta2", r.eta2}, {"eta3", r.eta1}, {"Fs", 1e30}});
    const double d0 = r.tau / k, f_inf = d0 * k * r.E2 / (k + r.E2);
    // Lagged: F_{n+1} - F_inf = (1 - b (1 + k/E2)) (F_n - F_inf), unstable when b(1 + k/E2) > 2.
    const double r_star = -std::log1p(-2.0 * r.E2 / (r.E2 + k));
    const double dt_star = r_star * r.eta2 / r.E2;
    BOOST_TEST(rel(dt_star, 2.0 * r.eta2 / (k + r.E2)) <= 0.02);  // rheology.md's estimate
    const auto above = deviations(*law, Scheme::lagged, 1.1 * dt_star, d0, f_inf);
    BOOST_TEST(magnitude_grows(above));
    BOOST_TEST(alternates(above));
    BOOST_TEST(magnitude_shrinks(deviations(*law, Scheme::lagged, 0.9 * dt_star, d0, f_inf)));
    for (double factor : {1.1, 10.0, 1e4}) {
      BOOST_TEST(monotone(deviations(*law, Scheme::implicit, factor * dt_star, d0, f_inf)), factor);
      BOOST_TEST(magnitude_shrinks(deviations(*law, Scheme::exponential_linear, factor * dt_star, d0, f_inf)), factor);
    }
  }
}

BOOST_AUTO_TEST_CASE(lagged_step_limit_is_the_boundary_the_cases_above_measure) {
  // SeriesLaw::lagged_step_limit (what `rheodda check` warns with) against the
  // two boundaries measured above, and stable at any step when k <= E2.
  for (const auto& r : table1()) {
    const auto mx = maxwell(r);
    const auto* m = dynamic_cast<const SeriesLaw*>(mx.get());
    BOOST_TEST_REQUIRE(m);
    const double maxwell_limit = m->lagged_step_limit(r.E1);
    BOOST_TEST(maxwell_limit == 2.0 * r.eta1 / r.E1, boost::test_tools::tolerance(1e-14));
    BOOST_TEST(magnitude_grows(deviations(*mx, Scheme::lagged, 1.1 * maxwell_limit, r.tau / r.E1, 0.0)));
    BOOST_TEST(magnitude_shrinks(deviations(*mx, Scheme::lagged, 0.9 * maxwell_limit, r.tau / r.E1, 0.0)));

    const double k = 100.0 * r.E2;
    const auto ni = make("nishihara", {{"E1", k}, {"E2", r.E2}, {"eta2", r.eta2}, {"eta3", r.eta1}, {"Fs", 1e30}});
    const auto* n = dynamic_cast<const SeriesLaw*>(ni.get());
    BOOST_TEST_REQUIRE(n);
    const double kelvin_limit = n->lagged_step_limit(k);
    const double d0 = r.tau / k, f_inf = d0 * k * r.E2 / (k + r.E2);
    BOOST_TEST(kelvin_limit == -std::log1p(-2.0 * r.E2 / (r.E2 + k)) * r.eta2 / r.E2,
               boost::test_tools::tolerance(1e-14));
    BOOST_TEST(magnitude_grows(deviations(*ni, Scheme::lagged, 1.1 * kelvin_limit, d0, f_inf)));
    BOOST_TEST(magnitude_shrinks(deviations(*ni, Scheme::lagged, 0.9 * kelvin_limit, d0, f_inf)));

    const auto kv = make("kelvin", {{"E2", r.E2}, {"eta2", r.eta2}});
    BOOST_TEST(std::isinf(dynamic_cast<const SeriesLaw&>(*kv).lagged_step_limit(0.5 * r.E2)));
    BOOST_TEST(std::isinf(dynamic_cast<const SeriesLaw&>(*kv).lagged_step_limit(r.E2)));
  }
}

BOOST_AUTO_TEST_SUITE_END()
