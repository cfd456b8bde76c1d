// Bounds that bind, the optimality conditions behind `converged`, parameters
// given by expressions (lmfit's expr) and profile-likelihood intervals
// (docs/guide/fitting.md), each against an independent reference: the fit with
// the bound's parameter held there, a fit with the expression's value held,
// and the closed-form profile of a model linear in its compliances.
// tests/python/test_fit_lmfit.py compares the same with lmfit.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "rheodda/fit/fit.hpp"
#include "rheodda/fit/profile.hpp"

#include "synthetic.hpp"

namespace {

using namespace rheodda;

const laws::LawInfo& burgers() { return laws::LawRegistry::builtin().get("burgers"); }

// The shipped lab curve: the seed's Table 1 row 1 under 0.232 MPa, 401 readings with 2e-5 mm of noise.
fit::CreepData table1_row1(bool with_sigma) {
  fit::CsvOptions o;
  o.stress = laws::StagedHistory({{0.0, 0.232}});
  auto d = fit::read_creep_csv(std::string(RHEODDA_SOURCE_DIR) + "/examples/creep-data/table1-row1.csv", o);
  if (with_sigma)  // [mm] grows with time, as tests/python/test_fit_lmfit.py's
    for (double t : d.t) d.sigma.push_back(2e-5 * (1.0 + t / 100.0));
  return d;
}

const fit::ParameterEstimate& param(const fit::FitResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p;
  throw std::runtime_error("no parameter " + name);
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

fit::ParameterSetting held(double v) {
  fit::ParameterSetting s;
  s.value = v;
  s.vary = false;
  return s;
}

// A bound that binds: the fit must end where the fit with the parameter held on
// the bound ends (the constrained minimum), and say converged.
void check_binding_bound(const fit::CreepData& data, fit::FitOptions bounded, const std::string& name, double bound) {
  const auto r = fit::fit_law(burgers(), data, bounded);
  fit::FitOptions at = bounded;
  at.parameters[name] = held(bound);
  const auto h = fit::fit_law(burgers(), data, at);
  BOOST_TEST(param(r, name).at_bound == "max");
  BOOST_TEST(param(r, name).value == bound);
  BOOST_TEST(rel(r.chi_square, h.chi_square) < 1e-10, r.chi_square << " vs held " << h.chi_square);
  for (const char* p : {"E1", "E2", "eta1"})
    BOOST_TEST(rel(param(r, p).value, param(h, p).value) < 1e-7, p << " " << param(r, p).value << " vs "
                                                                    << param(h, p).value);
  BOOST_TEST(r.converged);
  BOOST_TEST(r.optimality <= 1e-6);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(fit_constraints)

BOOST_AUTO_TEST_CASE(a_binding_bound_with_sigma_and_a_fixed_parameter_reaches_the_constrained_minimum) {
  // E1 held at 25, eta2 <= 1200, sigma 2e-5 (1 + t/100): lmfit's minimum is chi^2 16288.648 (E2 921.505,
  // eta1 25057.18; tests/python/test_fit_lmfit.py).
  fit::FitOptions o;
  o.parameters["E1"] = held(25.0);
  o.parameters["eta2"].max = 1200.0;
  check_binding_bound(table1_row1(true), o, "eta2", 1200.0);
}

BOOST_AUTO_TEST_CASE(an_unweighted_binding_bound_reaches_the_constrained_minimum) {
  // eta2 <= 1000: GSL through MINUIT's transform alone stalls here for 500 iterations.
  fit::FitOptions o;
  o.parameters["eta2"].max = 1000.0;
  check_binding_bound(table1_row1(false), o, "eta2", 1000.0);
}

BOOST_AUTO_TEST_CASE(a_fit_cut_short_by_the_iteration_limit_does_not_say_converged) {
  fit::FitOptions o;
  o.parameters["eta2"].max = 1000.0;
  o.max_iterations = 2;
  o.restarts = 0;
  const auto r = fit::fit_law(burgers(), table1_row1(false), o);
  BOOST_TEST(!r.converged);
  BOOST_TEST(r.optimality > 1e-6);
  bool said = false;
  for (const auto& w : r.warnings) said = said || w.find("--max-iterations") != std::string::npos;
  BOOST_TEST(said);
}

BOOST_AUTO_TEST_CASE(a_parameter_given_by_an_expression_is_its_value_at_the_minimum) {
  const auto data = table1_row1(false);
  fit::FitOptions o;
  o.parameters["eta2"].expr = "12*E2";
  const auto r = fit::fit_law(burgers(), data, o);
  const double e2 = param(r, "E2").value;
  BOOST_TEST(rel(param(r, "eta2").value, 12.0 * e2) < 1e-13);
  BOOST_TEST(!param(r, "eta2").vary);
  BOOST_TEST(param(r, "eta2").expr == "12*E2");
  BOOST_TEST(r.varying == 3);
  BOOST_TEST(r.converged);
  // Independent: with E2 and eta2 held at the values found, E1 and eta1 refitted land on the same
  // point and chi^2 (a necessary condition of the constrained minimum)...
  fit::FitOptions h;
  h.parameters["E2"] = held(e2);
  h.parameters["eta2"] = held(12.0 * e2);
  const auto f = fit::fit_law(burgers(), data, h);
  BOOST_TEST(rel(f.chi_square, r.chi_square) < 1e-10);
  BOOST_TEST(rel(param(f, "E1").value, param(r, "E1").value) < 1e-7);
  // ... and moving E2 along the constraint either way raises chi^2.
  for (double factor : {1.0 - 1e-3, 1.0 + 1e-3}) {
    fit::FitOptions m;
    m.parameters["E2"] = held(e2 * factor);
    m.parameters["eta2"] = held(12.0 * e2 * factor);
    BOOST_TEST(fit::fit_law(burgers(), data, m).chi_square > r.chi_square);
  }
  // The propagated error: se(eta2) = 12 se(E2) for a linear expression.
  BOOST_TEST(rel(param(r, "eta2").std_error, 12.0 * param(r, "E2").std_error) < 1e-10);
}

BOOST_AUTO_TEST_CASE(expressions_with_powers_parentheses_and_chains) {
  const auto data = table1_row1(false);
  fit::FitOptions o;
  o.parameters["eta2"].expr = "(E2 ** 2) / (E2/12) ^ 1";  // 12 E2, written the long way
  o.parameters["E1"].expr = "-(-E2) * 0.14 + eta2 * 0";  // a chain through eta2 is allowed
  const auto r = fit::fit_law(burgers(), data, o);
  BOOST_TEST(rel(param(r, "eta2").value, 12.0 * param(r, "E2").value) < 1e-12);
  BOOST_TEST(rel(param(r, "E1").value, 0.14 * param(r, "E2").value) < 1e-12);
  BOOST_TEST(r.varying == 2);
}

BOOST_AUTO_TEST_CASE(bad_expressions_are_refused_naming_the_parameter) {
  const auto data = table1_row1(false);
  auto error = [&](std::map<std::string, std::string> exprs, fit::ParameterSetting extra = {}) {
    fit::FitOptions o;
    for (const auto& [k, v] : exprs) o.parameters[k].expr = v;
    if (extra.value) o.parameters["eta2"].value = extra.value;
    try {
      fit::fit_law(burgers(), data, o);
    } catch (const fit::FitError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  BOOST_TEST(error({{"eta2", "12*E9"}}) ==
             "law 'burgers': eta2: expression '12*E9': unknown name 'E9' (the parameters: E1, E2, eta1, eta2) at "
             "character 4");
  BOOST_TEST(error({{"eta2", "12*(E2"}}) == "law 'burgers': eta2: expression '12*(E2': ')' expected at character 7");
  BOOST_TEST(error({{"eta2", "12 E2"}}) == "law 'burgers': eta2: expression '12 E2': unexpected 'E' at character 4");
  BOOST_TEST(error({{"eta2", "1200"}}).find("names no parameter") != std::string::npos);
  BOOST_TEST(error({{"eta2", "2*E2"}, {"E2", "eta2/2"}}) ==
             "law 'burgers': the expressions refer to each other in a cycle: E2 -> eta2 -> E2");
  BOOST_TEST(error({{"eta2", "2*E2"}}, held(5.0)).find("is given by the expression '2*E2'") != std::string::npos);
}

// Maxwell, d = F/E1 + F t/eta1, is linear in c = (1/E1, 1/eta1): with absolute sigma chi^2 is
// exactly quadratic in c, so the profile of c1 is chi^2_min + (c1 - c1^)^2 / Var(c1), Var from
// (X^T W X)^-1, and the 1-sigma interval (delta chi^2 = 1) is c1^ +- sd: E1 in [1/(c1^ + sd), 1/(c1^ - sd)].
BOOST_AUTO_TEST_CASE(profile_intervals_of_a_linear_model_equal_the_closed_form) {
  const laws::StagedHistory h({{0.0, 0.4}});
  const double noise = 2e-4;
  auto data = fit::test::synthetic_curve("maxwell", {{"E1", 26.87}, {"eta1", 34807.72}}, h,
                                         fit::test::sample_times(200, 1, h), noise, 3);
  data.sigma.assign(data.t.size(), noise);
  fit::FitOptions o;
  o.scale_covariance = false;
  const auto& maxwell = laws::LawRegistry::builtin().get("maxwell");
  const auto best = fit::fit_law(maxwell, data, o);
  double a = 0, b = 0, c = 0;  // X^T W X = [[a, b], [b, c]], rows (F, F t)/sigma
  for (double t : data.t) {
    const double x1 = 0.4 / noise, x2 = 0.4 * t / noise;
    a += x1 * x1, b += x1 * x2, c += x2 * x2;
  }
  const double det = a * c - b * b, sd1 = std::sqrt(c / det), sd2 = std::sqrt(a / det);
  const double c1 = 1.0 / param(best, "E1").value, c2 = 1.0 / param(best, "eta1").value;
  const auto ci = fit::profile_intervals(maxwell, data, o, best, {1.0});
  BOOST_TEST_REQUIRE(ci.size() == 2u);
  BOOST_TEST(ci[0].name == "E1");
  // The levels are exact: chi2 quantile of 1 dof at erf(1/sqrt 2) is 1.
  BOOST_TEST(std::abs(ci[0].levels[0].chi_square - best.chi_square - 1.0) < 1e-9);
  BOOST_TEST(rel(ci[0].levels[0].lower, 1.0 / (c1 + sd1)) < 1e-8);
  BOOST_TEST(rel(ci[0].levels[0].upper, 1.0 / (c1 - sd1)) < 1e-8);
  BOOST_TEST(rel(ci[1].levels[0].lower, 1.0 / (c2 + sd2)) < 1e-8);
  BOOST_TEST(rel(ci[1].levels[0].upper, 1.0 / (c2 - sd2)) < 1e-8);
  BOOST_TEST(ci[0].levels[0].lower_found);
}

BOOST_AUTO_TEST_CASE(a_profile_interval_stops_at_a_bound) {
  fit::FitOptions o;
  o.parameters["eta2"].max = 1000.0;
  const auto data = table1_row1(false);
  const auto best = fit::fit_law(burgers(), data, o);
  const auto ci = fit::profile_intervals(burgers(), data, o, best, {1.0}, {"eta2"});
  BOOST_TEST(ci[0].levels[0].upper == 1000.0);
  BOOST_TEST(!ci[0].levels[0].upper_found);
  BOOST_TEST(ci[0].levels[0].lower < 1000.0);
  BOOST_TEST(ci[0].levels[0].lower_found);
}

BOOST_AUTO_TEST_SUITE_END()
