// `rheodda forecast` (docs/guide/forecast.md): the draws follow the fit's covariance on ln p,
// unidentified parameters are handled as asked, non-physical draws are rejected and
// counted, units convert, and on the two-block creep test the ensemble's bands equal
// the Burgers closed form evaluated with the same parameter samples.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../scene/test_support.hpp"
#include "rheodda/forecast/forecast.hpp"

namespace fc = rheodda::forecast;
namespace fs = std::filesystem;
using rheodda::test::fresh_dir;
using rheodda::test::read_text;
using rheodda::test::run_rheodda;
using rheodda::test::source_path;

namespace {

/// A Burgers fit as `rheodda fit --json` would report it (units MPa, mm, h).
fc::FittedLaw burgers_fit() {
  fc::FittedLaw f;
  f.file = "fit.json";
  f.law = "burgers";
  f.names = {"E1", "E2", "eta1", "eta2"};
  f.dimensions = {"stress/length", "stress/length", "stress*time/length", "stress*time/length"};
  f.units = {"MPa/mm", "MPa/mm", "MPa*h/mm", "MPa*h/mm"};
  f.values = {26.87, 192.43, 34807.72, 2141.23};
  f.identifiable = {true, true, true, true};
  f.log_std = {0.1, 0.2, 0.05, 0.3};
  f.correlation = {1.0, 0.6, 0.0, 0.0,  //
                   0.6, 1.0, 0.0, 0.0,  //
                   0.0, 0.0, 1.0, -0.4,  //
                   0.0, 0.0, -0.4, 1.0};
  f.stress_unit = "MPa";
  f.length_unit = "mm";
  f.time_unit = "h";
  return f;
}

/// A CSV file as rows of column -> number (lines starting with '#' skipped).
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  const auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::string cur;
    for (char ch : l) {
      if (ch == ',') { f.push_back(cur); cur.clear(); }
      else cur += ch;
    }
    f.push_back(cur);
    return f;
  };
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) { header = split(line); continue; }
    const auto f = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(forecast)

BOOST_AUTO_TEST_CASE(percentiles_interpolate_between_order_statistics_as_numpy_does) {
  std::vector<double> v{4, 1, 3, 2};
  BOOST_TEST(fc::percentile(v, 50) == 2.5);
  BOOST_TEST(fc::percentile(v, 5) == 1.15, boost::test_tools::tolerance(1e-14));  // h = 3 * 0.05 = 0.15
  BOOST_TEST(fc::percentile(v, 100) == 4.0);
  BOOST_TEST(fc::percentile(v, 0) == 1.0);
}

