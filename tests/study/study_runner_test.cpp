// `rheodda study`: parallel cases give exactly what each case gives run alone, and a
// failing case is reported without losing the others.
#include <boost/test/unit_test.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <thread>
#include <vector>

#include "rheodda/study/study.hpp"
#include "study_support.hpp"

using namespace rheodda::study_test;
namespace st = rheodda::study;
namespace fs = std::filesystem;


BOOST_AUTO_TEST_SUITE(study_runner)

BOOST_AUTO_TEST_CASE(a_study_of_4_cases_gives_the_results_of_each_case_run_alone) {
  const fs::path dir = fresh_dir("four");
  const std::string base_text = read_text(source_path("examples/sliding-block.yaml"));
  const fs::path study = dir / "four.yaml";
  std::ofstream(study) << "scene: " << source_path("examples/sliding-block.yaml") << "\n"
                       << "set: {analysis.duration: 0.1}\n"
                          "outputs: [centre.u, centre.v, slope.shear_displacement]\n"
                          "times: [0.01, 0.0315, 0.1]\n"
                          "cases:\n"
                          "  - {name: phi10, set: {joint_sets.slope.friction_angle: 10}}\n"
                          "  - {name: phi15, set: {joint_sets.slope.friction_angle: 15}}\n"
                          "  - {name: phi25, set: {joint_sets.slope.friction_angle: 25}}\n"
                          "  - {name: dt2ms, set: {analysis.dt: 0.002}}\n";
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  BOOST_TEST(r.output.find("4 cases, 4 completed, 0 failed") != std::string::npos, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 4u);

  // Each case again, alone, from a scene edited by hand (not by the study's overrides),
  // with the study's times as output times (docs/guide/studies.md, "What a case writes").
  const std::string shorter = with("  duration: 1 ", "  duration: 0.1 ",
                                   with("  output_interval: 0.02  # s\n",
                                        "  output_interval: 0.02  # s\n  output_times: [0.01, 0.0315, 0.1]\n", base_text));
  const std::vector<std::pair<std::string, std::string>> alone{
      {"phi10", with("friction_angle: 20", "friction_angle: 10", shorter)},
      {"phi15", with("friction_angle: 20", "friction_angle: 15", shorter)},
      {"phi25", with("friction_angle: 20", "friction_angle: 25", shorter)},
      {"dt2ms", with("  dt: 0.001 ", "  dt: 0.002 ", shorter)}};
  for (std::size_t i = 0; i < alone.size(); ++i) {
    const auto& [name, text] = alone[i];
    BOOST_TEST_CONTEXT("case " << name) {
      const fs::path scene = dir / (name + ".yaml");
      std::ofstream(scene) << text;
      const fs::path out = dir / ("alone-" + name);
      const auto a = run_rheodda("run " + scene.string() + " -o " + out.string());
      BOOST_TEST_REQUIRE(a.exit_code == 0, a.output);
      const auto& row = rows[i];
      BOOST_TEST(row.at("case") == name);
      BOOST_TEST(row.at("status") == "completed");
      BOOST_TEST(row.at("message").empty());
      // The same time series, byte for byte, and the same values in study.csv (exact: shortest round-trip text).
      const std::string h_alone = read_text((out / "history.csv").string());
      BOOST_TEST(read_text((dir / "out" / "cases" / name / "history.csv").string()) == h_alone);
      for (const std::string col : {"centre.u", "centre.v", "slope.shear_displacement"}) {
        const auto series = st::read_history_series((out / "history.csv").string(), col);
        for (const std::string t : {"0.01", "0.0315", "0.1"}) {
          const auto v = st::value_at(series, std::stod(t));
          BOOST_TEST_REQUIRE(v.has_value(), col << "@" << t);
          BOOST_TEST(std::stod(row.at(col + "@" + t)) == *v, col << "@" << t);
        }
      }
      // The step that lands on 0.0315 and the one that takes the steps back onto the
      // output time 0.04 are one step more than dt would take.
      BOOST_TEST(std::stoi(row.at("steps")) == (name == "dt2ms" ? 51 : 101));
      // A case writes what the study reads: no frames (analysis.frames: false).
      BOOST_TEST(!fs::exists(dir / "out" / "cases" / name / "blocks.pvd"));
      BOOST_TEST(!fs::exists(dir / "out" / "cases" / name / "contacts.csv"));
      BOOST_TEST(std::stod(row.at("wall_seconds")) > 0.0);
    }
  }
  // Friction: the block slides (towards -x) less far as the friction angle grows (10 < 15 < 25 deg).
  BOOST_TEST(std::stod(rows[0].at("centre.u@0.1")) < std::stod(rows[1].at("centre.u@0.1")));
  BOOST_TEST(std::stod(rows[1].at("centre.u@0.1")) < std::stod(rows[2].at("centre.u@0.1")));
  const std::string png = read_text((dir / "out" / "study.png").string());
  BOOST_TEST(png.substr(0, 4) == "\x89PNG");
}

