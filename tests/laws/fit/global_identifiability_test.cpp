// The global minimum and honest error bars (issue 18; docs/guide/fitting.md, "How the
// minimum is found" and "Identifiability"): the variable-projection search
// never ends in a local minimum where a 20-start classic search finds a lower
// one; parameters the data cannot fix get no standard error, and the
// combinations the data do fix are reported with theirs; R^2 is undefined on a
// curve without spread; a minimum reached by one start only is flagged.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "rheodda/fit/fit.hpp"
#include "synthetic.hpp"

namespace {

using namespace rheodda;

const laws::LawInfo& law_info(const std::string& name) { return laws::LawRegistry::builtin().get(name); }

const fit::ParameterEstimate& param(const fit::FitResult& r, const std::string& name) {
  return *std::find_if(r.parameters.begin(), r.parameters.end(),
                       [&](const fit::ParameterEstimate& p) { return p.name == name; });
}

bool any_warning_contains(const fit::FitResult& r, const std::string& text) {
  return std::any_of(r.warnings.begin(), r.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

const laws::ParameterValues kNishihara{{"E1", 30.0}, {"E2", 200.0}, {"eta2", 2000.0},
                                       {"eta3", 5000.0}, {"Fs", 0.1}};

}  // namespace

BOOST_AUTO_TEST_SUITE(fit_global_identifiability)

BOOST_AUTO_TEST_CASE(single_stage_nishihara_flags_eta3_and_fs_and_reports_their_fixed_combination) {
  // Under one stress F the Bingham term is (F - Fs) t/eta3: only (F - Fs)/eta3
  // is in the data, 2e-5 here (F = 0.2); eta3 and Fs each get no standard error.
  const laws::StagedHistory h({{0.0, 0.2}});
  const double rate = (0.2 - 0.1) / 5000.0;
  const auto times = fit::test::sample_times(200, 1, h);
  for (const double noise : {0.0, 2e-5}) {
    BOOST_TEST_CONTEXT("noise " << noise) {
      const auto data = fit::test::synthetic_curve("nishihara", kNishihara, h, times, noise, 17);
      const auto r = fit::fit_law(law_info("nishihara"), data);
      for (const char* name : {"eta3", "Fs"}) {
        BOOST_TEST(!param(r, name).identifiable, name);
        BOOST_TEST(param(r, name).std_error == 0.0, name);
        BOOST_TEST(!param(r, name).reason.empty(), name);
      }
      for (const char* name : {"E1", "E2", "eta2"}) BOOST_TEST(param(r, name).identifiable, name);
      BOOST_TEST(any_warning_contains(r, "eta3 and Fs are not identifiable"));
      const auto c = std::find_if(r.combinations.begin(), r.combinations.end(),
                                  [](const fit::FixedCombination& f) { return f.expression == "(0.2 - Fs)/eta3"; });
      BOOST_TEST_REQUIRE((c != r.combinations.end()));
      BOOST_TEST(c->unit == "length/time");
      BOOST_TEST((c->parameters == std::vector<std::string>{"eta3", "Fs"}));
      // The combination equals its value at the fitted parameters...
      BOOST_TEST(std::abs(c->value - (0.2 - param(r, "Fs").value) / param(r, "eta3").value) <=
                 1e-12 * c->value);
      if (noise == 0.0) {
        BOOST_TEST(std::abs(c->value - rate) <= 1e-6 * rate);  // ...and the truth exactly without noise
      } else {
        BOOST_TEST(c->std_error > 0.0);
        BOOST_TEST(c->std_error < 0.05 * rate);
        BOOST_TEST(std::abs(c->value - rate) <= 2.0 * c->std_error,
                   c->value << " +- " << c->std_error << " vs " << rate);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(staged_nishihara_300_noise_draws_never_end_in_a_local_minimum) {
  // Loading below and above the threshold Fs = 0.3, then unloading, 1 % noise:
  // the classic 5-start search ends in a local minimum in some draws (checked
  // below, so the case has local minima); the default fit never does.
  const laws::StagedHistory h({{0.0, 0.2}, {100.0, 0.4}, {200.0, 0.6}, {300.0, 0.0}});
  const laws::ParameterValues truth{{"E1", 30.0}, {"E2", 200.0}, {"eta2", 2000.0},
                                    {"eta3", 30000.0}, {"Fs", 0.3}};
  const auto times = fit::test::sample_times(400, 4, h);
  const auto clean = fit::test::synthetic_curve("nishihara", truth, h, times);
  const double noise = 0.01 * *std::max_element(clean.displacement.begin(), clean.displacement.end());
  fit::FitOptions reference;
  reference.structured_search = false;
  reference.restarts = 19;
  fit::FitOptions classic;
  classic.structured_search = false;
  int misses = 0, reference_misses = 0, classic_misses = 0;
  for (unsigned seed = 0; seed < 300; ++seed) {
    const auto data = fit::test::synthetic_curve("nishihara", truth, h, times, noise, 5000 + seed);
    const auto ours = fit::fit_law(law_info("nishihara"), data);
    const auto ref = fit::fit_law(law_info("nishihara"), data, reference);
    const auto old = fit::fit_law(law_info("nishihara"), data, classic);
    misses += ours.rss > ref.rss * (1.0 + 1e-6);
    reference_misses += ref.rss > ours.rss * (1.0 + 1e-6);
    // A distinct minimum: 0.1 % above the best (GSL alone stops within 1e-5 of a kink minimum).
    classic_misses += old.rss > std::min(ours.rss, ref.rss) * (1.0 + 1e-3);
  }
  BOOST_TEST(misses == 0);
  BOOST_TEST_MESSAGE("reference above the default fit in " << reference_misses << " draws; classic 5 starts in "
                                                           << classic_misses);
  BOOST_TEST(classic_misses > 0);
}

BOOST_AUTO_TEST_CASE(curve_without_time_dependence_flags_every_time_parameter_of_every_law) {
  // d(t) = F/E1 at every reading: no creep, so no viscosity (nor the
  // threshold) is in the data; R^2 has no spread to refer to.
  const laws::StagedHistory h({{0.0, 0.3}});
  const auto times = fit::test::sample_times(200, 1, h);
  fit::CreepData data = fit::test::synthetic_curve("maxwell", {{"E1", 30.0}, {"eta1", 1e4}}, h, times);
  data.displacement.assign(times.size(), 0.3 / 30.0);
  for (const auto& info : laws::LawRegistry::builtin().laws()) {
    if (!info.fittable) continue;  // the nonlinear laws: model_selection_test
    BOOST_TEST_CONTEXT(info.name) {
      const auto r = fit::fit_law(info, data);
      BOOST_TEST(!r.r2_defined());
      for (const auto& p : r.parameters) {
        if (p.unit.find("time") == std::string::npos && p.name != "Fs") continue;
        BOOST_TEST(!p.identifiable, p.name);
        BOOST_TEST(p.std_error == 0.0, p.name);
        BOOST_TEST(any_warning_contains(r, p.name), p.name);
      }
      if (info.name != "kelvin") {  // the jump is E1's
        BOOST_TEST(param(r, "E1").identifiable);
        BOOST_TEST(std::abs(param(r, "E1").value - 30.0) <= 1e-6 * 30.0);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(r2_is_defined_as_soon_as_the_data_have_spread) {
  const laws::StagedHistory h({{0.0, 0.232}});
  const auto data = fit::test::synthetic_curve("burgers", fit::test::burgers_values(fit::test::kTable1[0]), h,
                                               fit::test::sample_times(200, 1, h), 2e-5, 4);
  const auto r = fit::fit_law(law_info("burgers"), data);
  BOOST_TEST(r.r2_defined());
  BOOST_TEST(r.r2 > 0.99);
}

BOOST_AUTO_TEST_CASE(minimum_from_one_start_only_is_not_certain_and_says_so) {
  const laws::StagedHistory h({{0.0, 0.232}});
  const auto data = fit::test::synthetic_curve("burgers", fit::test::burgers_values(fit::test::kTable1[0]), h,
                                               fit::test::sample_times(200, 1, h), 2e-5, 4);
  fit::FitOptions one;
  one.structured_search = false;
  one.restarts = 0;
  const auto r = fit::fit_law(law_info("burgers"), data, one);
  BOOST_TEST(r.starts == 1);
  BOOST_TEST(!r.minimum_certain);
  BOOST_TEST(any_warning_contains(r, "the minimum is not certain"));
  // The default search: variable-projection start(s) plus the classic ones, which agree.
  const auto d = fit::fit_law(law_info("burgers"), data);
  BOOST_TEST(d.structured_starts >= 1);
  BOOST_TEST(d.starts_agreeing >= 2);
  BOOST_TEST(d.minimum_certain);
  BOOST_TEST(d.minimum_note.empty());
  BOOST_TEST(std::abs(d.rss - r.rss) <= 1e-6 * r.rss);
}

BOOST_AUTO_TEST_CASE(identified_parameters_keep_their_standard_errors_next_to_a_dropped_pair) {
  // Single-stage Nishihara on a Burgers-like curve: E1, E2, eta2 get the same
  // standard errors as the Burgers fit (the Bingham term plays the dashpot), not
  // errors conditioned on a fixed eta3 or Fs.
  const laws::StagedHistory h({{0.0, 0.2}});
  const auto data = fit::test::synthetic_curve("nishihara", kNishihara, h, fit::test::sample_times(200, 1, h),
                                               2e-5, 23);
  const auto n = fit::fit_law(law_info("nishihara"), data);
  const auto b = fit::fit_law(law_info("burgers"), data);
  for (const char* name : {"E1", "E2", "eta2"}) {
    BOOST_TEST(std::abs(param(n, name).value - param(b, name).value) <= 1e-5 * param(b, name).value, name);
    BOOST_TEST(std::abs(param(n, name).std_error - param(b, name).std_error) <=
                   0.01 * param(b, name).std_error,
               name << ": " << param(n, name).std_error << " vs " << param(b, name).std_error);
  }
}

BOOST_AUTO_TEST_CASE(ramp_of_many_stages_is_fitted_exactly_through_the_stage_sums) {
  // A loading ramp recorded as 60 stages, then held and unloaded: the model
  // carries its sums over earlier stages from stage to stage (O(1) per point);
  // its curve equals laws::exact_displacement and the fit recovers the law.
  std::vector<laws::StagedHistory::Stage> stages;
  for (int i = 0; i < 60; ++i) stages.push_back({0.5 * i, 0.005 * (i + 1)});
  stages.push_back({150.0, 0.0});
  const laws::StagedHistory h(stages);
  const auto truth = fit::test::burgers_values(fit::test::kTable1[0]);
  const auto data = fit::test::synthetic_curve("burgers", truth, h, fit::test::sample_times(250, 0.25, h));
  const auto r = fit::fit_law(law_info("burgers"), data);
  for (const auto& p : r.parameters)
    BOOST_TEST(std::abs(p.value - truth.at(p.name)) <= 1e-6 * truth.at(p.name), p.name);
  const auto law = laws::LawRegistry::builtin().create("burgers", r.values());
  const auto expected = fit::predict(*law, h, data.t);
  for (std::size_t j = 0; j < data.t.size(); ++j)
    BOOST_TEST(std::abs(r.fitted[j] - expected[j]) <= 1e-12 * std::abs(expected[j]) + 1e-15, "t = " << data.t[j]);
}

BOOST_AUTO_TEST_SUITE_END()
