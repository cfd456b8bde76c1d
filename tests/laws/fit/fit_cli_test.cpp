// `rheodda fit` end to end through the built binary: the report, the JSON and
// YAML files, the plot, multi-stage data from a stress column, and exit code 2
// with file, line and column for bad input; --fix, --bounds, --initial, --expr and
// --max-iterations against the library.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "rheodda/fit/fit.hpp"
#include "rheodda/laws/registry.hpp"
#include "synthetic.hpp"

namespace {

namespace fs = std::filesystem;

struct Run {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("rheodda-fit-cli-test-" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path operator/(const std::string& name) const { return path / name; }
};

Run run_rheodda(const std::string& args, const TempDir& dir, const std::string& env = "") {
  const std::string cmd = env + " '" RHEODDA_BINARY "' " + args + " >'" + (dir / "out.txt").string() +
                          "' 2>'" + (dir / "err.txt").string() + "'";
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "out.txt");
  r.err = slurp(dir / "err.txt");
  return r;
}

const std::string kExample = std::string(RHEODDA_SOURCE_DIR) + "/examples/creep-data/table1-row1.csv";

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

}  // namespace

BOOST_AUTO_TEST_SUITE(fit_cli)

BOOST_AUTO_TEST_CASE(yaml_block_builds_the_law_and_recovers_table1_row1_within_two_sigma) {
  TempDir dir;
  const Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --units 'MPa, mm, h' --yaml '" +
                            (dir / "law.yaml").string() + "' --json '" + (dir / "fit.json").string() + "'",
                        dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("MPa*h/mm") != std::string::npos);  // units from --units
  BOOST_TEST(r.out.find("units: MPa, mm, h") != std::string::npos);
  const YAML::Node law = YAML::LoadFile((dir / "law.yaml").string())["law"];
  BOOST_TEST(law["name"].as<std::string>() == "burgers");
  rheodda::laws::ParameterValues values;
  // The law's parameters; the range it was tested over (the scene loader's keys): one stress, 200 h.
  for (const auto& kv : law) {
    const std::string key = kv.first.as<std::string>();
    if (key != "name" && key != "tested_stress" && key != "tested_duration") values[key] = kv.second.as<double>();
  }
  BOOST_TEST(!law["unidentified"].IsDefined());  // every parameter determined
  BOOST_TEST(law["tested_stress"][0].as<double>() == 0.232);
  BOOST_TEST(law["tested_stress"][1].as<double>() == 0.232);
  BOOST_TEST(law["tested_duration"].as<double>() == 200.0);
  BOOST_CHECK_NO_THROW(rheodda::laws::LawRegistry::builtin().create("burgers", values));
  const auto json = nlohmann::json::parse(slurp(dir / "fit.json"));
  const auto truth = rheodda::fit::test::burgers_values(rheodda::fit::test::kTable1[0]);
  for (const auto& p : json["fits"][0]["parameters"]) {
    const std::string name = p["name"];
    BOOST_TEST(values.at(name) == p["value"].get<double>(), boost::test_tools::tolerance(1e-6));
    BOOST_TEST(std::abs(p["value"].get<double>() - truth.at(name)) <= 2.0 * p["std_error"].get<double>(),
               name);
  }
}

