// Fits recover the parameters that generated a synthetic curve: exactly
// (relative 1e-6) without noise, within two reported standard errors with
// noise; single-stage and multi-stage (loading steps and unloading) histories.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>

#include "rheodda/fit/fit.hpp"
#include "synthetic.hpp"

namespace {

using namespace rheodda;
using rheodda::fit::test::kTable1;

const laws::LawInfo& law_info(const std::string& name) {
  return laws::LawRegistry::builtin().get(name);
}

void check_exact(const fit::FitResult& r, const laws::ParameterValues& truth) {
  for (const auto& p : r.parameters) {
    BOOST_TEST_CONTEXT(r.law << " " << p.name) {
      BOOST_TEST(std::abs(p.value - truth.at(p.name)) <= 1e-6 * truth.at(p.name),
                 "fitted " << p.value << " vs true " << truth.at(p.name));
    }
  }
  BOOST_TEST(r.r2 > 1.0 - 1e-12);
}

void check_two_sigma(const fit::FitResult& r, const laws::ParameterValues& truth) {
  for (const auto& p : r.parameters) {
    BOOST_TEST_CONTEXT(r.law << " " << p.name) {
      BOOST_TEST(p.identifiable);
      BOOST_TEST(p.std_error > 0.0);
      BOOST_TEST(std::abs(p.value - truth.at(p.name)) <= 2.0 * p.std_error,
                 "fitted " << p.value << " +- " << p.std_error << " vs true " << truth.at(p.name));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(fit_recovery)

BOOST_AUTO_TEST_CASE(burgers_table1_rows_recovered_exactly_without_noise) {
  for (const auto& row : kTable1) {
    const laws::StagedHistory h({{0.0, row.tau}});
    const auto truth = fit::test::burgers_values(row);
    const auto data = fit::test::synthetic_curve("burgers", truth, h, fit::test::sample_times(200, 1, h));
    const auto r = fit::fit_law(law_info("burgers"), data);
    BOOST_TEST(r.converged);
    check_exact(r, truth);
  }
}

BOOST_AUTO_TEST_CASE(burgers_table1_rows_recovered_within_two_sigma_with_noise) {
  unsigned seed = 11;
  for (const auto& row : kTable1) {
    const laws::StagedHistory h({{0.0, row.tau}});
    const auto truth = fit::test::burgers_values(row);
    // 2e-5 mm noise on a curve of about 0.01 mm: a good displacement transducer.
    const auto data = fit::test::synthetic_curve("burgers", truth, h,
                                                 fit::test::sample_times(200, 0.5, h), 2e-5, seed++);
    const auto r = fit::fit_law(law_info("burgers"), data);
    BOOST_TEST(r.converged);
    check_two_sigma(r, truth);
    // The residual scatter is the noise that was added.
    BOOST_TEST(std::abs(r.rmse - 2e-5) <= 0.2 * 2e-5);
    BOOST_TEST(r.warnings.empty(), "unexpected warning: " << (r.warnings.empty() ? "" : r.warnings[0]));
  }
}

BOOST_AUTO_TEST_CASE(every_linear_law_recovered_exactly_without_noise) {
  const laws::StagedHistory h({{0.0, 0.3}});
  const std::vector<std::pair<std::string, laws::ParameterValues>> cases = {
      {"maxwell", {{"E1", 30.0}, {"eta1", 20000.0}}},
      {"kelvin", {{"E2", 50.0}, {"eta2", 1500.0}}},
      {"generalized-kelvin",
       {{"E1", 30.0}, {"E2", 200.0}, {"eta2", 400.0}, {"E3", 80.0}, {"eta3", 4000.0}}},
  };
  for (const auto& [law, truth] : cases) {
    const auto data = fit::test::synthetic_curve(law, truth, h, fit::test::sample_times(200, 1, h));
    check_exact(fit::fit_law(law_info(law), data), truth);
  }
}

BOOST_AUTO_TEST_CASE(every_linear_law_recovered_within_two_sigma_with_noise) {
  const laws::StagedHistory h({{0.0, 0.3}});
  const std::vector<std::pair<std::string, laws::ParameterValues>> cases = {
      {"maxwell", {{"E1", 30.0}, {"eta1", 20000.0}}},
      {"kelvin", {{"E2", 50.0}, {"eta2", 1500.0}}},
      {"generalized-kelvin",
       {{"E1", 30.0}, {"E2", 200.0}, {"eta2", 400.0}, {"E3", 80.0}, {"eta3", 4000.0}}},
  };
  unsigned seed = 21;
  for (const auto& [law, truth] : cases) {
    const auto data = fit::test::synthetic_curve(law, truth, h, fit::test::sample_times(200, 0.5, h),
                                                 2e-5, seed++);
    check_two_sigma(fit::fit_law(law_info(law), data), truth);
  }
}

BOOST_AUTO_TEST_CASE(multi_stage_burgers_with_unloading_recovered_by_superposition) {
  // Table 1 row 1 loaded in two steps, then unloaded: the fit sees all stages at once.
  const laws::StagedHistory h({{0.0, 0.232}, {100.0, 0.424}, {200.0, 0.0}});
  const auto truth = fit::test::burgers_values(kTable1[0]);
  const auto times = fit::test::sample_times(300, 1, h);
  check_exact(fit::fit_law(law_info("burgers"), fit::test::synthetic_curve("burgers", truth, h, times)),
              truth);
  const auto noisy = fit::test::synthetic_curve("burgers", truth, h, times, 2e-5, 7);
  const auto r = fit::fit_law(law_info("burgers"), noisy);
  check_two_sigma(r, truth);
  // The unloading branch is fitted, not dropped: its residuals are noise-sized.
  double worst = 0.0;
  for (std::size_t j = noisy.stages[2].first; j < noisy.t.size(); ++j)
    worst = std::max(worst, std::abs(r.fitted[j] - noisy.displacement[j]));
  BOOST_TEST(worst < 5 * 2e-5);
}

BOOST_AUTO_TEST_CASE(multi_stage_nishihara_below_and_above_threshold_recovered) {
  // Stages below and above Fs = 0.3, then unloading: the Bingham flow only in stage 3.
  const laws::StagedHistory h({{0.0, 0.2}, {100.0, 0.4}, {200.0, 0.6}, {300.0, 0.0}});
  const laws::ParameterValues truth{{"E1", 30.0}, {"E2", 200.0}, {"eta2", 2000.0},
                                    {"eta3", 30000.0}, {"Fs", 0.3}};
  const auto times = fit::test::sample_times(400, 1, h);
  check_exact(fit::fit_law(law_info("nishihara"),
                           fit::test::synthetic_curve("nishihara", truth, h, times)),
              truth);
  check_two_sigma(fit::fit_law(law_info("nishihara"),
                               fit::test::synthetic_curve("nishihara", truth, h, times, 2e-5, 3)),
                  truth);
}

BOOST_AUTO_TEST_CASE(fitted_curve_equals_exact_law_response) {
  // FitResult::fitted is the law's exact staged response at the fitted parameters.
  const laws::StagedHistory h({{0.0, 0.232}, {100.0, 0.424}});
  const auto truth = fit::test::burgers_values(kTable1[0]);
  const auto data = fit::test::synthetic_curve("burgers", truth, h, fit::test::sample_times(150, 1, h),
                                               2e-5, 5);
  const auto r = fit::fit_law(law_info("burgers"), data);
  const auto law = laws::LawRegistry::builtin().create("burgers", r.values());
  const auto expected = fit::predict(*law, h, data.t);
  for (std::size_t j = 0; j < data.t.size(); ++j)
    BOOST_TEST(std::abs(r.fitted[j] - expected[j]) <= 1e-12 * std::abs(expected[j]) + 1e-15);
}

namespace {
// A law that is not a SeriesLaw (it wraps one), as a law added later might be:
// the fit falls back on laws::exact_displacement with finite-difference derivatives.
class Wrapped final : public laws::ContactRheology {
 public:
  explicit Wrapped(const laws::ParameterValues& p)
      : inner_(laws::LawRegistry::builtin().create("burgers", p)) {}
  std::string_view name() const override { return "wrapped-burgers"; }
  const laws::ParameterValues& parameters() const override { return inner_->parameters(); }
  int internal_count() const override { return inner_->internal_count(); }
  std::optional<double> instantaneous_stiffness() const override {
    return inner_->instantaneous_stiffness();
  }
  bool is_linear() const override { return true; }
  laws::StepConstants step_constants(double dt, laws::Scheme s) const override {
    return inner_->step_constants(dt, s);
  }
  laws::Linearization linearize(const laws::StepConstants& k, const laws::RheologyState& old,
                                double fs, double fe) const override {
    return inner_->linearize(k, old, fs, fe);
  }
  double advance(const laws::StepConstants& k, const laws::RheologyState& old, double fs, double fe,
                 laws::RheologyState& next) const override {
    return inner_->advance(k, old, fs, fe, next);
  }
  double creep_closed_form(double force, double t) const override {
    return inner_->creep_closed_form(force, t);
  }

 private:
  std::unique_ptr<laws::ContactRheology> inner_;
};
}  // namespace

BOOST_AUTO_TEST_CASE(law_of_another_shape_fitted_through_its_exact_response) {
  laws::LawInfo info = law_info("burgers");
  info.name = "wrapped-burgers";
  info.make = [](const laws::ParameterValues& p) -> std::unique_ptr<laws::ContactRheology> {
    return std::make_unique<Wrapped>(p);
  };
  const laws::StagedHistory h({{0.0, 0.232}, {100.0, 0.424}, {200.0, 0.0}});
  const auto truth = fit::test::burgers_values(kTable1[0]);
  const auto times = fit::test::sample_times(300, 1, h);
  check_exact(fit::fit_law(info, fit::test::synthetic_curve("burgers", truth, h, times)), truth);
  check_two_sigma(fit::fit_law(info, fit::test::synthetic_curve("burgers", truth, h, times, 2e-5, 8)),
                  truth);
}

BOOST_AUTO_TEST_SUITE_END()
