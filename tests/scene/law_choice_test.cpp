// What a fitted law carries into a scene (docs/guide/fitting.md, "What a fitted law
// carries into a scene"): the loader reads a joint set's `unidentified`, `tested_stress`
// and `tested_duration`, and refuses them wrong or elsewhere with file, line and key;
// `check` and `run` warn with the factor; `rheodda fit --yaml` writes them, end to end on a
// Nishihara law whose threshold Fs the data do not determine.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "run_support.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

const std::string kBurgersLine = "law: {name: burgers, E1: 26.87, E2: 192.43, eta1: 34807.72, eta2: 2141.23}";

/// examples/shear-creep-test.yaml (one joint at 0.232 MPa, 200 h) with its law line replaced by `law`.
std::string shear_creep(const std::string& law) {
  return with(kBurgersLine, law, read_text(source_path("examples/shear-creep-test.yaml")));
}

/// A Nishihara law fitted elsewhere: Fs left undetermined, tested at 0.5 to 0.7 MPa for `duration` h.
std::string nishihara(double duration) {
  return fmt::format("law: {{name: nishihara, E1: 26.87, E2: 192.43, eta2: 2141.23, eta3: 17354, "
                     "Fs: 0.248, unidentified: [Fs], tested_stress: [0.5, 0.7], tested_duration: {:g}}}",
                     duration);
}

