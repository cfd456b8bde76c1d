// Sweeps in a study file (docs/guide/studies.md, "Sweeps"): grids of listed and spaced
// values, random and Latin-hypercube draws with a seed; cases named and titled by
// their values; study.csv with a column per swept parameter; the sweep pictures and
// `rheodda plot` of a study's folder.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "rheodda/scene/plot.hpp"
#include "rheodda/study/study.hpp"
#include "study_support.hpp"

using namespace rheodda::study_test;
namespace st = rheodda::study;
namespace fs = std::filesystem;

namespace {

std::string head() {
  return "scene: " + source_path("examples/sliding-block.yaml") + "\n"  // 1
         "set: {analysis.duration: 0.05}\n"                              // 2
         "outputs: [centre.u]\n"                                         // 3
         "times: [0.05]\n";                                              // 4
}

void expect_sweep_error(const std::string& sweep, int line, const std::string& key_part, const std::string& message_part) {
  try {
    (void)st::parse_study(head() + sweep, "bad-sweep.yaml");
    BOOST_ERROR("no error for a sweep expected to fail with '" << message_part << "'");
  } catch (const st::SceneError& e) {
    BOOST_TEST_INFO("error: " << e.what());
    BOOST_TEST(e.file() == "bad-sweep.yaml");
    BOOST_TEST(e.line() == line);
    BOOST_TEST(e.key().find(key_part) != std::string::npos);
    BOOST_TEST(e.message().find(message_part) != std::string::npos);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(study_sweep)

BOOST_AUTO_TEST_CASE(a_grid_is_the_product_of_listed_and_log_spaced_values_each_case_named_and_titled_by_them) {
  const auto s = st::parse_study(head() +
                                     "sweep:\n"
                                     "  parameters:\n"
                                     "    - {name: phi, key: joint_sets.slope.friction_angle, unit: deg, values: [10, 20]}\n"
                                     "    - {name: dt, key: analysis.dt, unit: s, range: [1.0e-4, 1.0e-2], count: 3, scale: log}\n",
                                 "grid.yaml");
  BOOST_TEST_REQUIRE(s.cases.size() == 6u);
  BOOST_TEST_REQUIRE(s.parameters.size() == 2u);
  BOOST_TEST(s.parameters[1].log_scale);
  // The last parameter varies fastest; log spacing: 1e-4, 1e-3, 1e-2 (ends exact, middle to rounding).
  const std::vector<std::string> names{"phi-10_dt-0.0001", "phi-10_dt-0.001", "phi-10_dt-0.01",
                                       "phi-20_dt-0.0001", "phi-20_dt-0.001", "phi-20_dt-0.01"};
  for (std::size_t k = 0; k < 6; ++k) {
    BOOST_TEST(s.cases[k].name == names[k]);
    BOOST_TEST(s.cases[k].parameter_values[0] == (k < 3 ? 10.0 : 20.0));
    BOOST_TEST(s.cases[k].parameter_values[1] == std::pow(10.0, -4.0 + static_cast<double>(k % 3)),
               boost::test_tools::tolerance(1e-14));
  }
  const auto texts = st::prepare_cases(s);
  BOOST_TEST(texts[4].find("friction_angle: 20") != std::string::npos, texts[4]);
  BOOST_TEST(texts[4].find("dt: 0.001") != std::string::npos, texts[4]);
  // A short title: the base title and the values with their units.
  BOOST_TEST(texts[4].find("title: Block sliding on a 30 deg incline, friction 20 deg [phi = 20 deg, dt = 0.001 s]") !=
                 std::string::npos,
             texts[4]);
}

BOOST_AUTO_TEST_CASE(latin_hypercube_draws_put_one_sample_in_each_stratum_and_a_seed_repeats_them) {
  const std::string sweep =
      "sweep:\n"
      "  method: latin_hypercube\n"
      "  samples: 10\n"
      "  seed: 42\n"
      "  parameters:\n"
      "    - {name: phi, key: joint_sets.slope.friction_angle, unit: deg, range: [10, 30]}\n"
      "    - {name: E, key: materials.rock.young_modulus, unit: Pa, range: [1.0e8, 1.0e10], scale: log}\n";
  const auto s = st::parse_study(head() + sweep, "lhs.yaml");
  BOOST_TEST_REQUIRE(s.cases.size() == 10u);
  BOOST_TEST(s.cases[0].name == "sample01");
  BOOST_TEST(s.cases[9].name == "sample10");
  std::set<int> phi_strata, e_strata;
  for (const auto& c : s.cases) {
    const double phi = c.parameter_values[0], e = c.parameter_values[1];
    BOOST_TEST((phi >= 10 && phi < 30));
    BOOST_TEST((e >= 1e8 && e < 1e10));
    phi_strata.insert(static_cast<int>(std::floor((phi - 10) / 20 * 10)));
    e_strata.insert(static_cast<int>(std::floor((std::log10(e) - 8) / 2 * 10)));  // strata of the logarithm
  }
  BOOST_TEST(phi_strata.size() == 10u);
  BOOST_TEST(e_strata.size() == 10u);
  const auto again = st::parse_study(head() + sweep, "lhs.yaml");
  for (std::size_t k = 0; k < 10; ++k) BOOST_TEST(again.cases[k].parameter_values == s.cases[k].parameter_values);
  std::string other = sweep;
  other.replace(other.find("seed: 42"), 8, "seed: 43");
  BOOST_TEST(st::parse_study(head() + other, "lhs.yaml").cases[0].parameter_values != s.cases[0].parameter_values);
}

BOOST_AUTO_TEST_CASE(random_draws_are_uniform_in_the_range_and_listed_cases_come_first) {
  const auto s = st::parse_study(head() +
                                     "cases: [{name: by_hand, set: {analysis.dt: 0.002}}]\n"
                                     "sweep:\n"
                                     "  method: random\n"
                                     "  samples: 2000\n"
                                     "  parameters: [{key: joint_sets.slope.friction_angle, unit: deg, range: [0, 20]}]\n",
                                 "random.yaml");
  BOOST_TEST_REQUIRE(s.cases.size() == 2001u);
  BOOST_TEST(s.cases[0].name == "by_hand");
  BOOST_TEST(s.cases[0].parameter_values.empty());
  BOOST_TEST(s.parameters[0].name == "friction_angle");  // default: the key's last part
  double mean = 0;
  for (std::size_t k = 1; k < s.cases.size(); ++k) {
    const double v = s.cases[k].parameter_values[0];
    BOOST_TEST((v >= 0 && v < 20));
    mean += v / 2000.0;
  }
  // Uniform on [0, 20): mean 10, standard error 20/sqrt(12 * 2000) = 0.129; 4 standard errors.
  BOOST_TEST(std::abs(mean - 10.0) < 4 * 0.129, "mean " << mean);
}

BOOST_AUTO_TEST_CASE(bad_sweeps_are_refused_with_line_and_key) {
  expect_sweep_error("sweep: {method: sobol, parameters: []}\n", 5, "sweep.method", "unknown method 'sobol'");
  expect_sweep_error("sweep:\n  parameters:\n    - {key: analysis.dt, values: [0.001]}\n", 7, "sweep.parameters[0].unit",
                     "missing key 'unit'");
  expect_sweep_error("sweep:\n  parameters:\n    - {key: analysis.dt, unit: s, range: [0.01, 0.001], count: 3}\n", 7,
                     "sweep.parameters[0].range", "is not below");
  expect_sweep_error("sweep:\n  parameters:\n    - {key: analysis.dt, unit: s, range: [0.001, 0.01]}\n", 7,
                     "sweep.parameters[0].count", "missing key 'count'");
  expect_sweep_error("sweep:\n  method: random\n  samples: 3\n  parameters:\n    - {key: analysis.dt, unit: s, values: [1]}\n",
                     9, "sweep.parameters[0].values", "draws from a 'range");
  expect_sweep_error("sweep:\n  method: random\n  parameters:\n    - {key: analysis.dt, unit: s, range: [0, 1]}\n", 6,
                     "sweep.samples", "missing key 'samples'");
  expect_sweep_error("sweep:\n  parameters:\n    - {key: analysis.dt, unit: s, values: [0, 1], scale: log}\n", 7,
                     "sweep.parameters[0].values[0]", "log scale needs values > 0");
  expect_sweep_error("sweep:\n  parameters:\n    - {key: analysis.dt, unit: s, values: [1]}\n  seed: 3\n", 8, "sweep.seed",
                     "random and latin_hypercube");
  expect_sweep_error("sweep:\n  parameters:\n    - {key: analysis.dt, unit: s, values: [1], colour: red}\n", 7,
                     "sweep.parameters[0].colour", "unknown key 'colour'");
  expect_sweep_error("cases: [{name: dt-1}]\nsweep:\n  parameters:\n    - {key: analysis.dt, unit: s, values: [1]}\n", 7,
                     "sweep", "two cases are named 'dt-1'");
}

BOOST_AUTO_TEST_CASE(a_swept_study_writes_a_column_per_parameter_and_draws_outputs_against_them) {
  const fs::path dir = fresh_dir("sweep-run");
  const fs::path study = dir / "sweep.yaml";
  // The block slides on the 30 deg incline when phi < 30 deg: u(t) = g (sin 30 - cos 30 tan phi) t^2 / 2.
  std::ofstream(study) << "title: sliding block, phi and dt\n"
                       << head()
                       << "sweep:\n"
                          "  parameters:\n"
                          "    - {name: phi, key: joint_sets.slope.friction_angle, unit: deg, values: [5, 15, 25]}\n"
                          "    - {name: dt, key: analysis.dt, unit: s, values: [0.001, 0.0025]}\n";
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 6u);
  for (const auto& row : rows) {
    BOOST_TEST_CONTEXT("case " << row.at("case")) {
      const double phi = std::stod(row.at("phi [deg]"));
      const double dt = std::stod(row.at("dt [s]"));
      BOOST_TEST(row.at("case") == fmt::format("phi-{:g}_dt-{:g}", phi, dt));
      const std::string scene = read_text((dir / "out" / "cases" / row.at("case") / "scene.yaml").string());
      BOOST_TEST(scene.find(fmt::format("friction_angle: {:g}", phi)) != std::string::npos);
      const double pi = std::acos(-1.0);
      const double u_closed = 9.81 * (std::sin(pi / 6) - std::cos(pi / 6) * std::tan(phi * pi / 180)) * 0.05 * 0.05 / 2;
      // u is the travel down the slope (to -x) projected on x (cos 30); measured within
      // 4.7e-4 of the closed form (phi 25 deg, dt 1 ms; the others closer).
      BOOST_TEST(-std::stod(row.at("centre.u@0.05")) == u_closed * std::cos(pi / 6), boost::test_tools::tolerance(2e-3));
    }
  }
  for (const char* f : {"study.png", "study_sweep.png", "study_map.png", "study.json"})
    BOOST_TEST(fs::exists(dir / "out" / f), f);
  const std::string map = read_text((dir / "out" / "study_map.dat").string());
  BOOST_TEST(map.find("5 0.001 ") != std::string::npos, map);
  // `rheodda plot` of the study's folder redraws its pictures; of a case, the run's.
  fs::remove(dir / "out" / "study_sweep.png");
  const auto p = run_rheodda("plot " + (dir / "out").string());
  BOOST_TEST_REQUIRE(p.exit_code == 0, p.output);
  BOOST_TEST(p.output.find("study_sweep.png") != std::string::npos, p.output);
  BOOST_TEST(read_text((dir / "out" / "study_sweep.png").string()).substr(0, 4) == "\x89PNG");
  const auto bad = run_rheodda("plot " + (dir / "out").string() + " --times 0.01");
  BOOST_TEST(bad.exit_code == 2, bad.output);
  BOOST_TEST(bad.output.find("study's folder") != std::string::npos, bad.output);
}

BOOST_AUTO_TEST_CASE(a_latin_hypercube_study_draws_a_sensitivity_scatter_and_no_map) {
  const fs::path dir = fresh_dir("lhs-run");
  const fs::path study = dir / "lhs.yaml";
  std::ofstream(study) << head()
                       << "sweep:\n"
                          "  method: latin_hypercube\n"
                          "  samples: 4\n"
                          "  parameters:\n"
                          "    - {name: phi, key: joint_sets.slope.friction_angle, unit: deg, range: [5, 25]}\n"
                          "    - {name: E, key: materials.rock.young_modulus, unit: Pa, range: [1.0e9, 1.0e10], scale: log}\n";
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 4u);
  for (const auto& row : rows) BOOST_TEST((!row.at("phi [deg]").empty() && !row.at("E [Pa]").empty()));
  BOOST_TEST(fs::exists(dir / "out" / "study_sweep.png"));
  BOOST_TEST(!fs::exists(dir / "out" / "study_map.png"));  // a map needs a grid of two parameters
  // One panel per parameter: the output against phi, then against E (log axis).
  const std::string gp = read_text((dir / "out" / "study_sweep.gp").string());
  BOOST_TEST(gp.find("set multiplot layout 1,2") != std::string::npos, gp);
  BOOST_TEST(gp.find("set logscale x\nset xlabel 'E [Pa]'") != std::string::npos, gp);
}

BOOST_AUTO_TEST_CASE(a_log_grid_takes_round_values_and_many_cases_are_told_apart_on_axes_with_units) {
  // issue 52: study.csv held 79999999999.99991 for 8e10 (exp(log) of a log grid), the
  // cases' colours repeated after 8, and the y axis read "(units: length=m force=N ...)".
  const fs::path dir = fresh_dir("sweep-many");
  const fs::path study = dir / "many.yaml";
  std::ofstream(study) << head()
                       << "sweep:\n"
                          "  parameters:\n"
                          "    - {name: phi, key: joint_sets.slope.friction_angle, unit: deg, values: [5, 15, 25]}\n"
                          "    - {name: E, key: materials.rock.young_modulus, unit: Pa, range: [1.0e10, 1.6e11], "
                          "count: 5, scale: log}\n";
  const auto parsed = st::parse_study(read_text(study.string()), study.string());
  BOOST_TEST((parsed.parameters[1].values == std::vector<double>{1e10, 2e10, 4e10, 8e10, 1.6e11}));
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 15u);
  std::set<std::string> es;
  for (const auto& row : rows) es.insert(row.at("E [Pa]"));
  BOOST_TEST((es == std::set<std::string>{"10000000000", "20000000000", "40000000000", "80000000000", "160000000000"}));
  BOOST_TEST(read_text((dir / "out" / "cases" / "phi-5_E-8e10" / "scene.yaml").string()).find("young_modulus: 80000000000") !=
             std::string::npos);
  // study.png: each axis with its unit in brackets; 15 cases, 15 looks (colour and dash).
  const std::string gp = read_text((dir / "out" / "study.gp").string());
  BOOST_TEST(gp.find("set xlabel 'time [s]'\n") != std::string::npos, gp);
  BOOST_TEST(gp.find("set ylabel 'centre.u [m]'\n") != std::string::npos, gp);
  BOOST_TEST(gp.find("units:") == std::string::npos, gp);
  std::set<std::string> looks;
  std::size_t curves = 0;
  for (std::size_t at = gp.find(" lc rgb '"); at != std::string::npos; at = gp.find(" lc rgb '", at + 1), ++curves)
    looks.insert(gp.substr(at, gp.find(" title", at) - at));
  BOOST_TEST(curves == 15u);
  BOOST_TEST(looks.size() == 15u, gp);
  // The sweep's panels likewise: the output at the last time with its unit.
  const std::string sweep = read_text((dir / "out" / "study_sweep.gp").string());
  BOOST_TEST(sweep.find("set ylabel 'centre.u at t = 0.05 s [m]'") != std::string::npos, sweep);
  // Forty curves before a look repeats (gnuplot's own line types repeat after 8).
  std::set<std::pair<std::string, int>> forty;
  for (std::size_t i = 0; i < 40; ++i) forty.insert({rheodda::scene::curve_style(i).colour, rheodda::scene::curve_style(i).dash});
  BOOST_TEST(forty.size() == 40u);
}

BOOST_AUTO_TEST_CASE(history_columns_carry_their_units_on_axis_labels) {
  using rheodda::scene::history_column_unit;
  BOOST_TEST(history_column_unit("time", "m", "N", "d") == "d");
  BOOST_TEST(history_column_unit("block10_top.u", "m", "N", "d") == "m");
  BOOST_TEST(history_column_unit("block10_top.displacement", "m", "N", "d") == "m");
  BOOST_TEST(history_column_unit("base.shear_displacement_magnitude", "mm", "N", "h") == "mm");
  BOOST_TEST(history_column_unit("base.shear_force", "m", "kN", "d") == "kN/m thickness");
  BOOST_TEST(history_column_unit("work_gravity", "m", "N", "d") == "N*m/m thickness");
  BOOST_TEST(history_column_unit("base.contacts", "m", "N", "d") == "-");
  BOOST_TEST(history_column_unit("inertia_share", "m", "N", "d") == "-");
  BOOST_TEST(history_column_unit("something_else", "m", "N", "d") == "");
}

BOOST_AUTO_TEST_SUITE_END()
