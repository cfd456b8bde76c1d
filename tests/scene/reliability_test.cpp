// A run's outputs under faults: a rerun killed before its first checkpoint, files
// cut or changed after a checkpoint, a deleted frame, two runs in one folder,
// values that are no longer finite, unbounded motion (docs/reference/outputs.md,
// "Interrupting and resuming" and "Runs that stop").
#include <boost/test/unit_test.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <algorithm>
#include <map>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <set>
#include <nlohmann/json.hpp>
#include <thread>

#include "run_support.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/run.hpp"


using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;

namespace {

std::string status_of(const fs::path& out) {
  return nlohmann::json::parse(read_text((out / "summary.json").string())).at("status").get<std::string>();
}

/// The message of the exception `f` throws as E (fails the test if none is thrown).
template <class E, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  BOOST_ERROR("no exception of the expected type");
  return "";
}

bool has_nonfinite_text(const std::string& csv) {
  return csv.find("nan") != std::string::npos || csv.find("inf") != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(run_reliability)

BOOST_AUTO_TEST_CASE(a_rerun_killed_before_its_first_checkpoint_is_never_resumed_onto_emptied_files) {
  // The full sliding-block example: run it, then run it again into the same
  // folder and kill -9 the second run as soon as it has emptied history.csv
  // (its first moments), at several moments. --resume must then either refuse
  // (nothing to continue) or produce exactly the uninterrupted files; never pad
  // the CSVs with NUL bytes or report success on a corrupt history.
  const std::string scene = source_path("examples/sliding-block.yaml");
  const fs::path whole = fresh_dir("rerun-whole");
  BOOST_TEST_REQUIRE(run_rheodda("run " + scene + " -o " + whole.string()).exit_code == 0);
  const std::string whole_history = read_text((whole / "history.csv").string());
  for (int attempt = 0; attempt < 4; ++attempt) {
    const fs::path out = fresh_dir("rerun-" + std::to_string(attempt));
    BOOST_TEST_REQUIRE(run_rheodda("run " + scene + " -o " + out.string()).exit_code == 0);
    const pid_t pid = spawn_rheodda({"run", scene, "-o", out.string()});
    // Wait until the new run has emptied the history (by watching the file), then
    // a little longer on each attempt, then kill it without warning.
    int status = 0;
    for (;;) {
      std::error_code ec;
      const auto size = fs::file_size(out / "history.csv", ec);
      if (ec || size < whole_history.size()) break;
      if (::waitpid(pid, &status, WNOHANG) == pid) break;
      std::this_thread::yield();
    }
    std::this_thread::sleep_for(std::chrono::microseconds(300 * attempt));
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);

    const auto resumed = run_rheodda("run " + scene + " -o " + out.string() + " --resume");
    const std::string history = read_text((out / "history.csv").string());
    BOOST_TEST(history.find('\0') == std::string::npos, "NUL bytes in history.csv after attempt " << attempt);
    if (resumed.exit_code == 0) {
      BOOST_TEST(history == whole_history, "attempt " << attempt);
      BOOST_TEST(read_text((out / "contacts.csv").string()) == read_text((whole / "contacts.csv").string()));
      BOOST_TEST(read_text((out / "blocks.pvd").string()) == read_text((whole / "blocks.pvd").string()));
    } else {
      BOOST_TEST(resumed.exit_code == 2, resumed.output);
      BOOST_TEST(resumed.output.find("no checkpoint.json") != std::string::npos, resumed.output);
    }
  }
}