BOOST_AUTO_TEST_CASE(fitted_parameters_convert_from_the_reports_units_to_the_scenes) {
  const auto f = burgers_fit();
  // MPa/mm -> N/m^2/m: 1e6 / 1e-3; MPa*h/mm -> N/m^2*d/m: 1e9 / 24.
  BOOST_TEST(fc::unit_factor("stress/length", f, "m", "N", "d") == 1e9, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(fc::unit_factor("stress*time/length", f, "m", "N", "d") == 1e9 / 24, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(fc::unit_factor("stress", f, "mm", "N", "h") == 1.0, boost::test_tools::tolerance(1e-14));  // N/mm^2 = MPa
  // UDUNITS-2 (rheodda::units) does the conversion: any unit it knows, none of another dimension.
  BOOST_TEST(fc::unit_factor("stress*time/length", f, "km", "kN", "min") == 1e9 * 60.0 * 1e6, boost::test_tools::tolerance(1e-14));
  BOOST_CHECK_THROW(fc::unit_factor("stress", f, "blorp", "N", "h"), std::invalid_argument);  // unknown
  BOOST_CHECK_THROW(fc::unit_factor("stress", f, "s", "N", "h"), std::invalid_argument);      // time for a length
}

BOOST_AUTO_TEST_CASE(draws_have_the_fits_mean_and_covariance_on_the_logarithms) {
  const auto f = burgers_fit();
  const std::size_t n = 20000;
  const auto s = fc::draw_samples(f, n, 11, {});
  BOOST_TEST_REQUIRE(s.accepted.size() == n);
  BOOST_TEST(s.drawn == n);  // log-normal draws of these are all within the law's ranges
  std::vector<std::vector<double>> x(4, std::vector<double>(n));
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < 4; ++i) x[i][k] = std::log(s.accepted[k].at(f.names[i]));
  for (std::size_t i = 0; i < 4; ++i) {
    double m = 0;
    for (double v : x[i]) m += v / static_cast<double>(n);
    // The mean of ln p is ln p_fit within 4 standard errors s_i / sqrt(n).
    BOOST_TEST(std::abs(m - std::log(f.values[i])) < 4 * f.log_std[i] / std::sqrt(static_cast<double>(n)), f.names[i]);
    for (std::size_t j = 0; j <= i; ++j) {
      double mj = 0, c = 0;
      for (double v : x[j]) mj += v / static_cast<double>(n);
      for (std::size_t k = 0; k < n; ++k) c += (x[i][k] - m) * (x[j][k] - mj) / static_cast<double>(n - 1);
      const double expected = f.correlation[i * 4 + j] * f.log_std[i] * f.log_std[j];
      // Standard error of a sample covariance of normals: sqrt((s_i^2 s_j^2 + C_ij^2) / n).
      const double se = std::sqrt((f.log_std[i] * f.log_std[i] * f.log_std[j] * f.log_std[j] + expected * expected) /
                                  static_cast<double>(n));
      BOOST_TEST(std::abs(c - expected) < 4 * se, f.names[i] << "," << f.names[j] << ": " << c << " vs " << expected);
    }
  }
  // The same seed gives the same draws; another seed others.
  BOOST_TEST(fc::draw_samples(f, 3, 11, {}).accepted[2] == s.accepted[2]);
  BOOST_TEST(fc::draw_samples(f, 3, 12, {}).accepted[2] != s.accepted[2]);
}

BOOST_AUTO_TEST_CASE(unidentified_parameters_are_held_or_drawn_within_the_spread_as_asked) {
  auto f = burgers_fit();
  f.identifiable[3] = false;  // eta2, as a fit flags a parameter the data do not fix
  f.log_std[3] = 0.0;
  const auto held = fc::draw_samples(f, 200, 3, {});
  BOOST_TEST(held.held == std::vector<std::string>{"eta2"});
  for (const auto& v : held.accepted) BOOST_TEST(v.at("eta2") == f.values[3]);
  fc::Unidentified u;
  u.spread = 10.0;
  const auto spread = fc::draw_samples(f, 2000, 3, u);
  BOOST_TEST(spread.spread == std::vector<std::string>{"eta2"});
  double lo = 1e300, hi = 0;
  for (const auto& v : spread.accepted) {
    lo = std::min(lo, v.at("eta2"));
    hi = std::max(hi, v.at("eta2"));
  }
  BOOST_TEST(lo >= f.values[3] / 10);
  BOOST_TEST(hi <= f.values[3] * 10);
  BOOST_TEST(hi / lo > 50.0);  // log-uniform over a factor 100: 2000 draws reach near both ends
}

BOOST_AUTO_TEST_CASE(non_physical_draws_are_rejected_and_counted) {
  auto f = burgers_fit();
  // A standard error of 400 on ln E1: exp overflows to inf (z > 1.77) or underflows to 0
  // (z < -1.86) in about 7 % of the draws; the law's range (0, max] refuses both.
  f.log_std[0] = 400.0;
  const auto s = fc::draw_samples(f, 500, 5, {});
  BOOST_TEST_REQUIRE(s.accepted.size() == 500u);
  std::size_t rejected = 0;
  for (const auto& [why, count] : s.rejected) rejected += count;
  BOOST_TEST(rejected > 0u);
  BOOST_TEST(s.drawn == s.accepted.size() + rejected);
  BOOST_TEST(s.rejected.count("E1 out of range") == 1u);
  for (const auto& v : s.accepted) BOOST_TEST((std::isfinite(v.at("E1")) && v.at("E1") > 0));
}

BOOST_AUTO_TEST_CASE(a_parameter_fitted_to_zero_is_read_as_unidentified_and_held_at_zero) {
  const fs::path dir = fresh_dir("forecast-zero");
  const fs::path report = dir / "fit.json";
  // A Nishihara fit whose threshold Fs came out 0 (no logarithm to draw); Fs has no standard error.
  std::ofstream(report) << R"({"units": {"stress": "MPa", "length": "mm", "time": "h"}, "best": "nishihara",
    "fits": [{"law": "nishihara", "parameters": [
      {"name": "E1", "value": 26.8, "std_error": 0.03, "identifiable": true},
      {"name": "E2", "value": 194.0, "std_error": 1.3, "identifiable": true},
      {"name": "eta2", "value": 2180.0, "std_error": 36.0, "identifiable": true},
      {"name": "eta3", "value": 34800.0, "std_error": 130.0, "identifiable": true},
      {"name": "Fs", "value": 0, "std_error": null, "identifiable": true}],
     "correlation": [[1,0,0,0,null],[0,1,0,0,null],[0,0,1,0,null],[0,0,0,1,null],[null,null,null,null,null]]}]})";
  const auto f = fc::read_fit_report(report.string(), "");
  BOOST_TEST(f.law == "nishihara");
  BOOST_TEST(!f.identifiable[4]);
  BOOST_TEST(f.log_std[0] == 0.03 / 26.8, boost::test_tools::tolerance(1e-14));  // se(ln p) = se(p) / p
  fc::Unidentified u;
  u.spread = 5.0;
  const auto s = fc::draw_samples(f, 50, 2, u);
  BOOST_TEST(s.held == std::vector<std::string>{"Fs"});
  BOOST_TEST(s.spread.empty());
  for (const auto& v : s.accepted) BOOST_TEST(v.at("Fs") == 0.0);
}

