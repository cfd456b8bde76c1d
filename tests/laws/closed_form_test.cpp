// Under a constant force every law and every scheme reproduces the closed-form
// creep curve (rheology.md, "The four laws under constant force"; the seed's
// eq. 2 for Burgers) to round-off at any step: the force really is constant
// over each step, and each element's update is exact for a constant force.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>

#include "rheodda/laws/history.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {
// Closed forms written out here, independently of the library (F applied at t = 0).
double kelvin_part(double f, double e, double eta, double t) { return -f / e * std::expm1(-e * t / eta); }
double bingham_part(double f, double fs, double eta, double t) {
  return (f > fs ? f - fs : 0.0) * t / eta;
}

// Runs `law` under F from t = 0 for each scheme and step; every sample must
// match `exact` to 1e-12 relative (round-off over up to 2e4 steps).
void check_all_steps(const ContactRheology& law, double f,
                     const std::function<double(double)>& exact) {
  for (Scheme scheme : all_schemes()) {
    for (double dt : {0.1, 1.0, 7.3, 200.0, 2000.0}) {
      const auto samples =
          integrate_curve(law, Control::force, StagedHistory({{0.0, f}}), 2000.0, dt, scheme);
      BOOST_REQUIRE_GE(samples.size(), 2u);
      BOOST_TEST(samples.back().t == 2000.0);
      double worst = 0.0;
      for (const auto& s : samples) worst = std::max(worst, rel(s.displacement, exact(s.t)));
      BOOST_TEST(worst <= 1e-12, law.name() << " scheme " << scheme_name(scheme) << " dt " << dt
                                            << ": worst relative error " << worst);
    }
  }
}
}  // namespace

BOOST_AUTO_TEST_SUITE(closed_form)

BOOST_AUTO_TEST_CASE(burgers_table1_constant_force_matches_closed_form_at_any_step) {
  for (const auto& r : table1()) {
    check_all_steps(*burgers(r), r.tau, [&](double t) {
      return r.tau / r.E1 + kelvin_part(r.tau, r.E2, r.eta2, t) + r.tau * t / r.eta1;
    });
  }
}

BOOST_AUTO_TEST_CASE(maxwell_table1_constant_force_matches_closed_form_at_any_step) {
  for (const auto& r : table1())
    check_all_steps(*maxwell(r), r.tau, [&](double t) { return r.tau / r.E1 + r.tau * t / r.eta1; });
}

BOOST_AUTO_TEST_CASE(kelvin_table1_constant_force_matches_closed_form_at_any_step) {
  for (const auto& r : table1())
    check_all_steps(*kelvin(r), r.tau, [&](double t) { return kelvin_part(r.tau, r.E2, r.eta2, t); });
}

BOOST_AUTO_TEST_CASE(nishihara_table1_below_and_above_threshold_matches_closed_form_at_any_step) {
  for (const auto& r : table1()) {
    // Fs below the force: viscoplastic flow at (F - Fs)/eta3; above: none.
    for (double fs : {0.5 * r.tau, 1.5 * r.tau}) {
      check_all_steps(*nishihara(r, fs), r.tau, [&](double t) {
        return r.tau / r.E1 + kelvin_part(r.tau, r.E2, r.eta2, t) + bingham_part(r.tau, fs, r.eta1, t);
      });
    }
  }
}

BOOST_AUTO_TEST_CASE(generalized_kelvin_constant_force_matches_closed_form_at_any_step) {
  for (const auto& r : table1()) {
    check_all_steps(*generalized_kelvin(r), r.tau, [&](double t) {
      return r.tau / r.E1 + kelvin_part(r.tau, r.E2, r.eta2, t) +
             kelvin_part(r.tau, 0.5 * r.E2, r.eta1, t);
    });
  }
}

BOOST_AUTO_TEST_CASE(library_closed_form_equals_the_written_out_formula) {
  // displacement_closed_form is what `law curve` prints as `exact`; it must be
  // the formula of the law, checked here at a few times for each law.
  for (const auto& r : table1()) {
    for (double t : {0.0, 1e-6, 3.0, 250.0, 1e5}) {
      const double f = r.tau;
      BOOST_TEST(rel(burgers(r)->displacement_closed_form(f, t),
                     f / r.E1 + kelvin_part(f, r.E2, r.eta2, t) + f * t / r.eta1) <= 1e-14);
      BOOST_TEST(rel(maxwell(r)->displacement_closed_form(f, t), f / r.E1 + f * t / r.eta1) <= 1e-14);
      BOOST_TEST(rel(kelvin(r)->displacement_closed_form(f, t), kelvin_part(f, r.E2, r.eta2, t)) <=
                 1e-14);
      BOOST_TEST(rel(nishihara(r, 0.1)->displacement_closed_form(f, t),
                     f / r.E1 + kelvin_part(f, r.E2, r.eta2, t) + (f - 0.1) * t / r.eta1) <= 1e-14);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
