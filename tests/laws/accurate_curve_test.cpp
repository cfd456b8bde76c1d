// The accuracy layer of `rheodda law curve` (laws/accurate_curve.hpp): the curves
// the raw schemes got wrong (issue 43) against their closed forms, the failure of
// a damage law landed on, and the refusals.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/laws/accurate_curve.hpp"
#include "test_support.hpp"

using namespace rheodda::laws;
using namespace rheodda::laws::test;

namespace {

std::unique_ptr<ContactRheology> power_law(double n, double A = 1e-3) {
  return make("power-law", {{"E1", 20.0}, {"tau_ref", 0.2}, {"A", A}, {"n", n}});
}

/// Largest |force - exact| over the samples, relative to the largest |exact|.
double relaxation_error(const std::vector<CurveSample>& samples) {
  double err = 0.0, scale = 0.0;
  for (const auto& s : samples) {
    BOOST_TEST_REQUIRE(s.exact.has_value());
    err = std::max(err, std::abs(s.force - *s.exact));
    scale = std::max(scale, std::abs(*s.exact));
  }
  return err / scale;
}

bool all_finite(const std::vector<CurveSample>& samples) { return first_non_finite(samples) == samples.size(); }

}  // namespace

BOOST_AUTO_TEST_SUITE(accurate_curve)

BOOST_AUTO_TEST_CASE(power_law_relaxation_closed_form_satisfies_its_ode) {
  // exact_force of power-law: F' = -E1 A (F/tau_ref)^n, checked by a central
  // difference at a few times, and the stage jump E1 * delta d.
  const auto law = power_law(5.0);
  const StagedHistory d({{0.0, 0.02}, {50.0, 0.03}});
  for (double t : {1.0, 10.0, 40.0, 60.0, 90.0}) {
    const double h = 1e-4 * t;
    const double f = *exact_force(*law, d, t);
    const double rate = (*exact_force(*law, d, t + h) - *exact_force(*law, d, t - h)) / (2 * h);
    BOOST_TEST(rel(rate, -20.0 * 1e-3 * std::pow(f / 0.2, 5.0)) <= 1e-6, "t " << t);
  }
  BOOST_TEST(*exact_force(*law, d, 0.0) == 20.0 * 0.02);
  BOOST_TEST(rel(*exact_force(*law, d, 50.0) - *exact_force(*law, d, 50.0 - 1e-9), 20.0 * 0.01) <= 1e-6);
}

BOOST_AUTO_TEST_CASE(relaxations_the_raw_schemes_got_wrong_follow_the_closed_form) {
  // issue 43: n = 20 at 2 tau_ref with exponential-linear at dt = 10 h dropped to a
  // tenth of the exact force (0.0134 against 0.152 at 100 h), lagged went to NaN;
  // n = 100 at 10 tau_ref and n = 20 at 1000 tau_ref stopped Newton short (implicit).
  struct Case {
    double n, d, t_end, dt;
    Scheme scheme;
  };
  for (const Case& c : {Case{20, 0.02, 100, 10, Scheme::exponential_linear}, Case{20, 0.02, 100, 10, Scheme::lagged},
                        Case{20, 0.02, 100, 10, Scheme::implicit}, Case{100, 0.1, 2, 1, Scheme::implicit},
                        Case{20, 10.0, 2, 1, Scheme::implicit}, Case{100, 0.1, 2, 1, Scheme::exponential_linear}}) {
    const auto law = power_law(c.n);
    const StagedHistory d({{0.0, c.d}});
    BOOST_TEST_CONTEXT("n " << c.n << ", d " << c.d << ", " << scheme_name(c.scheme)) {
      const auto raw = integrate_curve(*law, Control::displacement, d, c.t_end, c.dt, c.scheme);
      const auto curve = integrate_curve_accurate(*law, Control::displacement, d, c.t_end, c.dt, c.scheme);
      BOOST_TEST(all_finite(curve.samples));
      BOOST_TEST(curve.samples.size() == raw.size());
      // Step doubling holds each substep's error and local extrapolation keeps the
      // global error near the tolerance, relative to the scale (the initial force).
      for (double tol : {1e-6, 1e-9}) {
        const auto c2 = integrate_curve_accurate(*law, Control::displacement, d, c.t_end, c.dt, c.scheme, {tol});
        BOOST_TEST(relaxation_error(c2.samples) <= 10 * tol, "tolerance " << tol);
      }
    }
  }
  // The figure: the exact force at 100 h is 0.152.
  const auto c = integrate_curve_accurate(*power_law(20), Control::displacement, StagedHistory({{0.0, 0.02}}), 100, 10,
                                          Scheme::exponential_linear);
  BOOST_TEST(std::abs(c.samples.back().force - 0.152) < 5e-4);
}

