// Stability map of the creep schemes (docs/notes/step-controls.md, "Stability map"):
// a shear spring k in series with a Kelvin element (E2, eta2; Table 1 row 1)
// held at a displacement from t = 0, solved by the law alone
// (laws::solve_series_force, the contact's k_eff algebra). Over the map
// dt E2/eta2 and k/E2 in [1e-2, 1e3] the implicit and exponential-linear
// schemes never let the force grow; the lagged scheme diverges beyond its
// limit (about dt < 2 eta2 / (k + E2) for k >> E2, exact form below).
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/laws/history.hpp"
#include "rheodda/laws/registry.hpp"
#include "held_spring.hpp"  // tests/models

using namespace rheodda;

namespace {

constexpr double kE2 = 192.43, kEta2 = 2141.23;  // [MPa/mm], [MPa h/mm]

/// Largest |F| over steps 100-200 divided by the force at t = 0+ (k delta).
double growth(laws::Scheme scheme, double x, double y) {
  const auto law = laws::LawRegistry::builtin().create("kelvin", {{"E2", kE2}, {"eta2", kEta2}});
  const double dt = x * kEta2 / kE2, k = y * kE2, delta = 1e-3;
  const laws::StepConstants ks = law->step_constants(dt, scheme);
  return models::held_spring_growth(*law, ks, ks, k, delta, 200);  // tests/models/held_spring.hpp
}

}  // namespace

BOOST_AUTO_TEST_SUITE(stability_map)

BOOST_AUTO_TEST_CASE(implicit_and_exponential_linear_never_grow_over_the_whole_map) {
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const double x = std::pow(10.0, -2.0 + 0.25 * i), y = std::pow(10.0, -2.0 + 0.25 * j);
      for (laws::Scheme s : {laws::Scheme::implicit, laws::Scheme::exponential_linear}) {
        const double g = growth(s, x, y);
        BOOST_TEST_INFO("scheme " << laws::scheme_name(s) << ", dt E2/eta2 = " << x
                                  << ", k/E2 = " << y);
        BOOST_TEST(g <= 1.0 + 1e-12);
      }
    }
}

// The lagged scheme (the seed's eqs. 12-16) integrates the Kelvin element
// exactly under the start force: q' = q + b (F_s/E2 - q), b = 1 - exp(-dt E2/eta2).
// With F = k (delta - q) the error amplification is 1 - b (k + E2)/E2, so it is
// stable for b < 2 E2/(k + E2): dt < -(eta2/E2) ln(1 - 2 E2/(k + E2)) when k > E2
// (-> 2 eta2/(k + E2) for k >> E2), at any dt when k <= E2.
BOOST_AUTO_TEST_CASE(lagged_is_stable_below_its_limit_and_diverges_beyond) {
  for (double y : {3.0, 10.0, 100.0, 1000.0}) {
    const double limit = -std::log(1.0 - 2.0 / (y + 1.0));  // dt E2/eta2 at the limit
    BOOST_TEST_INFO("k/E2 = " << y);
    BOOST_TEST(growth(laws::Scheme::lagged, 0.9 * limit, y) <= 1.0 + 1e-12);
    BOOST_TEST(growth(laws::Scheme::lagged, 1.1 * limit, y) > 1e6);
  }
  {  // k >> E2: the limit tends to the explicit one, 2 eta2 / (k + E2)
    const double y = 1000.0, limit = -std::log(1.0 - 2.0 / (y + 1.0));
    BOOST_TEST(std::abs(limit / (2.0 / (y + 1.0)) - 1.0) < 1.5e-3);
  }
  for (double y : {0.01, 0.1, 1.0})
    for (double x : {0.01, 1.0, 10.0, 1000.0}) {
      BOOST_TEST_INFO("k/E2 = " << y << ", dt E2/eta2 = " << x);
      BOOST_TEST(growth(laws::Scheme::lagged, x, y) <= 1.0 + 1e-12);
    }
}

BOOST_AUTO_TEST_SUITE_END()
