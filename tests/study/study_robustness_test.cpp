// `rheodda study` and `rheodda forecast` when things go wrong around them (issue 43):
// --resume recognises completed cases by their content whatever the spelling of the
// paths, a SIGKILL of the study leaves no case running, a SIGTERM while a large
// forecast is being prepared is honoured before the members are written, and the
// small things: drawn cases zero-padded, a crash message without a stray "; ",
// study_sweep.png's ticks telling values 1e-5 apart.
#include <boost/test/unit_test.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "rheodda/study/study.hpp"
#include "study_support.hpp"

using namespace rheodda::study_test;
namespace st = rheodda::study;
namespace fs = std::filesystem;

namespace {

/// A study of three cases of the sliding block, its base scene beside it (relative path).
void write_study(const fs::path& dir, double duration) {
  std::ofstream(dir / "sliding.yaml") << read_text(source_path("examples/sliding-block.yaml"));
  std::ofstream(dir / "study.yaml") << "scene: sliding.yaml\n"
                                    << "set: {analysis.duration: " << duration << "}\n"
                                    << "outputs: [centre.u]\n"
                                       "times: ["
                                    << duration
                                    << "]\n"
                                       "cases:\n"
                                       "  - {name: a, set: {joint_sets.slope.friction_angle: 10}}\n"
                                       "  - {name: b, set: {joint_sets.slope.friction_angle: 15}}\n"
                                       "  - {name: c, set: {joint_sets.slope.friction_angle: 25}}\n";
}

/// Modification time of each case's history.csv: unchanged when --resume kept the case.
std::vector<fs::file_time_type> history_times(const fs::path& out) {
  std::vector<fs::file_time_type> t;
  for (const char* c : {"a", "b", "c"}) t.push_back(fs::last_write_time(out / "cases" / c / "history.csv"));
  return t;
}

/// True once no process holds the run lock of the case folder (its case process ended).
bool lock_free(const fs::path& case_dir) {
  const fs::path lock = case_dir / ".rheodda.lock";
  if (!fs::exists(lock)) return true;
  const int fd = ::open(lock.c_str(), O_RDWR);
  const bool free = fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  if (fd >= 0) ::close(fd);
  return free;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(study_robustness)

BOOST_AUTO_TEST_CASE(resume_keeps_completed_cases_whatever_the_spelling_of_the_paths) {
  // issue 43: the case scene's header names the study and the scene as typed, so a
  // resume from another working directory, with absolute paths, or of a moved folder
  // ran every case again.
  const fs::path dir = fresh_dir("resume-spelling");
  write_study(dir, 0.05);
  const auto first = rheodda::test::run_command("cd " + dir.string() + " && " + RHEODDA_BINARY +
                                       " study study.yaml -o out -j 2 --no-plot");
  BOOST_TEST_REQUIRE(first.exit_code == 0, first.output);
  const auto before = history_times(dir / "out");
  const auto absolute = rheodda::test::run_command("cd / && " + std::string(RHEODDA_BINARY) + " study " +
                                          (dir / "study.yaml").string() + " -o " + (dir / "out").string() +
                                          " -j 2 --no-plot --resume");
  BOOST_TEST_REQUIRE(absolute.exit_code == 0, absolute.output);
  BOOST_TEST(absolute.output.find("3 cases, 3 completed, 0 failed") != std::string::npos, absolute.output);
  BOOST_TEST((history_times(dir / "out") == before));
  // The whole folder moved elsewhere, resumed from there.
  const fs::path moved = dir.string() + "-moved";
  fs::remove_all(moved);
  fs::rename(dir, moved);
  const auto again = rheodda::test::run_command("cd " + moved.string() + " && " + RHEODDA_BINARY +
                                       " study ./study.yaml -o ./out -j 2 --no-plot --resume");
  BOOST_TEST_REQUIRE(again.exit_code == 0, again.output);
  BOOST_TEST((history_times(moved / "out") == before));
  // A changed case is run again, the others kept.
  std::string text = read_text((moved / "study.yaml").string());
  text = with("friction_angle: 25", "friction_angle: 30", text);
  std::ofstream(moved / "study.yaml") << text;
  BOOST_TEST_REQUIRE(run_rheodda("study " + (moved / "study.yaml").string() + " -o " + (moved / "out").string() +
                                 " -j 2 --no-plot --resume")
                         .exit_code == 0);
  const auto after = history_times(moved / "out");
  BOOST_TEST((after[0] == before[0] && after[1] == before[1]));
  BOOST_TEST((after[2] != before[2]));
  fs::remove_all(moved);
}

BOOST_AUTO_TEST_CASE(a_killed_study_leaves_no_case_running_and_resumes_to_the_same_files) {
  // issue 43: after a SIGKILL of `rheodda study` its running cases ran on as orphans,
  // and a resume right after found their folders "in use by another rheodda run".
  const fs::path dir = fresh_dir("killed");
  write_study(dir, 0.5);
  BOOST_TEST_REQUIRE(run_rheodda("study " + (dir / "study.yaml").string() + " -o " + (dir / "whole").string() +
                                 " -j 2 --no-plot")
                         .exit_code == 0);
  const fs::path cut = dir / "cut";
  const pid_t pid = spawn_rheodda({"study", (dir / "study.yaml").string(), "-o", cut.string(), "-j", "2", "--no-plot"});
  // Each running case is frozen (SIGSTOP) as soon as it has written some steps, so that
  // neither runs to its end while the other starts: the kill finds both mid-run however
  // the machine schedules them. Its process id is in its folder's lock (output.hpp, FolderLock).
  int status = 0;
  std::vector<pid_t> frozen;
  for (const char* c : {"a", "b"}) {
    for (;;) {
      std::error_code ec;
      if (fs::exists(cut / "cases" / c / "history.csv", ec) &&
          fs::file_size(cut / "cases" / c / "history.csv", ec) > 3000) {
        std::ifstream lock(cut / "cases" / c / ".rheodda.lock");
        pid_t owner = 0;
        if (lock >> owner && owner > 0 && ::kill(owner, SIGSTOP) == 0) {
          frozen.push_back(owner);
          break;
        }
      }
      BOOST_TEST_REQUIRE(::waitpid(pid, &status, WNOHANG) == 0, "the study ended before it could be killed");
      std::this_thread::yield();
    }
  }
  auto ran_to_its_end = [&](const char* c) {
    return fs::exists(cut / "cases" / c / "summary.json") &&
           read_text((cut / "cases" / c / "summary.json").string()).find("\"completed\"") != std::string::npos;
  };
  for (const char* c : {"a", "b"}) BOOST_TEST_REQUIRE(!ran_to_its_end(c), "case " << c);  // frozen mid-run
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  BOOST_TEST_REQUIRE(WIFSIGNALED(status));
  // The parent-death signal (SIGKILL) ends a stopped process too.
  // The cases die with the study (the kernel's parent-death signal): their locks are free
  // as soon as the kernel has ended them, not when their runs end (3 s each here).
  for (const char* c : {"a", "b"}) {
    int polls = 0;
    while (!lock_free(cut / "cases" / c) && polls++ < 400) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    BOOST_TEST(lock_free(cut / "cases" / c), "case " << c << " still running");
    BOOST_TEST(!ran_to_its_end(c), "case " << c);
  }
  const auto resumed = run_rheodda("study " + (dir / "study.yaml").string() + " -o " + cut.string() +
                                   " -j 2 --no-plot --resume");
  BOOST_TEST_REQUIRE(resumed.exit_code == 0, resumed.output);
  BOOST_TEST(resumed.output.find("3 cases, 3 completed, 0 failed") != std::string::npos, resumed.output);
  for (const char* c : {"a", "b", "c"})
    BOOST_TEST(read_text((cut / "cases" / c / "history.csv").string()) ==
                   read_text((dir / "whole" / "cases" / c / "history.csv").string()),
               c);
}

BOOST_AUTO_TEST_CASE(sigterm_while_a_large_forecast_is_prepared_stops_it_before_its_members_are_written) {
  // issue 43: a 20 000-member forecast honoured SIGTERM only after writing every case
  // folder (45 s). Here 4000 members: the signal comes once ensemble.yaml is written,
  // while the member scenes are built and checked; the forecast stops at once (exit
  // 128 + 15), with fewer member folders than members and nothing run.
  const fs::path dir = fresh_dir("forecast-term");
  const std::string fit = (dir / "fit.json").string();
  BOOST_TEST_REQUIRE(run_rheodda("fit " + source_path("examples/creep-data/table1-row1.csv") +
                                 " --law burgers --stress 0.232 --units 'MPa, mm, h' --json " + fit)
                         .exit_code == 0);
  const fs::path out = dir / "out";
  const pid_t pid = spawn_rheodda({"forecast", source_path("examples/shear-creep-test.yaml"), "--fit", fit,
                                   "--joint-set", "plane", "--samples", "4000", "-j", "1", "--no-plot", "-o",
                                   out.string()});
  int status = 0;
  while (!fs::exists(out / "ensemble.yaml")) {
    BOOST_TEST_REQUIRE(::waitpid(pid, &status, WNOHANG) == 0, "the forecast ended before it could be stopped");
    std::this_thread::yield();
  }
  ::kill(pid, SIGTERM);
  ::waitpid(pid, &status, 0);
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 128 + SIGTERM);
  std::size_t folders = 0, runs = 0;
  if (fs::exists(out / "cases"))
    for (const auto& e : fs::directory_iterator(out / "cases")) {
      ++folders;
      runs += fs::exists(e.path() / "history.csv");
    }
  BOOST_TEST(folders < 4000u);
  BOOST_TEST(runs == 0u);
}

BOOST_AUTO_TEST_CASE(drawn_cases_are_zero_padded_as_the_docs_show_them) {
  BOOST_TEST(st::drawn_case_name(6, 8) == "sample07");  // issue 43: "sample7" with 8 draws
  BOOST_TEST(st::drawn_case_name(6, 20) == "sample07");
  BOOST_TEST(st::drawn_case_name(6, 100) == "sample007");
  BOOST_TEST(st::drawn_case_name(99, 100) == "sample100");
}

BOOST_AUTO_TEST_CASE(a_case_killed_without_a_word_gets_no_stray_separator) {
  // A case whose program dies by a signal before writing anything: the message is
  // "killed by signal 9 (Killed)", not "...(Killed); ".
  const fs::path dir = fresh_dir("silent-crash");
  write_study(dir, 0.05);
  const fs::path wrapper = dir / "case-program.sh";
  std::ofstream(wrapper) << "#!/bin/sh\n"
                            "case \"$2\" in */cases/b/*) kill -KILL $$ ;; esac\n"
                            "exec "
                         << RHEODDA_BINARY << " \"$@\"\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  const auto r = run_rheodda("study " + (dir / "study.yaml").string() + " -o " + (dir / "out").string() +
                             " -j 2 --no-plot --case-program " + wrapper.string());
  BOOST_TEST(r.exit_code == 1, r.output);
  const auto rows = read_study_csv((dir / "out" / "study.csv").string());
  BOOST_TEST_REQUIRE(rows.size() == 3u);
  BOOST_TEST(rows[1].at("status") == "failed");
  BOOST_TEST(rows[1].at("message") == "killed by signal 9 (Killed)");
}

