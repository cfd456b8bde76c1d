// Resuming from the saved state (docs/reference/outputs.md, "Interrupting and resuming"):
// a run stopped at 90 % and resumed computes only the steps after its
// checkpoint and writes the files an uninterrupted run writes, byte for byte
// (a creeping run with adaptive steps and a damage law, a static run with
// dynamic settling and collapse stages, an amg run, a run stopped within an explicit step's
// cycles); a state file of another
// scene, a corrupt one, one of another version, and one that is not the file
// the checkpoint recorded are refused with the file named and nothing changed.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "run_support.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/run.hpp"

using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

json summary(const fs::path& out) { return json::parse(read_text((out / "summary.json").string())); }

/// summary.json without what belongs to the process that wrote it (its wall
/// time, where it resumed, the steps and solves it computed itself).
json run_summary(const fs::path& out) {
  json j = summary(out);
  for (const char* k : {"wall_seconds", "resumed_from_step", "steps_computed"}) j.erase(k);
  for (const char* k : {"solves", "cg_iterations", "analyses"}) j.at("solver").erase(k);
  return j;
}

/// Every file of the run folder but summary.json, checkpoint.json, the state
/// files and the lock: the outputs a user reads.
std::set<std::string> output_files(const fs::path& out) {
  std::set<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), out).string();
    if (rel == "summary.json" || rel == "checkpoint.json" || rel == ".rheodda.lock" ||
        e.path().extension() == ".state")
      continue;
    files.insert(rel);
  }
  return files;
}

/// The outputs of `split` are those of `whole`, byte for byte.
void same_outputs(const fs::path& whole, const fs::path& split) {
  const auto files = output_files(whole);
  BOOST_TEST(output_files(split) == files);
  for (const auto& f : files) BOOST_TEST(read_text((split / f).string()) == read_text((whole / f).string()), f);
  BOOST_TEST(run_summary(split) == run_summary(whole));
}

/// Stops `s` at 90 % of its `steps`, resumes it for one step (the cost of a
/// resume), then to the end; checks what each process computed and that the
/// outputs are those of the uninterrupted run in `whole`.
void stop_at_90_percent_and_resume(const scene::SceneDescription& s, const fs::path& whole, const fs::path& split) {
  const int steps = summary(whole).at("steps").get<int>();
  const long solves = summary(whole).at("solver").at("solves").get<long>();
  const int stop = steps * 9 / 10;
  BOOST_TEST_REQUIRE(stop > 10);
  const auto first = run(s, split, stop);
  BOOST_TEST_REQUIRE((first.status == scene::RunStatus::interrupted));
  BOOST_TEST(first.steps_computed == stop);

  // A resume at 90 % plus one step: one step computed, a small share of the solves.
  const auto one = run(s, split, stop + 1, true);
  BOOST_TEST_REQUIRE((one.status == scene::RunStatus::interrupted));
  BOOST_TEST(one.resumed_from_step == stop);
  BOOST_TEST(one.steps_computed == 1);
  BOOST_TEST(summary(split).at("steps_computed").get<int>() == 1);
  const long one_solves = summary(split).at("solver").at("solves").get<long>();
  BOOST_TEST(one_solves > 0);
  BOOST_TEST(20 * one_solves < solves, one_solves << " solves of the run's " << solves);  // < 5 %

  const auto rest = run(s, split, -1, true);
  BOOST_TEST_REQUIRE((rest.status == scene::RunStatus::completed));
  BOOST_TEST(rest.resumed_from_step == stop + 1);
  BOOST_TEST(rest.steps_computed == steps - stop - 1);
  BOOST_TEST(rest.steps == steps);
  same_outputs(whole, split);
}

/// The example `name` with `changes` (text replacements) applied, as a file in `dir`.
scene::SceneDescription variant(const std::string& name, const fs::path& dir,
                                const std::vector<std::pair<std::string, std::string>>& changes) {
  std::string text = read_text(source_path("examples/" + name));
  for (const auto& [from, to] : changes) {
    const auto at = text.find(from);
    BOOST_TEST_REQUIRE(at != std::string::npos, from);
    text.replace(at, from.size(), to);
  }
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return scene::load_scene(file.string());
}