BOOST_AUTO_TEST_CASE(resume_refuses_files_cut_or_changed_after_the_checkpoint_and_changes_nothing) {
  const auto s = sliding(0.05, 0.01);
  const fs::path base = fresh_dir("cut-base");
  BOOST_TEST_REQUIRE((run(s, base, 20).status == scene::RunStatus::interrupted));
  const auto history_size = fs::file_size(base / "history.csv");

  // A history.csv shorter than the checkpoint says (a crash without fsync, a copy).
  const fs::path cut = fresh_dir("cut-short");
  fs::copy(base, cut, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::resize_file(cut / "history.csv", 500);
  const std::string m1 = message_of<std::invalid_argument>([&] { run(s, cut, -1, true); });
  BOOST_TEST(m1.find("history.csv has 500 bytes") != std::string::npos, m1);
  BOOST_TEST(fs::file_size(cut / "history.csv") == 500u);  // nothing padded

  // A checkpoint claiming far more than the file holds (1 TB).
  const fs::path big = fresh_dir("cut-big");
  fs::copy(base, big, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  auto ck = nlohmann::json::parse(read_text((big / "checkpoint.json").string()));
  ck["history_bytes"] = 1000000000000ull;
  { std::ofstream(big / "checkpoint.json") << ck.dump(1); }
  const std::string m2 = message_of<std::invalid_argument>([&] { run(s, big, -1, true); });
  BOOST_TEST(m2.find("checkpoint counts 1000000000000") != std::string::npos, m2);
  BOOST_TEST(fs::file_size(big / "history.csv") == history_size);

  // Same length, one byte changed within what the checkpoint keeps.
  const fs::path edited = fresh_dir("cut-edited");
  fs::copy(base, edited, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  std::string text = read_text((edited / "contacts.csv").string());
  text[text.size() / 2] = text[text.size() / 2] == '1' ? '2' : '1';
  { std::ofstream(edited / "contacts.csv", std::ios::binary) << text; }
  const std::string m3 = message_of<std::invalid_argument>([&] { run(s, edited, -1, true); });
  BOOST_TEST(m3.find("contacts.csv differ from those the checkpoint recorded") != std::string::npos, m3);
  BOOST_TEST(read_text((edited / "contacts.csv").string()) == text);
}

BOOST_AUTO_TEST_CASE(resume_writes_a_deleted_or_changed_frame_again) {
  const auto s = sliding(0.05, 0.01);
  const fs::path whole = fresh_dir("frames-whole"), out = fresh_dir("frames-cut");
  BOOST_TEST_REQUIRE((run(s, whole).status == scene::RunStatus::completed));
  BOOST_TEST_REQUIRE((run(s, out, 30).status == scene::RunStatus::interrupted));  // frames 0..3 written
  fs::remove(out / "frames/blocks_000001.vtp");
  fs::remove(out / "frames/blocks_000003.vtp");  // the frame of the checkpoint's segment
  { std::ofstream(out / "frames/blocks_000002.vtp") << "changed"; }
  fs::remove(out / "blocks.pvd");
  fs::remove(out / "frames/contacts_000001.vtp");  // the contact layer of a frame likewise
  { std::ofstream(out / "frames/contacts_000000.vtp") << "changed"; }
  fs::remove(out / "contacts.pvd");
  const auto r = run(s, out, -1, true);
  BOOST_TEST((r.status == scene::RunStatus::completed));
  for (const char* f : {"frames/blocks_000001.vtp", "frames/blocks_000002.vtp", "frames/blocks_000003.vtp",
                        "frames/blocks_000005.vtp", "blocks.pvd", "history.csv", "contacts.csv",
                        "frames/contacts_000000.vtp", "frames/contacts_000001.vtp", "frames/contacts_000005.vtp",
                        "contacts.pvd"})
    BOOST_TEST(read_text((out / f).string()) == read_text((whole / f).string()), f);
}

BOOST_AUTO_TEST_CASE(a_second_run_into_a_folder_in_use_is_refused_with_the_first_runs_process) {
  const auto s = sliding(0.01, 0.01);
  const fs::path out = fresh_dir("locked");
  const scene::FolderLock held(out.string());  // as a run in progress holds it
  const std::string m = message_of<std::runtime_error>([&] { run(s, out); });
  BOOST_TEST(m.find("in use by another rheodda run (process " + std::to_string(::getpid()) + ")") !=
                 std::string::npos,
             m);
  BOOST_TEST(!fs::exists(out / "history.csv"));  // nothing written
}

BOOST_AUTO_TEST_CASE(resume_into_a_missing_folder_or_another_scenes_folder_is_refused_without_writing) {
  const auto s = sliding(0.02, 0.01);
  const fs::path missing = fs::temp_directory_path() / ("rheodda-apps-test-missing-" + std::to_string(::getpid()));
  fs::remove_all(missing);
  const std::string m1 = message_of<std::invalid_argument>([&] { run(s, missing, -1, true); });
  BOOST_TEST(m1.find("no checkpoint.json (the folder does not exist)") != std::string::npos, m1);
  BOOST_TEST(!fs::exists(missing));

  const fs::path other = fresh_dir("other-scene");
  auto creep = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  creep.analysis.duration = 2.0;
  creep.analysis.output_interval = 1.0;
  BOOST_TEST_REQUIRE((run(creep, other, 1).status == scene::RunStatus::interrupted));
  const std::string before = read_text((other / "history.csv").string());
  const std::string m2 = message_of<std::invalid_argument>([&] { run(s, other, -1, true); });
  BOOST_TEST(m2.find("shear-creep-test.yaml") != std::string::npos, m2);  // the folder's scene
  BOOST_TEST(m2.find(creep.title) != std::string::npos, m2);
  BOOST_TEST(m2.find("new folder") != std::string::npos, m2);
  BOOST_TEST(read_text((other / "history.csv").string()) == before);
}

BOOST_AUTO_TEST_CASE(values_at_the_limits_of_double_precision_stop_the_run_before_a_nan_is_written) {
  // Each value passes its range check; each makes the state non-finite.
  struct Case {
    const char* what;
    std::function<void(scene::SceneDescription&)> change;
  };
  const std::vector<Case> cases{
      {"dt 1e-300", [](scene::SceneDescription& s) { s.analysis.dt = 1e-300; }},
      {"penalty 1e308", [](scene::SceneDescription& s) { s.analysis.penalty = 1e308; }},
      {"dt 1e-16, density 1e300",
       [](scene::SceneDescription& s) {
         s.analysis.dt = 1e-16;
         s.materials[0].density = 1e300;
       }},
  };
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.what) {
      auto s = sliding(0.01, 0.005);
      c.change(s);
      const fs::path out = fresh_dir("nonfinite");
      const std::string m = message_of<std::runtime_error>([&] { run(s, out); });
      BOOST_TEST(m.find("is not finite after step") != std::string::npos, m);
      BOOST_TEST(!has_nonfinite_text(read_text((out / "history.csv").string())));
      BOOST_TEST(!has_nonfinite_text(read_text((out / "contacts.csv").string())));
      BOOST_TEST(status_of(out) == "failed");
    }
  }
  // A viscosity of 5e-324 (the smallest double) on the shear creep test.
  auto creep = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  creep.joint_sets[0].law->parameters["eta1"] = 5e-324;
  creep.analysis.duration = 2.0;
  creep.analysis.output_interval = 1.0;
  const fs::path out = fresh_dir("nonfinite-eta");
  const std::string m = message_of<std::runtime_error>([&] { run(creep, out); });
  BOOST_TEST(m.find("not finite") != std::string::npos, m);
  BOOST_TEST(!has_nonfinite_text(read_text((out / "history.csv").string())));
  BOOST_TEST(status_of(out) == "failed");
}

BOOST_AUTO_TEST_CASE(unbounded_motion_and_runaway_output_stop_at_the_guards_with_outputs_kept) {
  // No friction: the block slides off its base and falls without end.
  auto s = sliding(1e6, 1e3);
  s.joint_sets[0].friction_angle = 0.0;
  s.analysis.history = scene::HistoryRows::steps;  // a row per step, up to the one that tripped the guard
  const fs::path out = fresh_dir("runaway");
  const std::string m = message_of<std::runtime_error>([&] { run(s, out); });
  BOOST_TEST(m.find("max_travel_ratio (10)") != std::string::npos, m);
  BOOST_TEST(m.find("run stopped") == 0u, m);
  BOOST_TEST(status_of(out) == "failed");
  // The history is kept, whole rows, up to the step that tripped the guard.
  const std::string h = read_text((out / "history.csv").string());
  BOOST_TEST(h.back() == '\n');
  BOOST_TEST(std::count(h.begin(), h.end(), '\n') > 100);

  // The output guard: 0.05 MB of outputs allowed.
  auto t = sliding(1.0, 0.001);
  t.analysis.max_output_size = 0.05;  // [MB]
  const fs::path out2 = fresh_dir("runaway-output");
  const std::string m2 = message_of<std::runtime_error>([&] { run(t, out2); });
  BOOST_TEST(m2.find("max_output_size (0.05 MB)") != std::string::npos, m2);
  const double bytes = double(fs::file_size(out2 / "history.csv") + fs::file_size(out2 / "contacts.csv"));
  BOOST_TEST(bytes < 0.05e6 + 2e4);  // stopped within a step's output of the limit (frames aside)

  // 0 = no limit: the same scene runs to its end.
  auto u = sliding(0.02, 0.01);
  u.analysis.max_output_size = 0.0;
  u.analysis.max_travel_ratio = 0.0;
  BOOST_TEST((run(u, fresh_dir("no-guard")).status == scene::RunStatus::completed));
}

BOOST_AUTO_TEST_CASE(a_write_that_fails_names_the_file_and_the_reason_and_leaves_no_tmp_file) {
  BOOST_TEST(scene::write_error("/x/out/summary.json", ENOSPC).find("No space left on device") != std::string::npos);
  BOOST_TEST(scene::write_error("/x/out/summary.json", ENOSPC).find("free space in /x/out") != std::string::npos);
  // A target that cannot be renamed over (a non-empty folder): the .tmp goes.
  const fs::path d = fresh_dir("atomic");
  fs::create_directories(d / "target" / "inside");
  const std::string m = message_of<std::runtime_error>(
      [&] { scene::write_file_atomic((d / "target").string(), "text"); });
  BOOST_TEST(m.find("cannot write " + (d / "target").string()) == 0u, m);
  BOOST_TEST(!fs::exists(d / "target.tmp"));
}

BOOST_AUTO_TEST_CASE(a_step_ends_on_every_output_time_where_cuts_take_the_steps_off_the_grid) {
  // The seed's slope over 60 days on its own static steps: its cuts take the time off
  // the grid k dt, and frames used to come at the end of the first step past each output
  // time (1.0076, 2.0216, ... d for an interval of 1 d). Now a step ends on each output
  // time, whatever the interval, and history.csv has its row there. (The output times
  // are then part of the path: docs/notes/step-controls.md, "Output times and the steps".)
  for (const double interval : {1.0, 7.0, 10.0}) {
    BOOST_TEST_CONTEXT("output_interval " << interval << " d") {
      auto s = scene::load_scene(source_path("bench/scenes/goodman-toppling-seed-steps.yaml"));
      s.analysis.output_interval = interval;
      const fs::path out = fresh_dir("interval");
      const auto r = run(s, out);
      BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
      BOOST_TEST(r.cuts > 0);  // the case this is about
      std::vector<double> expected;
      for (int k = 0; k * interval < 60.0; ++k) expected.push_back(k * interval);
      expected.push_back(60.0);
      std::vector<double> frames;  // blocks.pvd's times
      const std::string pvd = read_text((out / "blocks.pvd").string());
      for (std::size_t at = pvd.find("timestep=\""); at != std::string::npos; at = pvd.find("timestep=\"", at + 1))
        frames.push_back(std::stod(pvd.substr(at + 10)));
      BOOST_TEST_REQUIRE(frames.size() == expected.size());
      std::set<double> rows;  // history.csv's times
      std::istringstream in(read_text((out / "history.csv").string()));
      std::string line;
      while (std::getline(in, line))
        if (!line.empty() && line[0] != '#' && line.rfind("time,", 0) != 0) rows.insert(std::stod(line));
      for (std::size_t k = 0; k < expected.size(); ++k) {
        BOOST_TEST(std::abs(frames[k] - expected[k]) <= 1e-9 * 60.0, frames[k] << " for " << expected[k]);
        const auto row = rows.lower_bound(expected[k] - 1e-9 * 60.0);
        BOOST_TEST((row != rows.end() && std::abs(*row - expected[k]) <= 1e-9 * 60.0), "no row at t = " << expected[k]);
      }
      BOOST_TEST(rows.size() == expected.size());  // no dynamic stage, no failure: the output times' rows only
    }
  }
}

BOOST_AUTO_TEST_CASE(check_and_run_warn_of_a_step_beyond_the_lagged_limit_and_of_slivers) {
  // The shear creep test's Burgers joint (k = E1 = 26.87 MPa/mm): its dashpot's
  // lagged limit is 2 eta1/E1 = 2 x 34807.72/26.87 = 2590.8 h.
  auto s = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  s.analysis.scheme = laws::Scheme::lagged;
  s.analysis.duration = 6000.0;
  s.analysis.output_interval = 3000.0;
  s.analysis.dt = 2000.0;
  BOOST_TEST(scene::scene_warnings(s).empty());
  s.analysis.dt = 3000.0;
  const auto w = scene::scene_warnings(s);
  BOOST_TEST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("joint set 'plane': the lagged scheme is unstable for steps above 2590.82 h") == 0u, w[0]);
  BOOST_TEST(scene::describe_scene(s).find(w[0]) != std::string::npos);
  s.analysis.scheme = laws::Scheme::implicit;  // stable at any step: no warning
  BOOST_TEST(scene::scene_warnings(s).empty());
  // The run lists the warning in summary.json.
  s.analysis.scheme = laws::Scheme::lagged;
  const fs::path out = fresh_dir("lagged-warning");
  const auto r = run(s, out);
  BOOST_TEST(r.warnings == w);
  const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(sum.at("warnings").at(0).get<std::string>() == w[0]);

  // A sliver block (1e-7 m thick on a 10 m model).
  auto t = scene::parse_scene(
      with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1, 1.5], [2, 1.5], [2, 1.5000001], [1, 1.5000001]]"), "sliver.yaml");
  const auto ws = scene::scene_warnings(t);
  BOOST_TEST_REQUIRE(ws.size() == 1u);
  BOOST_TEST(ws[0].find("block 'top' is a sliver") == 0u, ws[0]);
}