BOOST_AUTO_TEST_CASE(yaml_in_a_scenes_units_is_the_fit_converted) {
  // --scene-units (or --scene, the units of a scene file): the law in m, N, d from MPa, mm, h.
  TempDir dir;
  const std::string args = "fit '" + kExample + "' --law burgers --stress 0.232 --units 'MPa, mm, h' --quiet --json '" +
                           (dir / "fit.json").string() + "' --yaml ";
  Run r = run_rheodda(args + "'" + (dir / "si.yaml").string() + "' --scene-units 'm, N, d'", dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const std::string goodman = std::string(RHEODDA_SOURCE_DIR) + "/examples/goodman-toppling.yaml";  // m, N, d
  r = run_rheodda(args + "'" + (dir / "scene.yaml").string() + "' --scene '" + goodman + "'", dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(slurp(dir / "si.yaml") == slurp(dir / "scene.yaml"));
  const std::string text = slurp(dir / "si.yaml");
  BOOST_TEST(text.find("# in the scene's units m, N, d (length, force, time), converted from the data's MPa, mm, h") !=
             std::string::npos, text);
  BOOST_TEST(text.find("N/m^2*d/m (fitted ") != std::string::npos, text);
  const YAML::Node law = YAML::LoadFile((dir / "si.yaml").string())["law"];
  const auto json = nlohmann::json::parse(slurp(dir / "fit.json"));
  for (const auto& p : json["fits"][0]["parameters"]) {
    const std::string name = p["name"];
    // MPa/mm = 1e9 N/m^2/m; MPa*h/mm = 1e9/24 N/m^2*d/m
    const double factor = name.rfind("eta", 0) == 0 ? 1e9 / 24.0 : 1e9;
    BOOST_TEST(law[name].as<double>() == p["value"].get<double>() * factor, boost::test_tools::tolerance(1e-6));
  }
  // Refused before the fit: no --units to convert from, no --yaml to write, a label that is no unit.
  r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --yaml '" + (dir / "x.yaml").string() +
                      "' --scene-units 'm, N, d'", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("give them with --units") != std::string::npos, r.err);
  r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --units 'MPa, mm, h' --scene-units 'm, N, d'", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("give --yaml FILE") != std::string::npos, r.err);
  r = run_rheodda(args + "'" + (dir / "x.yaml").string() + "' --scene-units 'm, N, dx'", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("'dx' is not a unit UDUNITS-2 knows") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(stress_and_parameter_settings_may_carry_their_units) {
  // --stress 232 kPa is --stress 0.232 in MPa; --fix E1=26870 kPa/mm is 26.87 MPa/mm.
  TempDir dir;
  const std::string base = "fit '" + kExample + "' --law burgers --units 'MPa, mm, h' --quiet --json ";
  Run r = run_rheodda(base + "'" + (dir / "a.json").string() + "' --stress 0.232 --fix E1=26.87", dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  r = run_rheodda(base + "'" + (dir / "b.json").string() + "' --stress '232 kPa' --fix 'E1=26870 kPa/mm'", dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const auto a = nlohmann::json::parse(slurp(dir / "a.json"))["fits"][0]["parameters"];
  const auto b = nlohmann::json::parse(slurp(dir / "b.json"))["fits"][0]["parameters"];
  for (std::size_t i = 0; i < a.size(); ++i)
    BOOST_TEST(b[i]["value"].get<double>() == a[i]["value"].get<double>(), boost::test_tools::tolerance(1e-9));
  r = run_rheodda("fit '" + kExample + "' --law burgers --stress '232 kPa'", dir);  // no --units to convert into
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("give the data's units with --units") != std::string::npos, r.err);
  r = run_rheodda(base + "'" + (dir / "c.json").string() + "' --stress 0.232 --initial 'eta1=3 MPa*h'", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("--initial eta1: '3 MPa*h': MPa*h is force*time/length^2, not force*time/length^3") !=
             std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(law_all_ranks_burgers_first_on_the_example) {
  TempDir dir;
  const Run r = run_rheodda("fit '" + kExample + "' --law all --stress 0.232 --json '" +
                            (dir / "fit.json").string() + "'",
                        dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const auto json = nlohmann::json::parse(slurp(dir / "fit.json"));
  BOOST_TEST(json["best"] == "burgers");
  BOOST_TEST(json["rank_by"] == "bic");
  // Every fittable law (the nonlinear ones are skipped, fit.hpp fit_all).
  const auto& all = rheodda::laws::LawRegistry::builtin().laws();
  BOOST_TEST(json["fits"].size() ==
             static_cast<std::size_t>(std::count_if(all.begin(), all.end(),
                                                    [](const auto& i) { return i.fittable; })));
  for (std::size_t i = 1; i < json["fits"].size(); ++i)
    BOOST_TEST(json["fits"][i - 1]["bic"].get<double>() <= json["fits"][i]["bic"].get<double>());
  BOOST_TEST(r.out.find("ranking by BIC") != std::string::npos);
  // Ranked by BIC, the verdict still gives the Akaike weights, each the JSON's.
  std::string akaike = "  Akaike weights (on AIC): ";
  for (std::size_t i = 0; i < json["fits"].size(); ++i)
    akaike += fmt::format("{}{} {:.3g}", i ? ", " : "", json["fits"][i]["law"].get<std::string>(),
                          json["fits"][i]["akaike_weight"].get<double>());
  BOOST_TEST(r.out.find(akaike + "\n") != std::string::npos, r.out);
}

BOOST_AUTO_TEST_CASE(law_all_ends_with_a_verdict_whose_weights_are_the_hand_computed_akaike_weights) {
  TempDir dir;
  const Run r = run_rheodda("fit '" + kExample + "' --law all --stress 0.232 --rank-by aic --json '" +
                                (dir / "fit.json").string() + "'",
                            dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const auto json = nlohmann::json::parse(slurp(dir / "fit.json"));
  // By hand: w_i = exp(-(AIC_i - AIC_min)/2) / sum_j exp(-(AIC_j - AIC_min)/2) (Burnham & Anderson 2002).
  double best = INFINITY, sum = 0.0;
  for (const auto& f : json["fits"]) best = std::min(best, f["aic"].get<double>());
  for (const auto& f : json["fits"]) sum += std::exp(-0.5 * (f["aic"].get<double>() - best));
  std::map<std::string, double> weight;
  for (const auto& f : json["fits"]) {
    const double w = std::exp(-0.5 * (f["aic"].get<double>() - best)) / sum;
    weight[f["law"]] = w;
    BOOST_TEST(f["akaike_weight"].get<double>() == w, boost::test_tools::tolerance(1e-12));
  }
  // Burgers generated the curve; Nishihara and the generalized Kelvin law contain it (Fs -> 0, E3 -> 0) and
  // lose 2 on AIC by their extra parameter: supported less, at e = 2.72 times less weight.
  BOOST_TEST(r.out.find("verdict: weights w = exp(-dAIC/2) / sum exp(-dAIC/2) on AIC, the Akaike weights") !=
                 std::string::npos,
             r.out);
  BOOST_TEST(r.out.find(fmt::format("  the data support: burgers (weight {:.3g})", weight["burgers"])) !=
                 std::string::npos,
             r.out);
  BOOST_TEST(r.out.find("they do not support: maxwell, kelvin") != std::string::npos, r.out);
  // What nishihara leaves undetermined is said in the verdict, as in the JSON.
  const auto nishihara = std::find_if(json["fits"].begin(), json["fits"].end(),
                                      [](const auto& f) { return f["law"] == "nishihara"; });
  BOOST_TEST_REQUIRE((nishihara != json["fits"].end()));
  const auto unidentified = (*nishihara)["unidentified"].get<std::vector<std::string>>();
  BOOST_TEST((std::find(unidentified.begin(), unidentified.end(), "Fs") != unidentified.end()),
             (*nishihara)["unidentified"].dump());
  BOOST_TEST(r.out.find(fmt::format("  nishihara: the data do not determine {}", fmt::join(unidentified, ", "))) !=
                 std::string::npos,
             r.out);
  BOOST_TEST(json["tested_duration"].get<double>() == 200.0);
}

BOOST_AUTO_TEST_CASE(stress_column_multi_stage_with_unloading_is_fitted_at_once) {
  TempDir dir;
  const rheodda::laws::StagedHistory h({{0.0, 0.232}, {100.0, 0.424}, {200.0, 0.0}});
  const auto truth = rheodda::fit::test::burgers_values(rheodda::fit::test::kTable1[0]);
  const auto data = rheodda::fit::test::synthetic_curve("burgers", truth, h,
                                                        rheodda::fit::test::sample_times(300, 1, h));
  std::string csv = "hours,tau,u\n";
  for (std::size_t j = 0; j < data.t.size(); ++j)
    csv += fmt::format("{},{},{:.17g}\n", data.t[j], h.at(data.t[j]), data.displacement[j]);
  write(dir / "steps.csv", csv);
  const Run r = run_rheodda("fit '" + (dir / "steps.csv").string() +
                            "' --law burgers --stress-column tau --time-column hours "
                            "--displacement-column u --json '" + (dir / "fit.json").string() + "'",
                        dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("3 stages") != std::string::npos);
  const auto json = nlohmann::json::parse(slurp(dir / "fit.json"));
  for (const auto& p : json["fits"][0]["parameters"])
    BOOST_TEST(p["value"].get<double>() == truth.at(p["name"].get<std::string>()),
               boost::test_tools::tolerance(1e-6));
  // The same stages given on the command line, each time and stress with its unit (the data
  // in MPa, mm, h): the same law.
  const Run staged = run_rheodda("fit '" + (dir / "steps.csv").string() +
                                     "' --law burgers --stress '0 h:232 kPa,6000 min:0.424 MPa,200 h:0 MPa' "
                                     "--units 'MPa, mm, h' --time-column hours --displacement-column u --json '" +
                                     (dir / "staged.json").string() + "'",
                                 dir);
  BOOST_TEST_REQUIRE(staged.code == 0, staged.err);
  BOOST_TEST(staged.out.find("3 stages") != std::string::npos, staged.out);
  for (const auto& p : nlohmann::json::parse(slurp(dir / "staged.json"))["fits"][0]["parameters"])
    BOOST_TEST(p["value"].get<double>() == truth.at(p["name"].get<std::string>()),
               boost::test_tools::tolerance(1e-6));
  const Run wrong = run_rheodda("fit '" + (dir / "steps.csv").string() +
                                    "' --law burgers --stress '0 h:232 kPa,100 mm:0.424 MPa' --units 'MPa, mm, h' "
                                    "--time-column hours --displacement-column u",
                                dir);
  BOOST_TEST(wrong.code == 2);
  BOOST_TEST(wrong.err.find("--stress (a stage's time): '100 mm'") != std::string::npos, wrong.err);
}

BOOST_AUTO_TEST_CASE(plot_writes_an_svg_and_fails_clearly_without_gnuplot) {
  TempDir dir;
  const std::string args = "fit '" + kExample + "' --law burgers --stress 0.232 --plot '" +
                           (dir / "fit.svg").string() + "'";
  const Run r = run_rheodda(args, dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(slurp(dir / "fit.svg").find("<svg") != std::string::npos);
  const Run none = run_rheodda(args, dir, "PATH=/nonexistent");
  BOOST_TEST(none.code == 1);
  BOOST_TEST(none.err.find("gnuplot") != std::string::npos, none.err);
}

BOOST_AUTO_TEST_CASE(the_plot_draws_names_as_written) {
  // issue 52: the title turned the underscore of a file name into a subscript (gnuplot's
  // enhanced text).
  TempDir dir;
  fs::copy_file(kExample, dir / "table1_row1.csv");
  const Run r = run_rheodda("fit '" + (dir / "table1_row1.csv").string() + "' --law burgers --stress 0.232 --plot '" +
                                (dir / "fit.svg").string() + "'",
                            dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const std::string svg = slurp(dir / "fit.svg");
  BOOST_TEST(svg.find("<text>table1_row1.csv: burgers fit</text>") != std::string::npos, svg.substr(0, 4000));
  BOOST_TEST(svg.find("dy=") == std::string::npos);  // no sub- or superscript anywhere
}

BOOST_AUTO_TEST_CASE(the_report_prints_the_correlation_matrix_of_the_json_and_python) {
  // issue 52: the CLI report omitted the correlations that --json and Python's FitResult give.
  TempDir dir;
  const Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --json '" +
                                (dir / "fit.json").string() + "'",
                            dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  const auto at = r.out.find("correlation of the estimates");
  BOOST_TEST_REQUIRE(at != std::string::npos, r.out);
  std::istringstream lines(r.out.substr(at));
  std::string line;
  std::getline(lines, line);  // the heading
  std::getline(lines, line);  // the names
  std::istringstream names(line);
  std::vector<std::string> header{std::istream_iterator<std::string>(names), {}};
  BOOST_TEST((header == std::vector<std::string>{"E1", "E2", "eta1", "eta2"}), line);
  const auto json = nlohmann::json::parse(slurp(dir / "fit.json"));
  const auto& corr = json["fits"][0]["correlation"];
  for (std::size_t i = 0; i < 4; ++i) {
    std::getline(lines, line);
    std::istringstream row(line);
    std::string name;
    row >> name;
    BOOST_TEST(name == header[i]);
    for (std::size_t j = 0; j <= i; ++j) {
      std::string cell;
      row >> cell;
      BOOST_TEST(std::abs(std::stod(cell) - corr[i][j].get<double>()) <= 5e-5, cell << " vs " << corr[i][j]);
    }
    std::string more;
    BOOST_TEST(!(row >> more), line);  // the lower triangle only
  }
  BOOST_TEST(corr[1][0].get<double>() != 0.0);  // the example's estimates are correlated
}

BOOST_AUTO_TEST_CASE(bad_input_exits_2_naming_file_line_and_column) {
  TempDir dir;
  const std::string bad = (dir / "bad.csv").string();
  write(bad, "t,displacement\n0,0.0086\n1,nan\n");
  Run r = run_rheodda("fit '" + bad + "' --law burgers --stress 0.232", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find(bad + ":3: column 'displacement'") != std::string::npos, r.err);

  write(bad, "t,displacement\n0,0.0086\n1,0.009\n2,0.0093\n");
  r = run_rheodda("fit '" + bad + "' --law burgers --stress 0.232", dir);  // 3 points, 4 parameters
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("too few points") != std::string::npos, r.err);

  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--law burgerz --stress 0.232", "burgers"},                  // unknown law, with a hint
      {"--law burgers", "--stress"},                                // no stress at all
      {"--law burgers --stress abc", "--stress"},                   // stress not a number
      {"--law burgers --stress 0:0.2,100:0.4", "stage 2"},          // a stage without points
      {"--law burgers --stress 0.232 --units MPa", "--units"},      // units not STRESS, LENGTH, TIME
      {"--law burgers --stress 0.232 --plot fit.jpg", "--plot"},    // unknown picture format
      {"--law burgers --stress 0.232 --time-column hours", "hours"}, // no such column
      {"--law burgers --stress 0.232 --rank-by aic", "--rank-by"}   // ranking needs --law all
  };
  for (const auto& [args, words] : cases) {
    r = run_rheodda("fit '" + bad + "' " + args, dir);
    BOOST_TEST(r.code == 2, args);
    BOOST_TEST(r.err.find(words) != std::string::npos, args << ": " << r.err);
  }
  r = run_rheodda("fit '" + (dir / "missing.csv").string() + "' --law burgers --stress 0.2", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("cannot open") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(no_stress_option_says_no_applied_stress_as_the_docs_do) {
  TempDir dir;
  const Run r = run_rheodda("fit '" + kExample + "' --law burgers", dir);
  BOOST_TEST(r.code == 2);
  BOOST_TEST(r.err.find("no applied stress: give one stress for the file (--stress VALUE or --stress "
                        "T:V,...) or a stress column (--stress-column NAME)") != std::string::npos,
             r.err);
}

BOOST_AUTO_TEST_CASE(report_and_json_give_no_error_bar_the_data_cannot_support) {
  // Single-stage Nishihara on the example: eta3 and Fs without standard error,
  // (0.232 - Fs)/eta3 with one; the minimum's certainty in the JSON.
  TempDir dir;
  const std::string json = (dir / "fit.json").string();
  const Run r = run_rheodda("fit '" + kExample + "' --law nishihara --stress 0.232 --units 'MPa, mm, h' --json '" +
                                json + "'",
                            dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("fixed by the data: (0.232 - Fs)/eta3 = ") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("mm/h") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("eta3 and Fs are not identifiable") != std::string::npos, r.out);
  const auto j = nlohmann::json::parse(slurp(json));
  const auto& fit = j["fits"][0];
  for (const auto& p : fit["parameters"]) {
    const bool dropped = p["name"] == "eta3" || p["name"] == "Fs";
    BOOST_TEST(p["identifiable"].get<bool>() == !dropped, p["name"]);
    BOOST_TEST(p["std_error"].is_null() == dropped, p["name"]);
    BOOST_TEST(p["reason"].get<std::string>().empty() == !dropped, p["name"]);
  }
  BOOST_TEST_REQUIRE(fit["combinations"].size() == 1u);
  BOOST_TEST(fit["combinations"][0]["expression"] == "(0.232 - Fs)/eta3");
  BOOST_TEST(fit["combinations"][0]["unit"] == "mm/h");
  BOOST_TEST(fit["combinations"][0]["std_error"].get<double>() > 0.0);
  BOOST_TEST(fit["minimum_certain"].get<bool>());
  BOOST_TEST(fit["structured_starts"].get<int>() >= 1);
}

BOOST_AUTO_TEST_CASE(flat_curve_reports_r2_undefined) {
  TempDir dir;
  const std::string flat = (dir / "flat.csv").string(), json = (dir / "flat.json").string();
  std::string text = "t,displacement\n";
  for (int i = 0; i <= 50; ++i) text += fmt::format("{},0.01\n", i);
  write(flat, text);
  const Run r = run_rheodda("fit '" + flat + "' --law maxwell --stress 0.3 --json '" + json + "'", dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("R^2 undefined (the data have no spread)") != std::string::npos, r.out);
  const auto j = nlohmann::json::parse(slurp(json));
  BOOST_TEST(j["fits"][0]["r2"].is_null());
  BOOST_TEST(j["fits"][0]["parameters"][1]["identifiable"].get<bool>() == false);  // eta1
}

BOOST_AUTO_TEST_CASE(fix_bounds_initial_and_sigma_column_reach_the_library_and_the_json) {
  // The example with a sigma column (its noise, 2e-5 mm): --fix, --bounds,
  // --initial and --sigma-column give what fit::fit_law gives with the same
  // settings (the library is tested in settings_test.cpp).
  TempDir dir;
  std::ifstream in(kExample);
  std::string line, text;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    text += line + (line.rfind("t,", 0) == 0 ? ",sigma\n" : ",2e-5\n");
  }
  const std::string csv = (dir / "sigma.csv").string(), json = (dir / "fit.json").string();
  write(csv, text);
  const Run r = run_rheodda("fit '" + csv + "' --law burgers --stress 0.232 --fix E1=26.87 --bounds eta2=100:1e4 "
                            "--initial E2=150 --sigma-column sigma --absolute-sigma --json '" + json + "'",
                            dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("fixed") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("bounds [100, 10000]") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("chi-square") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("from sigma as absolute errors") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("minima of the starts (chi-square)") != std::string::npos, r.out);
  const auto j = nlohmann::json::parse(slurp(json))["fits"][0];
  BOOST_TEST(j["varying"].get<int>() == 3);
  BOOST_TEST(j["weighted"].get<bool>());
  BOOST_TEST(!j["scale_covariance"].get<bool>());
  BOOST_TEST(j["parameters"][0]["vary"].get<bool>() == false);
  BOOST_TEST(j["parameters"][0]["value"].get<double>() == 26.87);
  // held: no spread, and no correlation with the others (rheodda forecast holds it)
  BOOST_TEST(j["parameters"][0]["std_error"].get<double>() == 0.0);
  BOOST_TEST(j["correlation"][0][0].get<double>() == 1.0);
  BOOST_TEST(j["correlation"][0][2].get<double>() == 0.0);
  BOOST_TEST(j["correlation"][2][0].get<double>() == 0.0);
  BOOST_TEST(j["parameters"][3]["min"].get<double>() == 100.0);
  BOOST_TEST(j["parameters"][3]["max"].get<double>() == 1e4);

  rheodda::fit::CsvOptions o;
  o.stress = rheodda::laws::StagedHistory({{0.0, 0.232}});
  o.sigma_column = "sigma";
  const auto data = rheodda::fit::read_creep_csv(csv, o);
  rheodda::fit::FitOptions opt;
  opt.parameters["E1"].value = 26.87;
  opt.parameters["E1"].vary = false;
  opt.parameters["eta2"].min = 100.0;
  opt.parameters["eta2"].max = 1e4;
  opt.parameters["E2"].value = 150.0;
  opt.scale_covariance = false;
  const auto lib = rheodda::fit::fit_law(rheodda::laws::LawRegistry::builtin().get("burgers"), data, opt);
  for (std::size_t k = 0; k < 4; ++k) {
    BOOST_TEST(j["parameters"][k]["value"].get<double>() == lib.parameters[k].value,
               boost::test_tools::tolerance(1e-15));
    if (k > 0)
      BOOST_TEST(j["parameters"][k]["std_error"].get<double>() == lib.parameters[k].std_error,
                 boost::test_tools::tolerance(1e-15));
  }
  BOOST_TEST(j["chi_square"].get<double>() == lib.chi_square, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(a_fixed_parameter_is_held_by_rheodda_forecast) {
  // The JSON gives a fixed parameter std_error 0 and correlation 0: `rheodda forecast --fit`
  // draws the others and holds it (docs/guide/fitting.md). E1 = 26.87 MPa/mm is 26.87e9 N/m^2/m
  // in the slope's units (examples/studies/forecast-slope.yaml).
  TempDir dir;
  const std::string json = (dir / "fit.json").string(), out = (dir / "forecast").string();
  Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --units 'MPa, mm, h' --fix E1=26.87 --json '" +
                          json + "'",
                      dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  r = run_rheodda("forecast '" + std::string(RHEODDA_SOURCE_DIR) + "/examples/studies/forecast-slope.yaml' --fit '" +
                      json + "' --joint-set plane --samples 3 --threshold 3e-6 --by 100 -o '" + out + "'",
                  dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  std::istringstream samples(slurp(fs::path(out) / "samples.csv"));
  std::string line;
  std::getline(samples, line);  // header: case,E1 [...],E2 [...],...
  int rows = 0;
  while (std::getline(samples, line)) {
    const auto first = line.find(','), second = line.find(',', first + 1);
    const double e1 = std::stod(line.substr(first + 1, second - first - 1));
    BOOST_TEST(e1 == 26.87e9, boost::test_tools::tolerance(1e-12));
    ++rows;
  }
  BOOST_TEST(rows == 3);
}

BOOST_AUTO_TEST_CASE(bad_settings_exit_2_naming_the_option) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--fix E1", "--fix 'E1': expected NAME=VALUE"},
      {"--fix E1=abc", "--fix E1: 'abc' is not a number"},
      {"--fix E1=20 --fix E1=30", "--fix E1 is given twice"},
      {"--fix E1=20 --bounds E1=1:100", "--fix E1 holds E1 at its value"},
      {"--bounds eta2=100", "--bounds eta2: '100' is not MIN:MAX"},
      {"--bounds eta2=1e4:100", "eta2: the bounds [10000, 100] are empty"},
      {"--initial E9=3", "law 'burgers' has no parameter 'E9'"},
      {"--absolute-sigma", "--absolute-sigma takes the --sigma-column values"},
      {"--sigma-column err", "column 'err': no such column"},
  };
  for (const auto& [args, words] : cases) {
    const Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 " + args, dir);
    BOOST_TEST(r.code == 2, args);
    BOOST_TEST(r.err.find(words) != std::string::npos, args << ": " << r.err);
  }
}

BOOST_AUTO_TEST_CASE(expr_gives_a_parameter_as_that_expression_of_the_others) {
  // --expr eta2=12*E2: eta2 is 12 E2 in the report, the JSON and the YAML, not counted in k,
  // its standard error propagated (12 se(E2) for this linear expression), and the fit is
  // the library's with the same setting.
  TempDir dir;
  const std::string json = (dir / "fit.json").string(), yaml = (dir / "law.yaml").string();
  const Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --expr 'eta2=12*E2' --json '" +
                                json + "' --yaml '" + yaml + "'",
                            dir);
  BOOST_TEST_REQUIRE(r.code == 0, r.err);
  BOOST_TEST(r.out.find("= 12*E2") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("k = 3") != std::string::npos, r.out);
  const auto j = nlohmann::json::parse(slurp(json))["fits"][0];
  const auto& e2 = j["parameters"][1];
  const auto& eta2 = j["parameters"][3];
  BOOST_TEST_REQUIRE(eta2["name"] == "eta2");
  BOOST_TEST(e2["expr"] == "");
  BOOST_TEST(eta2["expr"] == "12*E2");
  BOOST_TEST(eta2["vary"].get<bool>() == false);
  BOOST_TEST(eta2["value"].get<double>() == 12.0 * e2["value"].get<double>(), boost::test_tools::tolerance(1e-13));
  BOOST_TEST(eta2["std_error"].get<double>() == 12.0 * e2["std_error"].get<double>(),
             boost::test_tools::tolerance(1e-10));
  BOOST_TEST(j["varying"].get<int>() == 3);
  BOOST_TEST(j["converged"].get<bool>());
  BOOST_TEST(j["optimality"].get<double>() <= 1e-6);
  BOOST_TEST(slurp(yaml).find("# = 12*E2") != std::string::npos, slurp(yaml));

  rheodda::fit::CsvOptions o;
  o.stress = rheodda::laws::StagedHistory({{0.0, 0.232}});
  rheodda::fit::FitOptions opt;
  opt.parameters["eta2"].expr = "12*E2";
  const auto lib = rheodda::fit::fit_law(rheodda::laws::LawRegistry::builtin().get("burgers"),
                                         rheodda::fit::read_creep_csv(kExample, o), opt);
  for (std::size_t k = 0; k < 4; ++k)
    BOOST_TEST(j["parameters"][k]["value"].get<double>() == lib.parameters[k].value,
               boost::test_tools::tolerance(1e-15));
  BOOST_TEST(j["chi_square"].get<double>() == lib.chi_square, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(max_iterations_reaches_the_fit_and_a_fit_cut_short_is_not_called_converged) {
  // eta2 <= 1000 binds on the example. Two iterations per start stop far from the constrained
  // minimum: NOT converged, with the warning that names --max-iterations; the default limit
  // reaches it. Either way the result is the library's with the same max_iterations.
  TempDir dir;
  const std::string json = (dir / "fit.json").string();
  const auto& burgers = rheodda::laws::LawRegistry::builtin().get("burgers");
  rheodda::fit::CsvOptions o;
  o.stress = rheodda::laws::StagedHistory({{0.0, 0.232}});
  const auto data = rheodda::fit::read_creep_csv(kExample, o);
  for (const int limit : {2, 500}) {
    const Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 --bounds eta2=:1000 --restarts 0 "
                                  "--max-iterations " + std::to_string(limit) + " --json '" + json + "'",
                              dir);
    BOOST_TEST_REQUIRE(r.code == 0, r.err);
    const auto j = nlohmann::json::parse(slurp(json))["fits"][0];
    rheodda::fit::FitOptions opt;
    opt.restarts = 0;
    opt.max_iterations = limit;
    opt.parameters["eta2"].max = 1000.0;
    const auto lib = rheodda::fit::fit_law(burgers, data, opt);
    BOOST_TEST(j["iterations"].get<int>() == lib.iterations, limit);
    BOOST_TEST(j["chi_square"].get<double>() == lib.chi_square, boost::test_tools::tolerance(1e-15));
    BOOST_TEST(j["converged"].get<bool>() == lib.converged, limit);
    bool warned = false;
    for (const auto& w : j["warnings"])
      warned = warned || w.get<std::string>().find("--max-iterations") != std::string::npos;
    if (limit == 2) {
      BOOST_TEST(!j["converged"].get<bool>());
      BOOST_TEST(j["optimality"].get<double>() > 1e-6);
      BOOST_TEST(warned);
      BOOST_TEST(r.out.find("NOT converged") != std::string::npos, r.out);
      BOOST_TEST(r.out.find("the fit stopped before reaching the minimum") != std::string::npos, r.out);
    } else {
      BOOST_TEST(j["converged"].get<bool>());
      BOOST_TEST(j["optimality"].get<double>() <= 1e-6);
      BOOST_TEST(!warned);
      BOOST_TEST(j["parameters"][3]["at_bound"] == "max");
      BOOST_TEST(j["parameters"][3]["value"].get<double>() == 1000.0);
    }
  }
}

BOOST_AUTO_TEST_CASE(bad_expr_and_max_iterations_exit_2_saying_what_is_wrong) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--expr eta2", "--expr 'eta2': expected NAME=EXPRESSION"},
      {"--expr eta2=12*E9",
       "law 'burgers': eta2: expression '12*E9': unknown name 'E9' (the parameters: E1, E2, eta1, eta2) at "
       "character 4"},
      {"--expr 'eta2=12*(E2'", "law 'burgers': eta2: expression '12*(E2': ')' expected at character 7"},
      {"--expr 'eta2=12 E2'", "expression '12 E2': unexpected 'E' at character 4"},
      {"--expr eta2=1200", "the expression '1200' names no parameter: to hold eta2 at a value, fix it"},
      {"--expr eta2=2*E2 --expr E2=eta2/2", "the expressions refer to each other in a cycle: E2 -> eta2 -> E2"},
      {"--expr eta2=2*E2 --expr eta2=3*E2", "--expr eta2 is given twice"},
      {"--expr eta2=2*E2 --fix eta2=5", "--expr gives eta2 by an expression: --fix, --initial and --bounds on it"},
      {"--expr eta2=2*E2 --bounds eta2=1:10", "--expr gives eta2 by an expression"},
      {"--expr E9=2*E2", "law 'burgers' has no parameter 'E9'"},
      {"--max-iterations 0", "--max-iterations 0: expected 1 to 1000000"},
      {"--max-iterations 1000001", "--max-iterations 1000001: expected 1 to 1000000"},
  };
  for (const auto& [args, words] : cases) {
    const Run r = run_rheodda("fit '" + kExample + "' --law burgers --stress 0.232 " + args, dir);
    BOOST_TEST(r.code == 2, args);
    BOOST_TEST(r.err.rfind("rheodda: error: ", 0) == 0, args << ": " << r.err);
    BOOST_TEST(r.err.find(words) != std::string::npos, args << ": " << r.err);
    BOOST_TEST(r.out.find("parameter ") == std::string::npos, args << ": a report was printed: " << r.out);
  }
}

BOOST_AUTO_TEST_SUITE_END()