BOOST_AUTO_TEST_CASE(curves_the_raw_scheme_gets_right_at_the_output_step_take_no_substeps) {
  // A Burgers law under a staged force: every scheme is exact at any step, so each
  // output step is one substep (checked by two half steps) and the values are the
  // closed form's.
  const auto law = burgers(table1()[0]);
  const StagedHistory f({{0.0, 0.232}, {100.0, 0.5}, {150.0, 0.0}});
  for (Scheme s : all_schemes()) {
    const auto curve = integrate_curve_accurate(*law, Control::force, f, 200, 10, s);
    BOOST_TEST(curve.steps == static_cast<long long>(curve.samples.size()) - 1);
    for (const auto& x : curve.samples) BOOST_TEST(rel(x.displacement, *x.exact) <= 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(a_damage_law_lands_on_its_failure_and_keeps_its_creep_at_failure) {
  // damage-burgers of examples/damage-creep-test.yaml with n = 2 < r + 1 = 4 (p = 1/2):
  // the creep at failure is finite; after t_f the raw scheme's displacement is infinite
  // (each step of a failed law adds an infinite increment), the curve's is the creep at failure.
  const auto law = make("damage-burgers", {{"E1", 26.87}, {"E2", 192.43}, {"eta2", 2141.23}, {"A", 3.68e-6},
                                           {"tau_ref", 0.2}, {"n", 2}, {"t_r", 234}, {"r", 3}});
  const StagedHistory f({{0.0, 0.232}});
  const double tf = *law->failure_time(0.232);
  for (Scheme s : all_schemes()) {
    const auto raw = integrate_curve(*law, Control::force, f, 200, 10, s);
    BOOST_TEST(first_non_finite(raw) < raw.size());  // what the command printed before: inf
    const auto curve = integrate_curve_accurate(*law, Control::force, f, 200, 10, s);
    BOOST_TEST_REQUIRE(curve.failure_time.has_value());
    BOOST_TEST(rel(*curve.failure_time, tf) <= 1e-12);
    BOOST_TEST(!curve.ends_at_failure);
    BOOST_TEST(all_finite(curve.samples));
    // Before t_f the closed form; after it the creep of the failed law stays at its
    // value at failure (the closed form's Norton creep stops too, its Kelvin element
    // has relaxed to within e^(-E2 t_f/eta2) = 1.4e-6 of F/E2 by then).
    const double at_failure = *exact_displacement(*law, f, tf);
    for (const auto& x : curve.samples)
      BOOST_TEST(rel(x.displacement, x.t < tf ? *x.exact : at_failure) <= 1e-9, "t " << x.t);
    BOOST_TEST(curve.samples.back().damage == 1.0);
  }
}

BOOST_AUTO_TEST_CASE(a_damage_law_whose_creep_diverges_at_failure_ends_before_it) {
  // n = r + 1 (p = 0): the creep is infinite at t_f, so no finite sample exists at or
  // after it; the curve ends at the last output time before t_f = 149.9 h.
  const auto law = make("damage-burgers", {{"E1", 26.87}, {"E2", 192.43}, {"eta2", 2141.23}, {"A", 3.68e-6},
                                           {"tau_ref", 0.2}, {"n", 4}, {"t_r", 234}, {"r", 3}});
  const auto curve = integrate_curve_accurate(*law, Control::force, StagedHistory({{0.0, 0.232}}), 200, 10,
                                              Scheme::implicit);
  BOOST_TEST(curve.ends_at_failure);
  BOOST_TEST(rel(*curve.failure_time, *law->failure_time(0.232)) <= 1e-12);
  BOOST_TEST(curve.samples.back().t == 140.0);
  BOOST_TEST(all_finite(curve.samples));
}

BOOST_AUTO_TEST_CASE(a_damage_law_under_a_held_displacement_fails_on_a_substep_end) {
  // Relaxation of damage-burgers (p = 1/2) at a displacement that fails it: the force
  // falls while the damage grows; the failure ends a substep, and after it the force
  // stays at E1 (d - creep at failure).
  const auto law = make("damage-burgers", {{"E1", 26.87}, {"E2", 192.43}, {"eta2", 2141.23}, {"A", 3.68e-3},
                                           {"tau_ref", 0.2}, {"n", 2}, {"t_r", 2}, {"r", 3}});
  const auto curve = integrate_curve_accurate(*law, Control::displacement, StagedHistory({{0.0, 0.02}}), 20, 1,
                                              Scheme::implicit);
  BOOST_TEST_REQUIRE(curve.failure_time.has_value());
  BOOST_TEST(all_finite(curve.samples));
  const auto& last = curve.samples.back();
  BOOST_TEST(last.damage == 1.0);
  std::size_t after = 0;
  for (const auto& s : curve.samples)
    if (s.t > *curve.failure_time) {
      BOOST_TEST(s.force == last.force);
      ++after;
    }
  BOOST_TEST(after > 0u);
}

BOOST_AUTO_TEST_CASE(a_curve_beyond_the_range_of_a_double_is_refused_with_the_reason) {
  // A = 1e300 and (100/0.2)^100 = 1e270: the creep rate overflows.
  const auto law = power_law(100, 1e300);
  BOOST_CHECK_EXCEPTION(
      integrate_curve_accurate(*law, Control::force, StagedHistory({{0.0, 100.0}}), 1, 1, Scheme::implicit),
      CurveError, [](const CurveError& e) { return std::string(e.what()).find("not a finite number") != std::string::npos; });
  // A tolerance outside [1e-12, 1e-2] is bad input.
  BOOST_CHECK_THROW(integrate_curve_accurate(*law, Control::force, StagedHistory({{0.0, 0.1}}), 1, 1,
                                             Scheme::implicit, {0.5}),
                    LawError);
}

BOOST_AUTO_TEST_SUITE_END()
