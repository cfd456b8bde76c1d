// The user's settings of a fit (fit::ParameterSetting, measurement sigma):
// fixed parameters, bounds, initial values, weights and absolute sigma, each
// checked against a closed form of least squares or against a second fit that
// must give the same answer (docs/guide/fitting.md, "Initial values, bounds, fixed
// parameters and weights"). lmfit itself is the reference of
// tests/python/test_fit_lmfit.py.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <sstream>

#include "rheodda/fit/fit.hpp"
#include "synthetic.hpp"

namespace {

using namespace rheodda;
using rheodda::fit::test::kTable1;

const laws::LawInfo& burgers() { return laws::LawRegistry::builtin().get("burgers"); }

// Table 1 row 1 under its stress, 0..200 h every hour, with 2e-4 mm of noise
// (about 1.5% of the 0.014 mm curve: every parameter keeps a standard error).
fit::CreepData noisy_row1() {
  const laws::StagedHistory h({{0.0, kTable1[0].tau}});
  return fit::test::synthetic_curve("burgers", fit::test::burgers_values(kTable1[0]), h,
                                    fit::test::sample_times(200, 1, h), 2e-4, 7);
}

const fit::ParameterEstimate& param(const fit::FitResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p;
  throw std::runtime_error("no parameter " + name);
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

fit::FitOptions with(const std::string& name, fit::ParameterSetting s) {
  fit::FitOptions o;
  o.parameters[name] = s;
  return o;
}

std::string fit_error(const fit::CreepData& data, const fit::FitOptions& o) {
  try {
    fit::fit_law(burgers(), data, o);
  } catch (const fit::FitError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(fit_settings)

BOOST_AUTO_TEST_CASE(a_fixed_parameter_is_held_and_the_others_recovered) {
  const laws::StagedHistory h({{0.0, kTable1[0].tau}});
  const auto truth = fit::test::burgers_values(kTable1[0]);
  const auto data = fit::test::synthetic_curve("burgers", truth, h, fit::test::sample_times(200, 1, h));
  fit::ParameterSetting fix;
  fix.value = truth.at("E1");
  fix.vary = false;
  const auto r = fit::fit_law(burgers(), data, with("E1", fix));
  BOOST_TEST(r.converged);
  BOOST_TEST(r.varying == 3);
  BOOST_TEST(!param(r, "E1").vary);
  BOOST_TEST(param(r, "E1").value == truth.at("E1"));  // exactly the given value
  BOOST_TEST(param(r, "E1").std_error == 0.0);
  BOOST_TEST(std::isnan(r.correlation_at(0, 1)));
  // Noise-free: the other three come back to the 1e-6 of the unconstrained fit (recovery_test.cpp).
  for (const char* name : {"E2", "eta1", "eta2"}) BOOST_TEST(rel(param(r, name).value, truth.at(name)) < 1e-6, name);
  // AIC and BIC count the varying parameters only: n ln(RSS/n) + 2k, + k ln n, k = 3.
  const double n = static_cast<double>(r.points);
  BOOST_TEST(r.aic == n * std::log(r.rss / n) + 2.0 * 3.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.bic == n * std::log(r.rss / n) + 3.0 * std::log(n), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(bounds_that_do_not_bind_change_nothing) {
  const auto data = noisy_row1();
  const auto free = fit::fit_law(burgers(), data);
  fit::FitOptions o;
  for (const auto& p : free.parameters) {
    fit::ParameterSetting s;
    s.min = 0.3 * p.value;
    s.max = 3.0 * p.value;
    o.parameters[p.name] = s;
  }
  const auto r = fit::fit_law(burgers(), data, o);
  // The same minimum reached through MINUIT's transforms: values to the solver's
  // step tolerance (1e-10 in log, loosened to 1e-7 for the different path), the
  // errors (the same Jacobian at the same point) to 1e-5.
  for (const auto& p : free.parameters) {
    BOOST_TEST_CONTEXT(p.name) {
      BOOST_TEST(param(r, p.name).at_bound.empty());
      BOOST_TEST(rel(param(r, p.name).value, p.value) < 1e-7);
      BOOST_TEST(rel(param(r, p.name).std_error, p.std_error) < 1e-5);
      BOOST_TEST(param(r, p.name).min == 0.3 * p.value);
    }
  }
  BOOST_TEST(rel(r.rss, free.rss) < 1e-10);
}

BOOST_AUTO_TEST_CASE(a_binding_bound_holds_the_parameter_as_fixing_it_there_would) {
  const auto data = noisy_row1();
  const double cap = 0.8 * kTable1[0].E2;
  fit::ParameterSetting b;
  b.max = cap;
  b.min = 10.0;
  const auto bounded = fit::fit_law(burgers(), data, with("E2", b));
  BOOST_TEST(param(bounded, "E2").at_bound == "max");
  BOOST_TEST(param(bounded, "E2").value == cap);
  BOOST_TEST(param(bounded, "E2").std_error == 0.0);
  bool warned = false;
  for (const auto& w : bounded.warnings) warned = warned || w.find("E2 ended on its bound max") != std::string::npos;
  BOOST_TEST(warned);
  fit::ParameterSetting fix;
  fix.value = cap;
  fix.vary = false;
  const auto fixed = fit::fit_law(burgers(), data, with("E2", fix));
  // The two are the same least-squares problem once E2 sits on the bound; the
  // errors differ only by the residual spread s = sqrt(chi^2/(n - k)): the bounded
  // fit varied E2 (k = 4, as lmfit counts it), the fixed one did not (k = 3).
  const double n = static_cast<double>(bounded.points);
  const double k_ratio = std::sqrt((n - 3.0) / (n - 4.0));
  for (const char* name : {"E1", "eta1", "eta2"}) {
    BOOST_TEST_CONTEXT(name) {
      BOOST_TEST(rel(param(bounded, name).value, param(fixed, name).value) < 1e-6);
      BOOST_TEST(rel(param(bounded, name).std_error, param(fixed, name).std_error * k_ratio) < 1e-5);
    }
  }
  BOOST_TEST(rel(bounded.rss, fixed.rss) < 1e-8);
  // k: the bounded fit varied E2, the fixed one did not.
  BOOST_TEST(bounded.varying == 4);
  BOOST_TEST(fixed.varying == 3);
}

BOOST_AUTO_TEST_CASE(an_initial_value_is_the_first_start_and_reaches_the_same_minimum) {
  const auto data = noisy_row1();
  const auto free = fit::fit_law(burgers(), data);
  fit::ParameterSetting s;
  s.value = 10.0 * kTable1[0].eta2;
  const auto r = fit::fit_law(burgers(), data, with("eta2", s));
  BOOST_TEST(r.starts == free.starts + 1);  // the user's start comes on top
  BOOST_TEST(rel(r.rss, free.rss) < 1e-10);
  for (const auto& p : free.parameters) BOOST_TEST(rel(param(r, p.name).value, p.value) < 1e-6, p.name);
  BOOST_TEST(r.start_minima.size() == static_cast<std::size_t>(r.starts));
}

BOOST_AUTO_TEST_CASE(a_constant_sigma_scales_chi_square_and_leaves_the_fit) {
  const auto data = noisy_row1();
  const auto plain = fit::fit_law(burgers(), data);
  auto weighted = data;
  const double sigma = 2e-4;  // [mm], the noise of the curve
  weighted.sigma.assign(data.t.size(), sigma);
  const auto r = fit::fit_law(burgers(), weighted);
  BOOST_TEST(r.weighted);
  // Weighted least squares with equal weights is ordinary least squares:
  // the same values, chi^2 = RSS / sigma^2, the same (scaled) standard errors.
  BOOST_TEST(rel(r.chi_square, plain.rss / (sigma * sigma)) < 1e-9);
  BOOST_TEST(rel(r.rss, plain.rss) < 1e-9);
  for (const auto& p : plain.parameters) {
    BOOST_TEST(rel(param(r, p.name).value, p.value) < 1e-7, p.name);
    BOOST_TEST(rel(param(r, p.name).std_error, p.std_error) < 1e-5, p.name);
  }
  // Absolute sigma: cov = (J^T J)^-1 of the residuals / sigma, i.e. the scaled
  // errors divided by sqrt(reduced chi-square) (curve_fit's absolute_sigma).
  fit::FitOptions abs;
  abs.scale_covariance = false;
  const auto a = fit::fit_law(burgers(), weighted, abs);
  BOOST_TEST(!a.scale_covariance);
  for (const auto& p : r.parameters)
    BOOST_TEST(rel(param(a, p.name).std_error, p.std_error / std::sqrt(r.reduced_chi_square)) < 1e-6, p.name);
  // The noise was drawn with this sigma: reduced chi-square near 1 (201 points: 1 +- 0.1).
  BOOST_TEST(std::abs(r.reduced_chi_square - 1.0) < 0.3);
}

BOOST_AUTO_TEST_CASE(weights_follow_sigma_point_by_point) {
  // Points with a huge sigma do not count: the fit equals the fit of the others alone.
  const auto data = noisy_row1();
  auto weighted = data;
  fit::CreepData kept = data;
  kept.t.clear();
  kept.displacement.clear();
  kept.line.clear();
  for (std::size_t j = 0; j < data.t.size(); ++j) {
    const bool keep = j < 120;
    weighted.sigma.push_back(keep ? 2e-4 : 2e-4 * 1e6);
    if (keep) {
      kept.t.push_back(data.t[j]);
      kept.displacement.push_back(data.displacement[j]);
      kept.line.push_back(data.line[j]);
    }
  }
  kept.stages.front().count = kept.t.size();
  const auto r = fit::fit_law(burgers(), weighted);
  const auto k = fit::fit_law(burgers(), kept);
  // The far points weigh 1e-12 of the others in the sum: values within 1e-5.
  for (const auto& p : k.parameters) BOOST_TEST(rel(param(r, p.name).value, p.value) < 1e-5, p.name);
}

BOOST_AUTO_TEST_CASE(bad_settings_are_refused_naming_the_parameter) {
  const auto data = noisy_row1();
  fit::ParameterSetting s;
  s.value = 1.0;
  BOOST_TEST(fit_error(data, with("E9", s)).find("law 'burgers' has no parameter 'E9' (its parameters: E1, E2, "
                                                 "eta1, eta2)") != std::string::npos);
  s.min = 2.0;
  BOOST_TEST(fit_error(data, with("E1", s)).find("E1: value 1 is outside its bounds [2, inf]") != std::string::npos);
  fit::ParameterSetting e;
  e.min = 5.0;
  e.max = 5.0;
  BOOST_TEST(fit_error(data, with("E1", e)).find("E1: the bounds [5, 5] are empty") != std::string::npos);
  fit::ParameterSetting neg;
  neg.min = -1.0;
  BOOST_TEST(fit_error(data, with("E1", neg)).find("E1: min -1 is not a finite number >= 0") != std::string::npos);
  fit::ParameterSetting novalue;
  novalue.vary = false;
  BOOST_TEST(fit_error(data, with("E1", novalue)).find("E1 is fixed (vary = false) but has no value") !=
             std::string::npos);
  fit::ParameterSetting zero;
  zero.value = 0.0;
  BOOST_TEST(fit_error(data, with("eta1", zero)).find("eta1: value 0 is not a finite positive number") !=
             std::string::npos);
  fit::FitOptions all;
  for (const char* n : {"E1", "E2", "eta1", "eta2"}) {
    fit::ParameterSetting f;
    f.value = 1.0;
    f.vary = false;
    all.parameters[n] = f;
  }
  BOOST_TEST(fit_error(data, all).find("every parameter is fixed") != std::string::npos);
  fit::FitOptions abs;
  abs.scale_covariance = false;
  BOOST_TEST(fit_error(data, abs).find("need the measurement sigma") != std::string::npos);
  auto bad_sigma = data;
  bad_sigma.sigma.assign(3, 1.0);
  BOOST_TEST(fit_error(bad_sigma, {}).find("3 sigma values for 201 points") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(sigma_column_is_read_and_checked_with_file_line_and_column) {
  fit::CsvOptions o;
  o.stress = laws::StagedHistory({{0.0, 0.232}});
  o.sigma_column = "err";
  std::istringstream good("t,displacement,err\n0,0.01,1e-4\n1,0.011,2e-4\n");
  const auto d = fit::parse_creep_csv(good, "g.csv", o);
  BOOST_TEST(d.sigma.size() == 2u);
  BOOST_TEST(d.sigma[1] == 2e-4);
  BOOST_TEST(d.sigma_column == "err");
  std::istringstream bad("t,displacement,err\n0,0.01,1e-4\n1,0.011,0\n");
  try {
    fit::parse_creep_csv(bad, "b.csv", o);
    BOOST_FAIL("no error");
  } catch (const fit::DataError& e) {
    BOOST_TEST(std::string(e.what()) ==
               "b.csv:3: column 'err': sigma 0 is not positive; a measurement standard deviation is > 0");
  }
  std::istringstream missing("t,displacement\n0,0.01\n");
  try {
    fit::parse_creep_csv(missing, "m.csv", o);
    BOOST_FAIL("no error");
  } catch (const fit::DataError& e) {
    BOOST_TEST(std::string(e.what()).find("m.csv:1: column 'err': no such column in the header (set it with "
                                          "--sigma-column)") == 0);
  }
}

BOOST_AUTO_TEST_SUITE_END()