/// The message of the std::invalid_argument `f` throws (fails the test if none is).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  BOOST_ERROR("no refusal");
  return "";
}

void replace_in_file(const fs::path& p, const std::string& from, const std::string& to) {
  std::string text = read_text(p.string());
  const auto at = text.find(from);
  BOOST_TEST_REQUIRE(at != std::string::npos, from);
  text.replace(at, from.size(), to);
  std::ofstream(p, std::ios::binary) << text;
}

fs::path state_file(const fs::path& out) {
  return out / json::parse(read_text((out / "checkpoint.json").string())).at("state").at("file").get<std::string>();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_resume)

BOOST_AUTO_TEST_CASE(a_creeping_slope_resumed_at_90_percent_computes_only_the_rest_and_writes_the_same_files) {
  // examples/creeping-slope-failure.yaml: a block on its joint under a
  // damage-burgers law, adaptive creep steps (creep_tolerance) stepping onto the
  // failure; stopped at 90 % of its steps, after the failure.
  const auto s = scene::load_scene(source_path("examples/creeping-slope-failure.yaml"));
  const fs::path whole = fresh_dir("resume-creep-whole"), split = fresh_dir("resume-creep-split");
  BOOST_TEST_REQUIRE((run(s, whole).status == scene::RunStatus::completed));
  BOOST_TEST_REQUIRE(summary(whole).at("creep").at("slope").at("failures").get<int>() > 0);
  stop_at_90_percent_and_resume(s, whole, split);
  fs::remove_all(whole);
  fs::remove_all(split);
}

BOOST_AUTO_TEST_CASE(a_static_slide_resumed_within_its_dynamic_stages_gives_the_same_events) {
  // The sliding block in static analysis with a dynamic settling stage and
  // collapse stages (as in run_test.cpp): stopped within the settling stage, and
  // at 90 %, within a collapse stage; events.csv and the stages in summary.json
  // as the uninterrupted run's.
  const fs::path dir = fresh_dir("resume-stages");
  const auto s = variant(
      "sliding-block.yaml", dir,
      {{"type: dynamic", "type: static"},
       {"duration: 1 ", "duration: 0.3 "},
       {"dt: 0.001 ", "dt: 0.01\n  settle: {type: dynamic, until: 0.01, dt: 0.001, collapse_dt: 0.002}\n  # "}});
  const fs::path whole = dir / "whole";
  BOOST_TEST_REQUIRE((run(s, whole).status == scene::RunStatus::completed));
  BOOST_TEST_REQUIRE(summary(whole).at("events").size() >= 2u);
  BOOST_TEST_REQUIRE(summary(whole).at("static_mechanism").at("collapse_stages").size() >= 1u);
  BOOST_TEST_REQUIRE(fs::exists(whole / "events.csv"));

  const fs::path settling = dir / "settling";  // stopped in the settling stage (10 steps of 0.001 s)
  BOOST_TEST_REQUIRE((run(s, settling, 5).status == scene::RunStatus::interrupted));
  const auto r = run(s, settling, -1, true);
  BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
  BOOST_TEST(r.steps_computed == r.steps - 5);
  same_outputs(whole, settling);

  stop_at_90_percent_and_resume(s, whole, dir / "late");
  fs::remove_all(dir);
}