BOOST_AUTO_TEST_CASE(sweep_ticks_tell_apart_outputs_that_differ_by_1e_5) {
  // issue 43: an output varying by 1e-5 of its size got one label on every y tick of
  // study_sweep.png. The tick format study_sweep.gp sets must print the ticks gnuplot
  // would place (a tenth of the range apart, or finer) distinctly.
  const fs::path dir = fresh_dir("ticks");
  std::ofstream(dir / "sliding.yaml") << read_text(source_path("examples/sliding-block.yaml"));
  std::ofstream(dir / "sweep.yaml") << "scene: sliding.yaml\n"
                                       "set: {analysis.duration: 0.02}\n"
                                       "outputs: [centre.v]\n"
                                       "times: [0.02]\n"
                                       "sweep:\n"
                                       "  parameters:\n"
                                       "    - {name: phi, key: joint_sets.slope.friction_angle, unit: deg, "
                                       "values: [40, 40.0001, 40.0002, 40.0003]}\n";
  const auto r = run_rheodda("study " + (dir / "sweep.yaml").string() + " -o " + (dir / "out").string() + " -j 2");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.output);
  const std::string gp = read_text((dir / "out" / "study_sweep.gp").string());
  std::smatch m;
  BOOST_TEST_REQUIRE(std::regex_search(gp, m, std::regex("set format x '%\\.([0-9]+)g'")), gp);
  const int digits = std::stoi(m[1]);
  // Ticks 1e-5 deg apart at 40 deg (a tenth of the 1e-4 range, or finer: 2e-5 .. 1e-5).
  const auto label = [&](double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return std::string(buf);
  };
  BOOST_TEST(label(40.00001) != label(40.00002));
  BOOST_TEST(label(40.00002) != label(40.00003));
  BOOST_TEST(gp.find("set format y '") != std::string::npos, gp);
}

BOOST_AUTO_TEST_SUITE_END()
