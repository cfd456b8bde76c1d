// The rheodda command's own surface: --version, the exit codes listed by --help
// (and returned), a missing file named without a bogus location, `plot --times`
// outside the run's frames said, and engine_bench's argument parsing.
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include "rheodda/version.hpp"
#include "../scene/test_support.hpp"

using namespace rheodda::test;
namespace fs = std::filesystem;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The sliding block over `duration` s (frames every 0.02 s), run into dir/out.
fs::path short_run(const fs::path& dir, const std::string& duration) {
  const fs::path scene = dir / "short.yaml";
  std::ofstream(scene) << with("  duration: 1 ", "  duration: " + duration + " ",
                               read_text(source_path("examples/sliding-block.yaml")));
  const auto r = run_rheodda("run " + scene.string() + " -o " + (dir / "out").string());
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  return dir / "out";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(command_line)

BOOST_AUTO_TEST_CASE(version_prints_the_cmake_project_version_as_summary_json_records_it) {
  const auto v = run_rheodda("--version");
  BOOST_TEST(v.exit_code == 0);
  BOOST_TEST(v.output == std::string("rheodda ") + RHEODDA_VERSION + "\n");
  BOOST_TEST(std::string(RHEODDA_VERSION) == "0.1.0");  // project(rheodda VERSION 0.1.0)
  const fs::path out = short_run(fresh_dir("version"), "0.02");
  const auto summary = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(summary.at("program").get<std::string>() + "\n" == v.output);
}

BOOST_AUTO_TEST_CASE(help_lists_the_exit_codes_the_commands_return) {
  const auto h = run_rheodda("--help");
  BOOST_TEST(h.exit_code == 0);
  BOOST_TEST(has(h.output, "Exit codes:"), h.output);
  BOOST_TEST(has(h.output, "\n  0      success"), h.output);
  BOOST_TEST(has(h.output, "\n  1      the command failed while working"), h.output);
  BOOST_TEST(has(h.output, "\n  2      bad input"), h.output);
  BOOST_TEST(has(h.output, "\n  128+N  a run stopped by signal N"), h.output);
  BOOST_TEST(!has(h.output, "(`rheodda --help`)"), h.output);  // the whole list here, not the line
  // And the codes are the ones returned: 2 for bad arguments and unknown laws, 0 for success
  // (1 and 128+N: run_commands_test and run_test's interrupted runs, study_runner_test's failed cases).
  BOOST_TEST(run_rheodda("law curve nosuch --force 0:1 --t-end 1 --dt 1").exit_code == 2);
  BOOST_TEST(run_rheodda("run").exit_code == 2);
  BOOST_TEST(run_rheodda("--no-such-option").exit_code == 2);
  BOOST_TEST(run_rheodda("law list").exit_code == 0);
}

BOOST_AUTO_TEST_CASE(each_commands_help_refers_to_the_exit_codes_in_one_line) {
  // issue 52: every `--help` repeated the 17-line block of `rheodda --help`.
  for (const char* command : {"law", "law list", "law curve", "keys", "check", "generate", "run", "plot", "fit",
                              "study", "forecast"}) {
    const auto h = run_rheodda(std::string(command) + " --help");
    BOOST_TEST_CONTEXT(command) {
      BOOST_TEST(h.exit_code == 0, h.output);
      BOOST_TEST(has(h.output, "\nExit codes: 0 success, 1 failure, 2 bad input, 3 coarse step controls, 128+N signal N "
                               "(`rheodda --help`)\n"),
                 h.output);
      BOOST_TEST(!has(h.output, "0      success"), h.output);
      BOOST_TEST(!has(h.output, "128+N  a run stopped"), h.output);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_missing_scene_file_is_named_with_the_reason_without_a_location) {
  const fs::path dir = fresh_dir("missing");
  const std::string missing = (dir / "missing.yaml").string();
  for (const std::string& args : {"check " + missing, "run " + missing + " -o " + (dir / "out").string()}) {
    const auto r = run_rheodda(args);
    BOOST_TEST(r.exit_code == 2);
    BOOST_TEST(r.output == "rheodda: error: cannot open " + missing + ": No such file or directory\n", r.output);
  }
  BOOST_TEST(!fs::exists(dir / "out"));
}

BOOST_AUTO_TEST_CASE(plot_says_when_a_requested_time_has_no_frame) {
  const fs::path out = short_run(fresh_dir("plot-times"), "0.1");  // frames at 0, 0.02, ..., 0.1 s
  const auto p = run_rheodda("plot " + out.string() + " --times 0.1,1000,0.045");
  BOOST_TEST_REQUIRE(p.exit_code == 0, p.output);
  BOOST_TEST(has(p.output, "rheodda: warning: --times 1000: the run's frames end at t = 0.1 s; "
                           "drawing the last frame (t = 0.1 s)"), p.output);
  // 0.045 lies between the frames at 0.04 and 0.06: the one drawn is named.
  BOOST_TEST(has(p.output, "rheodda: warning: --times 0.045: no frame at that time; drawing the nearest, t = 0.04 s"),
             p.output);
  // A time on a frame draws it without a word.
  BOOST_TEST(!has(p.output, "--times 0.1:"), p.output);
  const auto q = run_rheodda("plot " + out.string() + " --times 0,0.1");
  BOOST_TEST(!has(q.output, "warning"), q.output);
}

#ifdef RHEODDA_ENGINE_BENCH
BOOST_AUTO_TEST_CASE(engine_bench_parses_its_arguments_and_refuses_bad_block_counts) {
  const auto run = [](const std::string& args) {
    CommandResult r;
    FILE* p = ::popen((std::string(RHEODDA_ENGINE_BENCH) + " " + args + " 2>&1").c_str(), "r");
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
    const int status = ::pclose(p);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;  // -1: killed by a signal (the old SIGFPE)
    return r;
  };
  const auto h = run("--help");
  BOOST_TEST(h.exit_code == 0, h.output);
  BOOST_TEST(has(h.output, "BLOCKS"), h.output);
  BOOST_TEST(has(h.output, "--solver"), h.output);
  BOOST_TEST(has(h.output, "--steps"), h.output);
  for (const char* bad : {"0", "-5", "abc", "--solver lu 100", "--steps 0 100"}) {
    const auto r = run(bad);
    BOOST_TEST(r.exit_code == 2, bad << ": " << r.output);
  }
  // A small wall, one solver, two timed steps: one row of figures.
  const auto ok = run("20 --solver cholmod --steps 2");
  BOOST_TEST_REQUIRE(ok.exit_code == 0, ok.output);
  BOOST_TEST(has(ok.output, "solver cholmod"), ok.output);
  BOOST_TEST(!has(ok.output, "solver pcg"), ok.output);
  BOOST_TEST(has(ok.output, "\n      20 "), ok.output);
}
#endif

BOOST_AUTO_TEST_SUITE_END()
