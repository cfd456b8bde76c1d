// The scene's keys of the static steps by cycles (analysis.static_force_ratio,
// static_max_cycles, static_local_damping; docs/reference/explicit-step.md, "Static steps by
// cycles"): they reach the engine, are refused where they cannot act (at the key's line and
// column), `rheodda check` says how the static steps are taken, and a run takes them.
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"
#include "rheodda/scene/build.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

/// The base scene (static) with its static steps by cycles; `extra`: more analysis lines.
std::string cycled(const std::string& extra = "") {
  return with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit\n  static_force_ratio: 1.0e-6\n" + extra);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(static_cycles)

BOOST_AUTO_TEST_CASE(the_keys_reach_the_engine) {
  const auto s = scene::build_scene(scene::parse_scene(cycled("  static_max_cycles: 5000\n  static_local_damping: 0.7"),
                                                        "cycled.yaml"))
                     .model.settings;
  BOOST_TEST(s.static_force_ratio == 1e-6);
  BOOST_TEST(s.static_max_cycles == 5000);
  BOOST_TEST(s.static_local_damping == 0.7);
  BOOST_TEST((s.integrator == core::Integrator::explicit_step));
  const auto plain = scene::build_scene(scene::parse_scene(kBaseScene, "base.yaml")).model.settings;
  BOOST_TEST(plain.static_force_ratio == 0.0);  // static steps implicit by default
  BOOST_TEST(plain.static_max_cycles == 100000);
  BOOST_TEST(plain.static_local_damping == 0.8);
}

BOOST_AUTO_TEST_CASE(keys_that_cannot_act_are_refused_where_they_are_written) {
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  static_force_ratio: 1.0e-6"), 5, "1.0e-6",
                  "analysis.static_force_ratio", "give integrator: explicit");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n  static_force_ratio: 1.0e-6"),
                  7, "1.0e-6", "analysis.static_force_ratio", "a dynamic analysis has no static steps");
  const std::string dynamic = "  dt: 0.01\n  type: dynamic\n  integrator: explicit\n";
  expect_error_at(with("  dt: 0.01", dynamic + "  static_max_cycles: 10"), 7, "10", "analysis.static_max_cycles",
                  "give static_force_ratio too");
  expect_error_at(with("  dt: 0.01", dynamic + "  static_local_damping: 0.5"), 7, "0.5",
                  "analysis.static_local_damping", "give static_force_ratio too");
  expect_error_at(cycled("  static_local_damping: 1"), 7, "1", "analysis.static_local_damping", "out of range");
  expect_error_at(cycled("  static_max_cycles: 0"), 7, "0", "analysis.static_max_cycles", "out of range");
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit\n  static_force_ratio: 1"), 6, "1",
                  "analysis.static_force_ratio", "out of range");
  // Without static_force_ratio a static analysis without a dynamic stage has nothing to cycle.
  expect_error_at(with("  dt: 0.01", "  dt: 0.01\n  integrator: explicit"), 5, "explicit", "analysis.integrator",
                  "static_force_ratio");
}

BOOST_AUTO_TEST_CASE(check_says_how_the_static_steps_are_taken_and_a_run_takes_them) {
  const auto dir = std::filesystem::temp_directory_path() / "rheodda-static-cycles-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "cycled.yaml";
  std::ofstream(file) << cycled();
  const CommandResult check = run_rheodda("check " + file.string());
  BOOST_TEST(check.exit_code == 0, check.output);
  BOOST_TEST(check.output.find("static steps by cycles from rest to an unbalanced-force ratio of 1e-06") !=
                 std::string::npos,
             check.output);
  const CommandResult run = run_rheodda("run " + file.string() + " -o " + (dir / "out").string() + " --quiet");
  BOOST_TEST(run.exit_code == 0, run.output);
  // history.csv's iterations hold each static step's cycles: more than one, the block
  // settling under gravity on its first step.
  std::ifstream history(dir / "out" / "history.csv");
  std::string line;
  int rows = 0, cycled_rows = 0;
  while (std::getline(history, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("time,", 0) == 0) continue;
    ++rows;
    std::size_t at = 0;
    for (int comma = 0; comma < 4; ++comma) at = line.find(',', at) + 1;  // the fifth column: iterations
    cycled_rows += std::stoi(line.substr(at)) > 1;
  }
  BOOST_TEST(rows > 0);
  BOOST_TEST(cycled_rows > 0);
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