BOOST_AUTO_TEST_CASE(files_that_are_not_scenes_are_refused_with_what_they_are) {
  const fs::path d = fresh_dir("inputs");
  auto error_of = [](const std::string& path) {
    try {
      (void)scene::load_scene(path);
    } catch (const scene::SceneError& e) {
      return std::string(e.what());
    }
    BOOST_ERROR("no SceneError for " << path);
    return std::string();
  };
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(d / name, std::ios::binary) << text;
    return (d / name).string();
  };
  // No ":0:0" where no line is known.
  BOOST_TEST(error_of((d / "missing.yaml").string()) ==
             (d / "missing.yaml").string() + ": cannot open the scene file: No such file or directory");
  BOOST_TEST(error_of(d.string()) == d.string() + ": is a folder, not a scene file");
  BOOST_TEST(error_of("/dev/zero").find("/dev/zero: is not a regular file") == 0u);
  BOOST_TEST(error_of(write("empty.yaml", "\n  \n")).find(": the scene file is empty") != std::string::npos);
  // Encodings: Latin-1 and UTF-16 are refused where the first foreign byte is;
  // a UTF-8 byte-order mark is accepted.
  const std::string latin1 = "title: \"Caf\xE9\"\n" + kBaseScene;
  BOOST_TEST(error_of(write("latin1.yaml", latin1)).find("latin1.yaml:1:12: byte 0xE9 is not UTF-8") !=
                 std::string::npos,
             error_of(write("latin1.yaml", latin1)));
  BOOST_TEST(error_of(write("utf16.yaml", "\xFF\xFEt\0i\0")).find("UTF-16") != std::string::npos);
  BOOST_TEST(scene::load_scene(write("bom.yaml", "\xEF\xBB\xBF" + kBaseScene)).blocks.size() == 2u);
  // A tab in the indentation (yaml-cpp would say "illegal map value").
  const std::string tabbed = with("  duration: 1\n", "\tduration: 1\n");
  BOOST_TEST(error_of(write("tab.yaml", tabbed)).find("tab.yaml:3:1: a tab in the indentation") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(geometry_messages_say_what_is_wrong_with_the_block_that_is_wrong) {
  // A symmetric bow-tie: zero area because its edges cross.
  expect_error(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1, 1], [2, 2], [2, 1], [1, 2]]"), 13, 0, "blocks[1]",
               "edges 0 and 2 cross");
  // A sliver thinner than the tolerance: not "repeats its first vertex".
  expect_error(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1, 1], [2, 1], [2, 1.000000000001], [1, 1.000000000001]]"),
               13, 0, "blocks[1]", "has vertices 0 and 3 only 1.0000");
  // A block 1e9 m away is named itself, not the blocks its size would make degenerate.
  expect_error(with("measurement_points:\n",
                    "  - {name: far, polygon: [[1e9, 0], [1.000000001e9, 0], [1.000000001e9, 1], [1e9, 1]], joint_set: bedding}\n"
                    "measurement_points:\n"),
               14, 0, "blocks[2]", "block 'far' lies 1e+09 m from all the other blocks");
  // With two blocks both are named.
  expect_error(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1e9, 1], [1.000000001e9, 1], [1.000000001e9, 2], [1e9, 2]]"),
               12, 0, "blocks[0]", "blocks 'base' and 'top' lie 1e+09 m apart");
  // Coordinates whose areas overflow.
  expect_error(with("[[1, 1], [2, 1], [2, 2], [1, 2]]", "[[1, 1], [1e200, 1], [1e200, 1e200], [1, 1e200]]"), 13, 0,
               "blocks[1]", "beyond 1e150");
}

