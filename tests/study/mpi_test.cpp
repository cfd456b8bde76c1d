// `mpirun --oversubscribe -np 3 rheodda study ...` (docs/guide/studies.md, "On a cluster: MPI"):
// rank 0 dispatches, ranks 1 and 2 run the cases; a failing and a crashing case are
// isolated and reported, the others give what the single-machine path gives; a resumed
// study skips its completed cases; a forecast over ranks gives the local one's bands.
#include <boost/test/unit_test.hpp>

#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <string>

#include "study_support.hpp"

using namespace rheodda::study_test;
namespace fs = std::filesystem;

namespace {

/// `mpirun --oversubscribe -np N rheodda ARGS` (as root, allowed through the environment ctest sets).
CommandResult mpirun_rheodda(int ranks, const std::string& args) {
  return rheodda::test::run_command(std::string(RHEODDA_MPIEXEC) + " --oversubscribe -np " + std::to_string(ranks) + " " +
                     RHEODDA_BINARY + " " + args);
}

/// Five cases of the sliding block; `broken` fails at its first step (a step displacement
/// above max_displacement_ratio, no cuts allowed), `crash` is killed by SIGSEGV through the case program.
fs::path write_study(const fs::path& dir) {
  const fs::path study = dir / "five.yaml";
  std::ofstream(study) << "scene: " << source_path("examples/sliding-block.yaml") << "\n"
                       << "set: {analysis.duration: 0.05, analysis.output_interval: 0.01}\n"
                          "outputs: [centre.u, slope.shear_displacement]\n"
                          "times: [0.02, 0.05]\n"
                          "cases:\n"
                          "  - {name: phi5, set: {joint_sets.slope.friction_angle: 5}}\n"
                          "  - {name: broken, set: {analysis.dt: 0.01, analysis.max_cuts: 0, analysis.max_displacement_ratio: 1.0e-6}}\n"
                          "  - {name: crash}\n"
                          "  - {name: phi15, set: {joint_sets.slope.friction_angle: 15}}\n"
                          "  - {name: phi25, set: {joint_sets.slope.friction_angle: 25}}\n";
  // The case program: rheodda itself, except for the case `crash`, which dies by a signal.
  const fs::path wrapper = dir / "case-program.sh";
  std::ofstream(wrapper) << "#!/bin/sh\n"
                            "case \"$2\" in */cases/crash/*) kill -SEGV $$ ;; esac\n"
                            "exec " << RHEODDA_BINARY << " \"$@\"\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  return study;
}

/// study.csv without the wall_seconds column (the only one that differs between runs).
std::vector<std::map<std::string, std::string>> results_of(const fs::path& csv) {
  auto rows = read_study_csv(csv.string());
  for (auto& r : rows) r.erase("wall_seconds");
  return rows;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(study_mpi)

BOOST_AUTO_TEST_CASE(over_mpi_a_failing_and_a_crashing_case_are_isolated_and_the_others_match_the_local_study) {
  const fs::path dir = fresh_dir("mpi-failing");
  const fs::path study = write_study(dir);
  const std::string program = " --case-program " + (dir / "case-program.sh").string() + " --no-plot";
  const auto m = mpirun_rheodda(3, "study " + study.string() + " -o " + (dir / "mpi").string() + program);
  BOOST_TEST(m.exit_code == 1, m.output);  // a case failed: exit 1, after every case was run
  BOOST_TEST(m.output.find("over 2 MPI worker ranks") != std::string::npos, m.output);
  BOOST_TEST(m.output.find("5 cases, 3 completed, 2 failed") != std::string::npos, m.output);
  BOOST_TEST(m.output.find("failed crash: killed by signal 11") != std::string::npos, m.output);
  const auto rows = results_of(dir / "mpi" / "study.csv");
  BOOST_TEST_REQUIRE(rows.size() == 5u);
  BOOST_TEST(rows[1].at("status") == "failed");
  BOOST_TEST(rows[1].at("message").find("exceeds max_displacement_ratio") != std::string::npos, rows[1].at("message"));
  BOOST_TEST(rows[2].at("status") == "failed");
  BOOST_TEST(rows[2].at("message").find("killed by signal 11") != std::string::npos, rows[2].at("message"));
  for (std::size_t i : {0u, 3u, 4u}) BOOST_TEST(rows[i].at("status") == "completed", rows[i].at("case"));

  // The single-machine path gives the same table, value for value.
  const auto l = run_rheodda("study " + study.string() + " -o " + (dir / "local").string() + " -j 2" + program);
  BOOST_TEST(l.exit_code == 1, l.output);
  const auto local = results_of(dir / "local" / "study.csv");
  BOOST_TEST_REQUIRE(local.size() == 5u);
  for (std::size_t i = 0; i < 5; ++i)
    for (const auto& [column, value] : local[i]) BOOST_TEST(rows[i].at(column) == value, local[i].at("case") << " " << column);
}

BOOST_AUTO_TEST_CASE(over_mpi_a_resumed_study_skips_its_completed_cases_and_runs_the_rest) {
  const fs::path dir = fresh_dir("mpi-resume");
  const fs::path study = write_study(dir);
  const std::string args = "study " + study.string() + " -o " + (dir / "out").string() + " --no-plot --case-program " +
                           (dir / "case-program.sh").string();
  const auto first = mpirun_rheodda(3, args);
  BOOST_TEST_REQUIRE(first.exit_code == 1, first.output);
  const auto before = results_of(dir / "out" / "study.csv");
  // As after an interruption: one case never ran (its folder is gone); the others are kept.
  fs::remove_all(dir / "out" / "cases" / "phi15");
  const auto stamp = [&](const std::string& c) { return fs::last_write_time(dir / "out" / "cases" / c / "history.csv"); };
  const auto kept0 = stamp("phi5"), kept4 = stamp("phi25");
  const auto again = mpirun_rheodda(3, args + " --resume");
  BOOST_TEST(again.exit_code == 1, again.output);
  BOOST_TEST((stamp("phi5") == kept0));   // completed: not run again
  BOOST_TEST((stamp("phi25") == kept4));
  BOOST_TEST(fs::exists(dir / "out" / "cases" / "phi15" / "history.csv"));  // run now
  // The progress lines name the cases run: phi15, and the failed ones (a failed case is run again).
  BOOST_TEST(again.output.find("phi15: completed") != std::string::npos, again.output);
  BOOST_TEST(again.output.find("phi5: completed (") == std::string::npos, again.output);
  const auto after = results_of(dir / "out" / "study.csv");
  BOOST_TEST_REQUIRE(after.size() == before.size());
  for (std::size_t i = 0; i < after.size(); ++i)
    for (const auto& [column, value] : before[i])
      if (column != "message") BOOST_TEST(after[i].at(column) == value, before[i].at("case") << " " << column);
}

BOOST_AUTO_TEST_CASE(over_mpi_jobs_per_rank_are_refused_with_exit_2) {
  const fs::path dir = fresh_dir("mpi-jobs");
  const fs::path study = write_study(dir);
  const auto r = mpirun_rheodda(2, "study " + study.string() + " -o " + (dir / "out").string() + " -j 4");
  BOOST_TEST(r.exit_code == 2, r.output);
  BOOST_TEST(r.output.find("one case at a time") != std::string::npos, r.output);
  BOOST_TEST(!fs::exists(dir / "out" / "study.csv"));
}

BOOST_AUTO_TEST_CASE(over_mpi_a_forecast_gives_the_bands_of_the_same_forecast_run_locally) {
  const fs::path dir = fresh_dir("mpi-forecast");
  const std::string fit = (dir / "fit.json").string();
  BOOST_TEST_REQUIRE(run_rheodda("fit " + source_path("examples/creep-data/table1-row1.csv") +
                                 " --law burgers --stress 0.232 --units 'MPa, mm, h' --json " + fit)
                         .exit_code == 0);
  const std::string args = "forecast " + source_path("examples/shear-creep-test.yaml") + " --fit " + fit +
                           " --joint-set plane --samples 6 --seed 9 --no-plot --threshold 0.01117 -o ";
  const auto m = mpirun_rheodda(3, args + (dir / "mpi").string());
  BOOST_TEST_REQUIRE(m.exit_code == 0, m.output);
  BOOST_TEST(m.output.find("members over 2 MPI worker ranks") != std::string::npos, m.output);
  BOOST_TEST(m.output.find("6 members completed") != std::string::npos, m.output);
  const auto l = run_rheodda(args + (dir / "local").string() + " -j 2");
  BOOST_TEST_REQUIRE(l.exit_code == 0, l.output);
  // The same seed draws the same members, each run gives the same history: the same bands, byte for byte.
  BOOST_TEST(read_text((dir / "mpi" / "bands.csv").string()) == read_text((dir / "local" / "bands.csv").string()));
  BOOST_TEST(read_text((dir / "mpi" / "samples.csv").string()) == read_text((dir / "local" / "samples.csv").string()));
}

BOOST_AUTO_TEST_SUITE_END()