bool has(const std::vector<std::string>& lines, const std::string& a, const std::string& b = "") {
  for (const auto& l : lines)
    if (l.find(a) != std::string::npos && l.find(b) != std::string::npos) return true;
  return false;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(law_choice)

BOOST_AUTO_TEST_CASE(the_loader_reads_what_a_fit_says_of_a_joint_sets_law_and_summary_echoes_it) {
  const auto s = scene::parse_scene(shear_creep(nishihara(12.5)), "fitted.yaml");
  const auto& law = *s.joint_sets.at(0).law;
  BOOST_TEST(law.unidentified == std::vector<std::string>{"Fs"}, boost::test_tools::per_element());
  BOOST_TEST_REQUIRE(law.tested_stress.has_value());
  BOOST_TEST((*law.tested_stress == std::vector<double>{0.5, 0.7}));
  BOOST_TEST(law.tested_duration.value_or(0) == 12.5);
  const auto inputs = nlohmann::json::parse(scene::scene_json_text(s));
  const auto& echoed = inputs["joint_sets"]["plane"]["law"];
  BOOST_TEST(echoed["unidentified"] == nlohmann::json({"Fs"}), echoed.dump());
  BOOST_TEST(echoed["tested_stress"] == nlohmann::json({0.5, 0.7}), echoed.dump());
  BOOST_TEST(echoed["tested_duration"] == 12.5, echoed.dump());
  // A law without them echoes as before: no such keys.
  const auto plain = nlohmann::json::parse(scene::scene_json_text(scene::parse_scene(shear_creep(kBurgersLine), "p.yaml")));
  BOOST_TEST(!plain["joint_sets"]["plane"]["law"].contains("tested_stress"));
  BOOST_TEST(!plain["joint_sets"]["plane"]["law"].contains("unidentified"));
}

BOOST_AUTO_TEST_CASE(a_wrong_mark_is_refused_with_file_line_and_key) {
  // Line 10 of kBaseScene holds the law of joint set `fault` (burgers).
  const std::string at = "{name: burgers,";
  expect_error_at(with(at, "{name: burgers, unidentified: [Fz],"), 10, "Fz", "joint_sets.fault.law.unidentified[0]",
                  "law 'burgers' has no parameter 'Fz'");
  expect_error_at(with(at, "{name: burgers, unidentified: [Fs],"), 10, "Fs", "joint_sets.fault.law.unidentified[0]",
                  "; its parameters: E1, E2, eta1, eta2");
  expect_error_at(with(at, "{name: burgers, unidentified: [eta2, eta2],"), 10, "eta2]",
                  "joint_sets.fault.law.unidentified[1]", "'eta2' is listed twice");
  expect_error_at(with(at, "{name: burgers, unidentified: eta2,"), 10, "eta2,", "joint_sets.fault.law.unidentified",
                  "expected a list of the law's parameters");
  expect_error_at(with(at, "{name: burgers, tested_stress: [0.7, 0.5],"), 10, "[0.7", "joint_sets.fault.law.tested_stress",
                  "is not [lowest, highest] with 0 < lowest <= highest");
  expect_error_at(with(at, "{name: burgers, tested_stress: [0, 0.5],"), 10, "[0,", "joint_sets.fault.law.tested_stress",
                  "0 < lowest");
  expect_error_at(with(at, "{name: burgers, tested_duration: 0,"), 10, "0, E1", "joint_sets.fault.law.tested_duration",
                  "out of range");
  // A bolt's law and a stage's take none of them: refused, not ignored.
  const std::string bolt = kBaseScene + "bolts:\n  - {name: b, from: {point: [1.5, 1.5]}, to: {fixed: [1.5, 4]}, "
                                        "law: {name: burgers, E1: 1, E2: 2, eta1: 3, eta2: 4, tested_duration: 5}}\n";
  expect_error_at(bolt, 17, "5}}", "bolts[0].law.tested_duration", "marks a fitted law of a joint set; a bolt's law");
  const std::string stage = kBaseScene + "stages:\n  - {name: a, at: 0.5, joint_sets: {fault: {law: {name: burgers, E1: 1, "
                                         "E2: 2, eta1: 3, eta2: 4, unidentified: [E2]}}}}\n";
  expect_error_at(stage, 17, "[E2]", "law.unidentified", "a stage changes the law's parameters only");
}

BOOST_AUTO_TEST_CASE(check_warns_of_an_unidentified_threshold_and_of_a_run_longer_than_the_tests) {
  // The run lasts 200 h; the law was tested for 12.5 h: 16 times as long.
  const auto s = scene::parse_scene(shear_creep(nishihara(12.5)), "fitted.yaml");
  const std::vector<std::string> w = scene::scene_warnings(s);
  BOOST_TEST(has(w, "joint set 'plane': the data law nishihara was fitted to do not determine Fs (unidentified)",
                 "Fs is a threshold: its element flows only where the shear stress exceeds it"),
             fmt::format("{}", fmt::join(w, "\n")));
  BOOST_TEST(has(w, "joint set 'plane': the run lasts 200 h, 16 times as long as the longest test law nishihara was "
                    "fitted to (tested_duration 12.5 h)"),
             fmt::format("{}", fmt::join(w, "\n")));
  const std::string described = scene::describe_scene(s);
  BOOST_TEST(described.find("16 times as long as the longest test") != std::string::npos, described);
  BOOST_TEST(described.find("fitted law: unidentified Fs; tested_stress [0.5, 0.7] N/mm^2; tested_duration 12.5 h") !=
                 std::string::npos,
             described);
  // Tested for as long as the run, no duration warning; without marks, none at all.
  BOOST_TEST(!has(scene::scene_warnings(scene::parse_scene(shear_creep(nishihara(200)), "f.yaml")), "as long as"));
  BOOST_TEST(scene::scene_warnings(scene::parse_scene(shear_creep(kBurgersLine), "p.yaml")).empty());
}

BOOST_AUTO_TEST_CASE(run_warns_where_the_contact_stresses_leave_the_tested_range_and_lie_below_an_unidentified_fs) {
  auto s = scene::parse_scene(shear_creep(nishihara(1)), source_path("examples/shear-creep-test.yaml"));
  s.analysis.duration = 4;
  s.analysis.output_interval = 2;
  const auto out = fresh_dir("law-choice-run");
  const scene::RunResult r = run(s, out);
  const std::string all = fmt::format("{}", fmt::join(r.warnings, "\n"));
  // The joint carries 0.232 MPa: 2.2 times below the lowest tested 0.5 MPa, and below Fs = 0.248.
  BOOST_TEST(has(r.warnings, "the run lasts 4 h, 4 times as long as the longest test"), all);
  BOOST_TEST(has(r.warnings, "leave the range its law nishihara was tested at (tested_stress [0.5, 0.7] N/mm^2)",
                 "the median is 2.2 times below the lowest"),
             all);
  BOOST_TEST(has(r.warnings, "locked contacts (100 %) carry a shear stress below Fs = 0.248 N/mm^2",
                 "the median is 1.1 times below Fs"),
             all);
  const auto summary = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(summary["warnings"].size() == r.warnings.size());
  BOOST_TEST(summary["warnings"].dump().find("tested_stress [0.5, 0.7] N/mm^2") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(fit_yaml_marks_an_unidentified_fs_the_loader_reads_it_and_check_warns) {
  // One stress level: Nishihara's Fs and eta3 enter only as (0.232 - Fs)/eta3 (docs/guide/fitting.md).
  const auto dir = fresh_dir("law-choice-fit");
  const auto yaml = dir / "law.yaml";
  const CommandResult fit = run_rheodda("fit " + source_path("examples/creep-data/table1-row1.csv") +
                                        " --law nishihara --stress 0.232 --units 'MPa, mm, h' --yaml " + yaml.string());
  BOOST_TEST_REQUIRE(fit.exit_code == 0, fit.output);
  const std::string block = read_text(yaml.string());
  BOOST_TEST(block.find("  unidentified: [eta3, Fs]\n") != std::string::npos, block);
  BOOST_TEST(block.find("  tested_stress: [0.232, 0.232]\n") != std::string::npos, block);
  BOOST_TEST(block.find("  tested_duration: 200\n") != std::string::npos, block);
  // The block, indented under the example's joint set, loads; check names Fs and what it decides.
  std::string law;
  std::istringstream in(block);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') law += "    " + line + "\n";
  std::string scene_text = read_text(source_path("examples/shear-creep-test.yaml"));
  scene_text = with("    " + kBurgersLine + "\n", law, scene_text);
  const auto scene_file = dir / "scene.yaml";
  std::ofstream(scene_file) << scene_text;
  const auto s = scene::load_scene(scene_file.string());
  BOOST_TEST(s.joint_sets.at(0).law->unidentified == (std::vector<std::string>{"eta3", "Fs"}),
             boost::test_tools::per_element());
  const CommandResult check = run_rheodda("check " + scene_file.string());
  BOOST_TEST(check.exit_code == 0, check.output);
  BOOST_TEST(check.output.find("the data law nishihara was fitted to do not determine eta3, Fs (unidentified)") !=
                 std::string::npos,
             check.output);
  BOOST_TEST(check.output.find("Fs is a threshold") != std::string::npos, check.output);
}

BOOST_AUTO_TEST_SUITE_END()