BOOST_AUTO_TEST_CASE(a_run_stopped_within_an_explicit_steps_cycles_resumes_to_the_uninterrupted_files) {
  // A stop asked while an explicit step cycles (a signal, here the scripted stop_within_step)
  // abandons that step at its cycles' next look (core::Engine::set_stop_request): the run ends
  // interrupted at the step before, with its checkpoint there, and resumed it writes the files
  // of the run that was never stopped, byte for byte. The sliding block at 10 ms steps: 400
  // cycles each, looked at after 256.
  auto s = sliding(0.2, 0.05);
  s.analysis.integrator = core::Integrator::explicit_step;
  s.analysis.dt = 0.01;
  const fs::path dir = fresh_dir("resume-within-cycles");
  const fs::path whole = dir / "whole", split = dir / "split";
  const auto all = run(s, whole);
  BOOST_TEST_REQUIRE((all.status == scene::RunStatus::completed));
  BOOST_TEST_REQUIRE(all.steps > 12);

  scene::RunOptions o;
  o.out_dir = split.string();
  o.stop_within_step = 12;
  const auto first = scene::run_scene(s, read_text(s.file), o);
  BOOST_TEST_REQUIRE((first.status == scene::RunStatus::interrupted));
  BOOST_TEST(first.steps == 12);  // the 13th step was abandoned within its cycles
  BOOST_TEST(first.steps_computed == 12);
  BOOST_TEST(summary(split).at("status").get<std::string>() == "interrupted");
  BOOST_TEST(summary(split).at("steps").get<int>() == 12);

  const auto rest = run(s, split, -1, true);
  BOOST_TEST_REQUIRE((rest.status == scene::RunStatus::completed));
  BOOST_TEST(rest.resumed_from_step == 12);
  BOOST_TEST(rest.steps == all.steps);
  same_outputs(whole, split);
  fs::remove_all(dir);
}

BOOST_AUTO_TEST_CASE(an_amg_run_resumed_solves_on_as_the_uninterrupted_one_to_the_last_bit) {
  // A wall of 120 blocks under gravity solved by amg: its conjugate gradient
  // starts from the last solution and its multigrid keeps the aggregates of
  // earlier systems, so a resume must take both up to write the same digits.
  const std::string wall =
      "title: wall\n"
      "units: {length: m, force: N, time: s}\n"
      "analysis: {type: dynamic, duration: 0.03, dt: 0.001, output_interval: 0.01, gravity: [0, -9.81], "
      "solver: amg}\n"
      "materials: {rock: {density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}}\n"
      "joint_sets: {j: {friction_angle: 35}}\n"
      "blocks:\n"
      "  - {name: base, rectangle: {x: -1, y: -1, width: 14, height: 1}, fixed: true}\n"
      "  - {name: w, grid: {x: 0, y: 0, width: 1, height: 0.5, columns: 12, rows: 10}}\n"
      "measurement_points:\n"
      "  - {name: top, point: [5.5, 4.75], block: w.r10.c6}\n";
  const fs::path dir = fresh_dir("resume-amg");
  std::ofstream(dir / "wall.yaml") << wall;
  const auto s = scene::load_scene((dir / "wall.yaml").string());
  const fs::path whole = dir / "whole";
  BOOST_TEST_REQUIRE((run(s, whole).status == scene::RunStatus::completed));
  BOOST_TEST_REQUIRE(summary(whole).at("solver").at("used").get<std::string>() == "amg");
  stop_at_90_percent_and_resume(s, whole, dir / "split");
  fs::remove_all(dir);
}