BOOST_AUTO_TEST_CASE(a_denormal_law_parameter_is_described_not_a_stod_error) {
  auto s = scene::parse_scene(with("E1: 1", "E1: 1e-310"), "denormal.yaml");
  BOOST_TEST(scene::describe_scene(s).find("E1=1e-310") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(an_output_folder_that_cannot_be_made_is_bad_input) {
  const fs::path d = fresh_dir("unusable");
  { std::ofstream(d / "file") << "x"; }
  const auto s = sliding(0.01, 0.01);
  const std::string m = message_of<std::invalid_argument>([&] { run(s, d / "file" / "out"); });
  BOOST_TEST(m.find("cannot write " + (d / "file" / "out" / "frames").string()) == 0u, m);
  const auto r = run_rheodda("run " + source_path("examples/sliding-block.yaml") + " -o " + (d / "file" / "out").string());
  BOOST_TEST(r.exit_code == 2, r.output);
}

BOOST_AUTO_TEST_CASE(the_run_says_where_each_joint_sets_law_acted) {
  // The shear creep test: the plane's law acts on every locked contact for the
  // whole run; contacts.csv carries each contact's creep displacement and state.
  auto s = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  s.analysis.duration = 10.0;
  s.analysis.output_interval = 5.0;
  const fs::path out = fresh_dir("creep-visible");
  const auto r = run(s, out);
  BOOST_TEST_REQUIRE(r.creep.size() == 1u);
  BOOST_TEST(r.creep[0].joint_set == "plane");
  BOOST_TEST(r.creep[0].contacts > 0);
  // Locked from the first step to the last: contact-time = contacts x duration.
  BOOST_TEST(r.creep[0].contact_time == r.creep[0].contacts * 10.0, boost::test_tools::tolerance(1e-12));
  const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(sum.at("creep").at("plane").at("contacts").get<int>() == r.creep[0].contacts);
  BOOST_TEST(r.warnings.empty());
  // history.csv: the mean magnitude of the joint's shear displacement beside the
  // signed mean; every contact of this joint slips the same way, so they agree.
  {
    std::istringstream in(read_text((out / "history.csv").string()));
    std::string line, header;
    std::getline(in, line);  // units
    std::getline(in, header);
    std::vector<std::string> names, last;
    for (std::istringstream h(header); std::getline(h, line, ',');) names.push_back(line);
    std::string row, final_row;
    while (std::getline(in, row)) final_row = row;
    for (std::istringstream cells(final_row); std::getline(cells, line, ',');) last.push_back(line);
    auto at = [&](const std::string& col) {
      const auto it = std::find(names.begin(), names.end(), col);
      BOOST_TEST_REQUIRE((it != names.end()), col);
      return std::stod(last.at(static_cast<std::size_t>(it - names.begin())));
    };
    BOOST_TEST(at("plane.shear_displacement_magnitude") > 0.0);
    BOOST_TEST(at("plane.shear_displacement_magnitude") == std::abs(at("plane.shear_displacement")),
               boost::test_tools::tolerance(1e-9));
  }
  const std::string csv = read_text((out / "contacts.csv").string());
  BOOST_TEST(csv.find(",creep_displacement,creep_state\n") != std::string::npos);
  BOOST_TEST(csv.find(",creeping\n") != std::string::npos);

  // A law on a joint set no contact lies on (the top face of the upper block) never acts: said so.
  auto t = scene::parse_scene(with("edge_joint_sets: [fault, bedding, bedding, bedding]",
                                   "edge_joint_sets: [bedding, bedding, fault, bedding]",
                                   with("  duration: 1\n", "  duration: 0.05\n")),
                              "never.yaml");
  const fs::path out2 = fresh_dir("creep-never");
  const auto r2 = scene::run_scene(t, "never", [&] {
    scene::RunOptions o;
    o.out_dir = out2.string();
    return o;
  }());
  BOOST_TEST_REQUIRE(r2.creep.size() == 1u);
  BOOST_TEST(r2.creep[0].joint_set == "fault");
  BOOST_TEST(r2.creep[0].contacts == 0);
  BOOST_TEST_REQUIRE(r2.warnings.size() == 1u);
  BOOST_TEST(r2.warnings[0] == "joint set 'fault' has a creep law but none of its contacts crept (none stayed locked "
                               "through a step)");
}

/// The regular files under `dir` (paths relative to it), sorted.
std::vector<std::string> files_under(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

/// Waits (by watching the file, not the clock) until the run `pid` has written some steps into `out`.
void wait_for_steps(pid_t pid, const fs::path& out) {
  int status = 0;
  for (;;) {
    std::error_code ec;
    if (fs::exists(out / "history.csv", ec) && fs::file_size(out / "history.csv", ec) > 3000) return;
    BOOST_TEST_REQUIRE(::waitpid(pid, &status, WNOHANG) == 0, "the run ended before it could be signalled");
    std::this_thread::yield();
  }
}

BOOST_AUTO_TEST_CASE(a_run_removes_its_lock_however_it_ends_and_keeps_its_outputs) {
  // issue 52: `.rheodda.lock` stayed in the folder after every run.
  const fs::path done = fresh_dir("lock-done");
  BOOST_TEST((run(sliding(0.02, 0.01), done).status == scene::RunStatus::completed));
  BOOST_TEST(!fs::exists(done / ".rheodda.lock"));
  BOOST_TEST(status_of(done) == "completed");
  // Stopped between two steps (what Ctrl-C and kill do): the checkpoint and outputs stay.
  const fs::path stopped = fresh_dir("lock-stopped");
  BOOST_TEST((run(sliding(0.05, 0.01), stopped, 3).status == scene::RunStatus::interrupted));
  BOOST_TEST(!fs::exists(stopped / ".rheodda.lock"));
  BOOST_TEST(fs::exists(stopped / "checkpoint.json"));
  BOOST_TEST(status_of(stopped) == "interrupted");
  // Failed.
  auto bad = sliding(0.01, 0.005);
  bad.analysis.dt = 1e-300;
  const fs::path failed = fresh_dir("lock-failed");
  (void)message_of<std::runtime_error>([&] { run(bad, failed); });
  BOOST_TEST(!fs::exists(failed / ".rheodda.lock"));
  BOOST_TEST(status_of(failed) == "failed");
  // Ctrl-C of the command: exit 130, no lock, the outputs so far kept and resumable.
  const std::string scene = source_path("examples/sliding-block.yaml");
  const fs::path cut = fresh_dir("lock-sigint");
  const pid_t pid = spawn_rheodda({"run", scene, "-o", cut.string()});
  wait_for_steps(pid, cut);
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 128 + SIGINT);
  BOOST_TEST(!fs::exists(cut / ".rheodda.lock"));
  BOOST_TEST(status_of(cut) == "interrupted");
  BOOST_TEST(fs::file_size(cut / "history.csv") > 3000u);
  const auto resumed = run_rheodda("run " + scene + " -o " + cut.string() + " --resume");
  BOOST_TEST(resumed.exit_code == 0, resumed.output);
  BOOST_TEST(!fs::exists(cut / ".rheodda.lock"));
}

BOOST_AUTO_TEST_CASE(a_lock_left_by_a_run_that_no_longer_runs_does_not_block_the_next) {
  // kill -9 leaves the file (nothing can remove it), with the process id of the dead run.
  const std::string scene = source_path("examples/sliding-block.yaml");
  const fs::path out = fresh_dir("lock-killed");
  const pid_t pid = spawn_rheodda({"run", scene, "-o", out.string()});
  wait_for_steps(pid, out);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  BOOST_TEST_REQUIRE(fs::exists(out / ".rheodda.lock"));
  long owner = 0;
  std::ifstream(out / ".rheodda.lock") >> owner;
  BOOST_TEST(owner == static_cast<long>(pid));
  const auto again = run_rheodda("run " + scene + " -o " + out.string());
  BOOST_TEST(again.exit_code == 0, again.output);
  BOOST_TEST(!fs::exists(out / ".rheodda.lock"));
  // A lock file naming a process that has ended, as any file system leaves it.
  std::ofstream(out / ".rheodda.lock") << pid << "\n";
  BOOST_TEST((run(sliding(0.02, 0.01), out).status == scene::RunStatus::completed));
  BOOST_TEST(!fs::exists(out / ".rheodda.lock"));
}

BOOST_AUTO_TEST_CASE(a_new_run_replaces_the_earlier_runs_outputs_and_pictures_and_keeps_the_users_files) {
  // issue 52: a second run into a folder kept the first one's plots/ beside the new
  // results (and the frames beyond its own end).
  const fs::path out = fresh_dir("fresh-run");
  BOOST_TEST_REQUIRE((run(sliding(0.1, 0.01), out).status == scene::RunStatus::completed));  // 11 frames
  scene::PlotOptions po;
  po.out_dir = out.string();
  (void)scene::plot_run(po);
  std::ofstream(out / "notes.txt") << "mine";
  std::ofstream(out / "plots" / "sketch.pdf") << "mine";
  BOOST_TEST_REQUIRE(fs::exists(out / "frames/blocks_000010.vtp"));
  BOOST_TEST_REQUIRE(fs::exists(out / "plots/history.png"));
  BOOST_TEST_REQUIRE((run(sliding(0.02, 0.01), out).status == scene::RunStatus::completed));  // 3 frames
  for (const char* gone : {"frames/blocks_000003.vtp", "frames/blocks_000010.vtp", "frames/contacts_000010.vtp",
                           "plots/history.png", "plots/history.gp", "plots/blocks_000005.png",
                           "plots/blocks_000005_initial.dat"})
    BOOST_TEST(!fs::exists(out / gone), gone);
  BOOST_TEST(fs::exists(out / "frames/blocks_000002.vtp"));
  BOOST_TEST(read_text((out / "notes.txt").string()) == "mine");
  BOOST_TEST(read_text((out / "plots" / "sketch.pdf").string()) == "mine");
  // --resume continues the run in place: the pictures of its first part stay.
  const fs::path part = fresh_dir("fresh-run-resume");
  BOOST_TEST_REQUIRE((run(sliding(0.1, 0.01), part, 30).status == scene::RunStatus::interrupted));
  po.out_dir = part.string();
  (void)scene::plot_run(po);
  BOOST_TEST_REQUIRE((run(sliding(0.1, 0.01), part, -1, true).status == scene::RunStatus::completed));
  BOOST_TEST(fs::exists(part / "plots/history.png"));
}

BOOST_AUTO_TEST_CASE(every_file_a_run_and_plot_write_is_one_a_new_run_removes) {
  // Bolts (bolts.csv, bolts.pvd, bolt frames, bolts.png) and a settling stage
  // (events.csv): a new output that remove_run_outputs does not know fails here.
  for (const char* example : {"examples/bolted-block.yaml", "examples/excavation-stages.yaml"}) {
    BOOST_TEST_CONTEXT(example) {
      const auto s = scene::load_scene(source_path(example));
      const fs::path out = fresh_dir("remove-outputs");
      BOOST_TEST_REQUIRE((run(s, out).status == scene::RunStatus::completed));
      scene::PlotOptions po;
      po.out_dir = out.string();
      (void)scene::plot_run(po);
      std::ofstream(out / "notes.txt") << "mine";
      BOOST_TEST(files_under(out).size() > 10u);
      scene::remove_run_outputs(out.string());
      BOOST_TEST(files_under(out) == std::vector<std::string>{"notes.txt"}, fmt::format("{}", fmt::join(files_under(out), " ")));
      BOOST_TEST(!fs::exists(out / "plots"));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_CASE(a_run_that_will_not_fit_in_memory_is_refused_before_it_starts_with_an_estimate) {
  // 400 x 400 = 160 000 blocks (about 2.7 GB by the estimate) under `ulimit -v`
  // of 1.5 GB: refused at once, naming the estimate and what is available,
  // instead of growing until std::bad_alloc.
  const fs::path d = fresh_dir("memory");
  {
    std::ofstream f(d / "big.yaml");
    f << "title: wall too large for its memory\n"
         "units: {length: m, force: N, time: s}\n"
         "analysis: {type: dynamic, duration: 0.01, dt: 0.001, gravity: [0, -9.81]}\n"
         "materials: {rock: {density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}}\n"
         "joint_sets: {j: {friction_angle: 35}}\n"
         "blocks:\n"
         "  - {name: base, rectangle: {x: -1, y: -1, width: 402, height: 1}, fixed: true}\n"
         "  - {name: w, grid: {x: 0, y: 0, width: 1, height: 0.5, columns: 400, rows: 400}}\n";
  }
  const auto r = run_command("ulimit -v 1500000; exec " + std::string(RHEODDA_BINARY) + " run " +
                              (d / "big.yaml").string() + " -o " + (d / "out").string());
  const std::string& out = r.output;
  BOOST_TEST(r.exit_code == 1, out);
  BOOST_TEST(out.find("the run needs about 2.7 GB of memory (160001 blocks, solver amg)") != std::string::npos, out);
  BOOST_TEST(out.find("may use only") != std::string::npos, out);
  // `check` says the same before anything runs.
  const auto c = run_rheodda("check " + (d / "big.yaml").string());
  BOOST_TEST(c.exit_code == 0, c.output);
  BOOST_TEST(c.output.find("estimated memory of a run: 2.7 GB (solver amg)") != std::string::npos, c.output);
  fs::remove_all(d);
}

BOOST_AUTO_TEST_CASE(the_run_reports_how_many_contacts_a_damage_law_failed_and_when_the_first_did) {
  // examples/damage-creep-test.yaml: the two contacts of the sheared joint fail
  // at 143.5-144 h and 151-151.5 h (Kachanov's t_f = 149.9 h at the mean stress;
  // the contact nearer the shear load carries more and fails first).
  const auto s = scene::load_scene(source_path("examples/damage-creep-test.yaml"));
  const fs::path out = fresh_dir("damage-failures");
  const auto r = run(s, out);
  BOOST_TEST_REQUIRE(r.creep.size() == 1u);
  BOOST_TEST(r.creep[0].failures == 2);
  BOOST_TEST(r.creep[0].first_failure_time >= 143.5);
  BOOST_TEST(r.creep[0].first_failure_time <= 144.0);
  const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(sum.at("creep").at("plane").at("failures").get<int>() == 2);
  BOOST_TEST(sum.at("creep").at("plane").at("first_failure_time").get<double>() == r.creep[0].first_failure_time);
  // A law that cannot fail reports none, and null for the time.
  const auto s2 = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  auto s3 = s2;
  s3.analysis.duration = 2.0;
  const fs::path out2 = fresh_dir("no-failures");
  const auto r2 = run(s3, out2);
  BOOST_TEST(r2.creep.at(0).failures == 0);
  const auto sum2 = nlohmann::json::parse(read_text((out2 / "summary.json").string()));
  BOOST_TEST(sum2.at("creep").at("plane").at("first_failure_time").is_null());
  fs::remove_all(out);
  fs::remove_all(out2);
}

BOOST_AUTO_TEST_CASE(automatic_solver_falls_back_to_cholmod_when_amg_does_not_converge) {
  // 2 001 blocks: `automatic` picks amg. With one CG iteration allowed, amg cannot
  // converge; the solve is redone by CHOLMOD, which runs the rest: the run is
  // the CHOLMOD run to the last digit, and summary.json says so.
  const std::string wall =
      "title: wall\n"
      "units: {length: m, force: N, time: s}\n"
      "analysis: {type: dynamic, duration: 0.002, dt: 0.001, gravity: [0, -9.81], solver_max_iterations: 1}\n"
      "materials: {rock: {density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}}\n"
      "joint_sets: {j: {friction_angle: 35}}\n"
      "blocks:\n"
      "  - {name: base, rectangle: {x: -1, y: -1, width: 52, height: 1}, fixed: true}\n"
      "  - {name: w, grid: {x: 0, y: 0, width: 1, height: 0.5, columns: 50, rows: 40}}\n"
      "measurement_points:\n"
      "  - {name: top, point: [10.5, 9.75], block: w.r20.c11}\n";
  const fs::path d = fresh_dir("amg-fallback");
  const auto automatic = scene::parse_scene(wall, "wall.yaml");
  const auto cholmod = scene::parse_scene(with("solver_max_iterations: 1", "solver_max_iterations: 1, solver: cholmod", wall),
                                          "wall-cholmod.yaml");
  run(automatic, d / "automatic");
  run(cholmod, d / "cholmod");
  BOOST_TEST(read_text((d / "automatic" / "history.csv").string()) == read_text((d / "cholmod" / "history.csv").string()));
  const auto sum = nlohmann::json::parse(read_text((d / "automatic" / "summary.json").string()));
  BOOST_TEST(sum.at("solver").at("used").get<std::string>() == "cholmod");
  BOOST_TEST(sum.at("solver").at("amg_fallback_solve").get<long>() == 1);
  const auto sum_c = nlohmann::json::parse(read_text((d / "cholmod" / "summary.json").string()));
  BOOST_TEST(sum_c.at("solver").at("amg_fallback_solve").get<long>() == -1);
  fs::remove_all(d);
}