BOOST_AUTO_TEST_CASE(on_the_two_block_creep_test_the_bands_equal_the_closed_form_with_the_same_samples) {
  const fs::path dir = fresh_dir("forecast-two-block");
  const std::string fit = (dir / "fit.json").string();
  const auto f = run_rheodda("fit " + source_path("examples/creep-data/table1-row1.csv") +
                             " --law burgers --stress 0.232 --units 'MPa, mm, h' --json " + fit);
  BOOST_TEST_REQUIRE(f.exit_code == 0, f.output);
  const std::string args = "forecast " + source_path("examples/shear-creep-test.yaml") + " --fit " + fit +
                           " --joint-set plane --samples 24 --seed 3 -j 2 -o " + (dir / "out").string();
  const auto r = run_rheodda(args);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  // The members' parameters (samples.csv) through the closed form of the joint's shear
  // displacement under tau = 0.232 MPa (seed eqs. 20-21; examples/shear-creep-test.yaml).
  const auto samples = read_csv(dir / "out" / "samples.csv");
  BOOST_TEST_REQUIRE(samples.size() == 24u);
  const auto closed = [&](double t) {
    std::vector<double> d;
    for (const auto& s : samples) {
      const double e1 = std::stod(s.at("E1 [N/mm^2/mm]")), e2 = std::stod(s.at("E2 [N/mm^2/mm]"));
      const double eta1 = std::stod(s.at("eta1 [N/mm^2*h/mm]")), eta2 = std::stod(s.at("eta2 [N/mm^2*h/mm]"));
      const double tau = 0.232;
      d.push_back(tau / e1 + tau / e2 * (1 - std::exp(-e2 * t / eta2)) + tau * t / eta1);
    }
    return d;
  };
  const auto bands = read_csv(dir / "out" / "bands.csv");
  std::size_t compared = 0;
  for (const auto& row : bands) {
    const double t = std::stod(row.at("time"));
    if (t < 1) continue;  // the load is applied in the first step
    BOOST_TEST_CONTEXT("t = " << t) {
      BOOST_TEST(row.at("members") == "24");
      for (double p : {5.0, 50.0, 95.0}) {
        auto d = closed(t);
        const double expected = fc::percentile(d, p);
        // The two-block test follows the closed form to 1.1e-5 (docs/reference/outputs.md; measured here
        // 1.14e-5 at most), inside the sampling error of a 24-member percentile (a fraction
        // of the 5-95 % band's width, 2.5e-4 to 1.8e-3 of the median here).
        BOOST_TEST(std::stod(row.at(fmt::format("plane.shear_displacement_magnitude.p{:g}", p))) == expected,
                   boost::test_tools::tolerance(3e-5));
      }
    }
    ++compared;
  }
  BOOST_TEST(compared >= 99u);
  const auto j = nlohmann::json::parse(read_text((dir / "out" / "forecast.json").string()));
  BOOST_TEST(j.at("accepted").get<int>() == 24);
  BOOST_TEST(j.at("members_completed").get<int>() == 24);
  BOOST_TEST(read_text((dir / "out" / "fan.png").string()).substr(0, 4) == "\x89PNG");

  // The probability of exceeding a threshold at 200 h, from the members kept (--resume runs
  // nothing again): the fraction of samples whose closed form exceeds it. The threshold
  // lies in the widest gap between the middle members' closed forms, far from each
  // member's value next to the 1.1e-5 by which the run may differ from it.
  auto d200 = closed(200);
  std::sort(d200.begin(), d200.end());
  std::size_t gap = 8;
  for (std::size_t k = 8; k < 16; ++k)
    if (d200[k + 1] - d200[k] > d200[gap + 1] - d200[gap]) gap = k;
  BOOST_TEST_REQUIRE((d200[gap + 1] - d200[gap]) / d200[gap] > 4e-5);
  const double threshold = 0.5 * (d200[gap] + d200[gap + 1]);
  const std::size_t above = 23 - gap;
  const double prob = static_cast<double>(above) / 24.0;
  const auto p = run_rheodda(args + fmt::format(" --resume --threshold {} --by 200", threshold));
  BOOST_TEST_REQUIRE(p.exit_code == 0, p.output);
  BOOST_TEST(p.output.find("completed (") == std::string::npos, "members run again: " << p.output);
  const std::string expected =
      fmt::format("= {:.3f} +- {:.3f} ({} of 24 members)", prob, std::sqrt(prob * (1 - prob) / 24.0), above);
  BOOST_TEST(p.output.find(expected) != std::string::npos, expected << " in " << p.output);
  // The same threshold and time with their units (the scene's are mm and h).
  const auto q = run_rheodda(args + fmt::format(" --resume --threshold '{:.17g} um' --by '200 h'", 1000.0 * threshold));
  BOOST_TEST_REQUIRE(q.exit_code == 0, q.output);
  BOOST_TEST(q.output.find(expected) != std::string::npos, expected << " in " << q.output);
  const auto wrong = run_rheodda(args + " --resume --threshold '5 s' --by 200");
  BOOST_TEST(wrong.exit_code == 2);
  BOOST_TEST(wrong.output.find("--threshold: '5 s' has the wrong dimension") != std::string::npos, wrong.output);
}