BOOST_AUTO_TEST_CASE(a_state_file_of_another_scene_a_corrupt_one_or_one_of_another_version_is_refused) {
  const auto s = sliding(0.05, 0.01);
  const fs::path base = fresh_dir("resume-refusals");
  BOOST_TEST_REQUIRE((run(s, base / "run", 20).status == scene::RunStatus::interrupted));
  auto creep = scene::load_scene(source_path("examples/shear-creep-test.yaml"));
  creep.analysis.duration = 2.0;
  creep.analysis.output_interval = 1.0;
  BOOST_TEST_REQUIRE((run(creep, base / "other", 1).status == scene::RunStatus::interrupted));

  // Each case: a copy of the stopped run, one thing done to it, the refusal's
  // words; the message names the state file, and nothing in the folder changes.
  struct Case {
    const char* what;
    std::function<void(const fs::path& out)> spoil;
    std::string words;
  };
  const std::vector<Case> cases{
      {"another scene's state",
       [&](const fs::path& out) {
         fs::copy_file(state_file(base / "other"), state_file(out), fs::copy_options::overwrite_existing);
       },
       "holds the state of another scene"},
      {"a flipped byte",
       [](const fs::path& out) {
         std::string bytes = read_text(state_file(out).string());
         bytes[bytes.size() - 100] = static_cast<char>(bytes[bytes.size() - 100] ^ 0x01);
         std::ofstream(state_file(out), std::ios::binary) << bytes;
       },
       "is corrupt: its checksum does not match its contents"},
      {"cut short",
       [](const fs::path& out) { fs::resize_file(state_file(out), fs::file_size(state_file(out)) - 8); },
       "is corrupt: its header counts"},
      {"another format version",
       [](const fs::path& out) { replace_in_file(state_file(out), "{\"rheodda_state\":", "{\"rheodda_state\":99"); },
       "has state format 99"},
      {"another program version",
       [](const fs::path& out) {
         replace_in_file(state_file(out), "\"program\":\"rheodda ", "\"program\":\"rheodda 0.0.0-");
       },
       "was written by rheodda 0.0.0-"},
      {"not a state file",
       [](const fs::path& out) { std::ofstream(state_file(out), std::ios::binary) << "hello\n"; },
       "is not a rheodda state file"},
  };
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.what) {
      const fs::path out = base / "case";
      fs::remove_all(out);
      fs::copy(base / "run", out, fs::copy_options::recursive);
      c.spoil(out);
      const std::string history = read_text((out / "history.csv").string());
      const std::string m = refusal([&] { run(s, out, -1, true); });
      BOOST_TEST(m.find(c.words) != std::string::npos, m);
      BOOST_TEST(m.find(state_file(out).string()) != std::string::npos, m);
      BOOST_TEST(read_text((out / "history.csv").string()) == history);
    }
  }

  // Through the command: exit code 2 and the message.
  const fs::path out = base / "cli";
  fs::copy(base / "run", out, fs::copy_options::recursive);
  fs::resize_file(state_file(out), fs::file_size(state_file(out)) - 1);
  // (the scene text is the example's: its hash is the folder's, though the run was shortened in memory)
  const auto cli =
      run_rheodda("run " + source_path("examples/sliding-block.yaml") + " -o " + out.string() + " --resume");
  BOOST_TEST(cli.exit_code == 2, cli.output);
  BOOST_TEST(cli.output.find(state_file(out).string()) != std::string::npos, cli.output);
  fs::remove_all(base);
}

BOOST_AUTO_TEST_CASE(an_older_state_file_or_a_checkpoint_without_one_is_refused) {
  const auto s = sliding(0.05, 0.01);
  const fs::path out = fresh_dir("resume-older");
  auto states = [&] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(out)) n += e.path().extension() == ".state";
    return n;
  };
  BOOST_TEST_REQUIRE((run(s, out, 10).status == scene::RunStatus::interrupted));
  const std::string first_bytes = read_text(state_file(out).string());
  BOOST_TEST(states() == 1);  // each checkpoint's state under the other name, the one before removed
  BOOST_TEST_REQUIRE((run(s, out, 20, true).status == scene::RunStatus::interrupted));
  BOOST_TEST(states() == 1);
  // The first state put where the checkpoint expects the second: a valid state
  // file of this scene, but not the one the checkpoint recorded.
  const std::string second_bytes = read_text(state_file(out).string());
  std::ofstream(state_file(out), std::ios::binary) << first_bytes;
  const std::string m = refusal([&] { run(s, out, -1, true); });
  BOOST_TEST(m.find("is not the state file the checkpoint recorded") != std::string::npos, m);
  std::ofstream(state_file(out), std::ios::binary) << second_bytes;

  // A checkpoint.json from before state files (it lacks "state").
  auto ck = json::parse(read_text((out / "checkpoint.json").string()));
  ck.erase("state");
  std::ofstream(out / "checkpoint.json") << ck.dump(1);
  const std::string m2 = refusal([&] { run(s, out, -1, true); });
  BOOST_TEST(m2.find("was written by a rheodda older than") != std::string::npos, m2);
  BOOST_TEST(m2.find((out / "checkpoint.json").string()) != std::string::npos, m2);

  // A new run into the folder leaves no state of the old one behind.
  BOOST_TEST_REQUIRE((run(s, out, 5).status == scene::RunStatus::interrupted));
  BOOST_TEST(states() == 1);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_SUITE_END()