BOOST_AUTO_TEST_CASE(a_failing_case_is_reported_and_does_not_lose_the_others) {
  const fs::path dir = fresh_dir("failing");
  const fs::path study = dir / "failing.yaml";
  // The middle case allows a step displacement of 5e-6 m (max_displacement_ratio = 1e-6), which its 0.01 s
  // steps exceed, and may not cut them: its run fails at the first step.
  std::ofstream(study) << "scene: " << source_path("examples/sliding-block.yaml") << "\n"
                       << "set: {analysis.duration: 0.05, analysis.output_interval: 0.01}\n"
                          "outputs: [centre.u]\n"
                          "times: [0.05]\n"
                          "cases:\n"
                          "  - {name: first}\n"
                          "  - {name: broken, set: {analysis.dt: 0.01, analysis.max_cuts: 0, analysis.max_displacement_ratio: 1.0e-6}}\n"
                          "  - {name: last, set: {joint_sets.slope.friction_angle: 10}}\n";
  const auto r = run_rheodda("study " + study.string() + " -o " + (dir / "out").string() + " -j 2");
  BOOST_TEST(r.exit_code == 1, r.output);
  BOOST_TEST(r.output.find("3 cases, 2 completed, 1 failed") != std::string::npos, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 3u);
  BOOST_TEST(rows[0].at("status") == "completed");
  BOOST_TEST(rows[2].at("status") == "completed");
  BOOST_TEST(!rows[0].at("centre.u@0.05").empty());
  BOOST_TEST(!rows[2].at("centre.u@0.05").empty());
  BOOST_TEST(std::stod(rows[2].at("centre.u@0.05")) < std::stod(rows[0].at("centre.u@0.05")));  // phi 10 < 20 deg
  BOOST_TEST(rows[1].at("case") == "broken");
  BOOST_TEST(rows[1].at("status") == "failed");
  BOOST_TEST(rows[1].at("centre.u@0.05").empty());
  BOOST_TEST(rows[1].at("message").find("exceeds max_displacement_ratio") != std::string::npos, "the failure says why: " << rows[1].at("message"));
  BOOST_TEST(fs::exists(dir / "out" / "cases" / "broken" / "log.txt"));
}

BOOST_AUTO_TEST_CASE(a_study_stopped_by_sigterm_stops_its_cases_writes_study_csv_and_resumes) {
  const fs::path dir = fresh_dir("stopped");
  const fs::path study = dir / "stopped.yaml";
  std::ofstream(study) << "scene: " << source_path("examples/sliding-block.yaml") << "\n"
                       << "set: {analysis.duration: 0.5}\n"
                          "outputs: [centre.u]\n"
                          "times: [0.5]\n"
                          "cases:\n"
                          "  - {name: a, set: {joint_sets.slope.friction_angle: 10}}\n"
                          "  - {name: b, set: {joint_sets.slope.friction_angle: 15}}\n"
                          "  - {name: c, set: {joint_sets.slope.friction_angle: 25}}\n";
  const fs::path whole = dir / "whole", cut = dir / "cut";
  BOOST_TEST_REQUIRE(run_rheodda("study " + study.string() + " -o " + whole.string() + " -j 1 --no-plot").exit_code == 0);

  const pid_t pid = spawn_rheodda({"study", study.string(), "-o", cut.string(), "-j", "1", "--no-plot"});
  // Wait (by watching the file) until the first case has written some steps, then stop the study.
  int status = 0;
  for (;;) {
    std::error_code ec;
    const fs::path h = cut / "cases" / "a" / "history.csv";
    if (fs::exists(h, ec) && fs::file_size(h, ec) > 3000) break;
    BOOST_TEST_REQUIRE(::waitpid(pid, &status, WNOHANG) == 0, "the study ended before it could be stopped");
    std::this_thread::yield();
  }
  ::kill(pid, SIGTERM);
  ::waitpid(pid, &status, 0);
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 128 + SIGTERM);
  // study.csv says where each case is; the running case stopped with a checkpoint.
  const auto rows = read_study_csv((cut / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 3u);
  BOOST_TEST((rows[0].at("status") == "interrupted" || rows[0].at("status") == "completed"), rows[0].at("status"));
  BOOST_TEST(rows[2].at("status") == "not started");
  if (rows[0].at("status") == "interrupted") BOOST_TEST(fs::exists(cut / "cases" / "a" / "checkpoint.json"));
  // No case process is left running: each case folder's lock is free.
  for (const char* c : {"a", "b"})
    if (fs::exists(cut / "cases" / c / ".rheodda.lock")) {
      const int fd = ::open((cut / "cases" / c / ".rheodda.lock").c_str(), O_RDWR);
      BOOST_TEST(::flock(fd, LOCK_EX | LOCK_NB) == 0, "case " << c << " still running");
      ::close(fd);
    }

  const auto resumed = run_rheodda("study " + study.string() + " -o " + cut.string() + " -j 1 --no-plot --resume");
  BOOST_TEST_REQUIRE(resumed.exit_code == 0, resumed.output);
  BOOST_TEST(resumed.output.find("3 cases, 3 completed, 0 failed") != std::string::npos, resumed.output);
  for (const char* c : {"a", "b", "c"})
    BOOST_TEST(read_text((cut / "cases" / c / "history.csv").string()) ==
                   read_text((whole / "cases" / c / "history.csv").string()),
               c);
  const auto again = read_study_csv((cut / "study.csv").string());
  const auto ref = read_study_csv((whole / "study.csv").string());
  for (std::size_t i = 0; i < 3; ++i) BOOST_TEST(again[i].at("centre.u@0.5") == ref[i].at("centre.u@0.5"));
}

BOOST_AUTO_TEST_SUITE_END()