BOOST_AUTO_TEST_CASE(bad_forecast_input_is_refused_with_exit_2_and_the_reason) {
  const fs::path dir = fresh_dir("forecast-bad");
  const std::string fit = (dir / "fit.json").string();
  BOOST_TEST_REQUIRE(run_rheodda("fit " + source_path("examples/creep-data/table1-row1.csv") +
                                 " --law burgers --stress 0.232 --units 'MPa, mm, h' --json " + fit)
                         .exit_code == 0);
  const std::string scene = source_path("examples/shear-creep-test.yaml");
  auto r = run_rheodda("forecast " + scene + " --fit " + fit + " --joint-set bedding -o " + (dir / "a").string());
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find("has no such joint set; it has: plane") != std::string::npos, r.output);
  r = run_rheodda("forecast " + scene + " --fit " + fit + " --joint-set plane --law maxwell -o " + (dir / "b").string());
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find("no fit of law 'maxwell'; it has: burgers") != std::string::npos, r.output);
  r = run_rheodda("forecast " + scene + " --fit " + scene + " --joint-set plane -o " + (dir / "c").string());
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find("not a `rheodda fit --json` report") != std::string::npos, r.output);
  r = run_rheodda("forecast " + scene + " --fit " + fit + " --joint-set plane --by 300 --threshold 1 -o " +
                  (dir / "d").string());
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find("--by 300 is outside the run") != std::string::npos, r.output);
  BOOST_TEST(!fs::exists(dir / "a"));  // nothing written before the input is checked
}

BOOST_AUTO_TEST_CASE(the_report_says_the_band_leaves_out_the_laws_form_and_what_an_unidentified_fs_decides) {
  // A Nishihara fit whose Fs the data do not determine, from a report where Burgers has the larger weight.
  fc::FittedLaw f;
  f.law = "nishihara";
  f.names = {"E1", "E2", "eta2", "eta3", "Fs"};
  f.units = {"MPa/mm", "MPa/mm", "MPa*h/mm", "MPa*h/mm", "MPa"};
  f.values = {26.87, 192.43, 2141.23, 17354.0, 0.248};
  f.identifiable = {true, true, true, true, false};
  f.rank_by = "bic";
  f.weights = {{"burgers", 0.9}, {"nishihara", 0.09}, {"maxwell", 0.01}};
  fc::Samples drawn;
  drawn.held = {"Fs"};
  const std::string text = fc::band_coverage(f, drawn, fc::Unidentified{});
  BOOST_TEST(text.find("what the band covers: the uncertainty of the parameters of law nishihara that the data "
                       "determine (E1, E2, eta2, eta3), drawn from the fit's covariance\n") != std::string::npos,
             text);
  BOOST_TEST(text.find("every member runs nishihara (weight 0.09 on BIC), and the data prefer burgers (weight 0.9, "
                       "10 times more") != std::string::npos,
             text);
  BOOST_TEST(text.find("the choice of Fs, which the data do not determine: every member holds it at the fit's 0.248 "
                       "MPa; Fs is a threshold: its element flows only where the shear stress exceeds it") !=
                 std::string::npos,
             text);
  // The best law of its report, with a rival within Delta 2 (weight ratio below e): named as supported as well.
  f.law = "burgers";
  f.weights = {{"burgers", 0.6}, {"nishihara", 0.4}};
  f.names = {"E1"};
  f.units = {"MPa/mm"};
  f.values = {26.87};
  f.identifiable = {true};
  const std::string rival = fc::band_coverage(f, fc::Samples{}, fc::Unidentified{});
  BOOST_TEST(rival.find("the data support nishihara (weight 0.4) about as well as burgers (weight 0.6 on BIC") !=
                 std::string::npos,
             rival);
  // A report of one law: the question was not asked.
  f.weights = {{"burgers", 1.0}};
  BOOST_TEST(fc::band_coverage(f, fc::Samples{}, fc::Unidentified{}).find("the report fitted law burgers only") !=
             std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
