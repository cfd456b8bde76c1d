// `rheodda run` (run.hpp): run_scene as a sequence of named steps over a Run
// (run_internal.hpp); each step lives in the file of its concern.
#include "rheodda/scene/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "rheodda/scene/assemble.hpp"
#include "law_choice.hpp"
#include "rheodda/scene/build.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {
namespace {

namespace fs = std::filesystem;

/// Refuses a --resume without a checkpoint, before anything is created or changed.
void check_resumable(const std::string& out, const std::string& checkpoint_path) {
  std::error_code ec;
  if (!fs::exists(checkpoint_path, ec))
    throw std::invalid_argument(fmt::format(
        "--resume: {} has no checkpoint.json{}: there is no run to continue; run without --resume", out,
        fs::exists(out, ec) ? "" : " (the folder does not exist)"));
}

/// The output folder and its frames/ folder; one that cannot be made is bad input (exit 2), as for `fit`.
void make_output_folder(const std::string& out) {
  std::error_code ec;
  fs::create_directories(fs::path(out) / "frames", ec);
  if (ec) throw std::invalid_argument(write_error((fs::path(out) / "frames").string(), ec.value()));
}

/// A new run invalidates an earlier run's checkpoint before it touches any
/// output: a later --resume must never continue files this run has emptied.
/// Then the earlier run's outputs go, frames and pictures included (a shorter run
/// would leave frames beyond its own, and `rheodda plot`'s pictures would show the
/// earlier results beside the new ones); the user's own files stay.
void forget_earlier_run(const std::string& out, const std::string& checkpoint_path) {
  std::error_code ec;
  if (fs::remove(checkpoint_path, ec)) sync_directory(out);
  if (ec) throw std::runtime_error(write_error(checkpoint_path, ec.value()));
  remove_run_outputs(out);
}

/// What the engine's step observer does after each accepted step: the totals,
/// the finite checks, the history row, the guards, the progress line, a stop.
void record_step(Run& run, const core::Engine& e, const core::StepReport& r) {
  const SceneDescription& s = run.s;
  const RunOptions& opt = run.opt;
  ++run.result.steps_computed;
  if (run.mode == Run::Mode::replay) {
    if (e.step_count() >= run.replay_target) throw StopAfterStep{};
    return;
  }
  run.run_totals.add(r, run.contacts.creep_counters());
  if (const std::string what = nonfinite_state(e, s); !what.empty())
    throw NonFinite(fmt::format("{} is not finite after step {} (t = {:g} {})", what, e.step_count(), e.time(),
                                s.units.time));
  note_settled(run);
  const std::string row = history_row(run, &r);
  // The numbers of the row: without the `stage` column's name (docs/reference/stages.md), the last.
  const std::string numbers = s.stages.empty() ? row : row.substr(0, row.rfind(',')) + '\n';
  if (const std::string col = nonfinite_column(run.history_header, numbers); !col.empty())
    throw NonFinite(fmt::format("history.csv column '{}' is not finite after step {} (t = {:g} {})", col,
                                e.step_count(), e.time(), s.units.time));
  if (history_row_due(run, r)) run.history.append(row);
  run.recorded_step = e.step_count();
  check_guards(run, e);
  run.progress.step(run, r);
  if ((opt.stop && *opt.stop) || (opt.stop_after_step >= 0 && e.step_count() >= opt.stop_after_step))
    throw StopAfterStep{};
}

/// Once settled (the first step outside a settling or collapse stage; at the end when the
/// run never left one): the contacts' shear stresses against what the laws were fitted to.
void check_law_stresses(Run& run, const core::Engine& e, bool at_end) {
  if (run.law_stresses_done || (!at_end && e.in_stage())) return;
  run.law_stresses_done = true;
  const std::string when = at_end           ? "at the end of the run"
                           : run.opt.resume ? "at the first step after resuming"
                           : run.a.has_settle()   ? "after settling"
                                            : "after the first step";
  for (auto& w : detail::law_stress_warnings(run.s, run.contacts.contacts(), e.time(), when))
    run.result.warnings.push_back(std::move(w));
}

/// The frames still due, each at its output time: the step that would pass it is
/// shortened to end on it, as the last step is to end on the duration
/// (Engine::run_until; the step after it takes up the step size the control had
/// reached, docs/reference/outputs.md "Output times"). A run resumed at an output time
/// whose frame was not written (stopped on that very step) writes it now.
void run_to_end(Run& run) {
  if (run.frames_done == 0) write_frame(run);
  for (std::size_t k = run.next_output(run.pvd.back().first); k < run.frame_times.size();
       k = run.next_output(run.pvd.back().first)) {
    run.engine.run_until(run.frame_times[k]);  // returns at once if the time is reached
    write_frame(run);
  }
}

/// A run that failed on `e`: keeps what can be kept (a second failure, e.g. a
/// full disk, must not hide the first) and throws the message.
[[noreturn]] void fail(Run& run, const std::exception& e) {
  std::string error = failure_text(run, e);
  try {
    // Only where the state is that of the outputs: not within a step (a
    // failure inside the engine can leave it there), nor within a frame.
    if (run.engine.step_count() == run.recorded_step && !run.frame_open) write_checkpoint(run);
  } catch (const std::exception&) {
  }
  try {
    write_summary(run, "failed", error);
  } catch (const std::exception& e2) {
    error += fmt::format(" (summary.json could not be updated either: {})", e2.what());
  }
  throw std::runtime_error(fmt::format("run {} at t = {:g} {} (step {}): {}",
                                       dynamic_cast<const GuardTripped*>(&e) ? "stopped" : "failed",
                                       run.engine.time(), run.s.units.time, run.engine.step_count(), error));
}

}  // namespace

Run::Run(const SceneDescription& scene, const RunOptions& options, RunResult& run_result,
         contact::ContactSystem& contact_system, core::Engine& run_engine, const std::string& scene_text,
         Clock::time_point start)
    : s(scene),
      a(scene.analysis),
      opt(options),
      result(run_result),
      contacts(contact_system),
      engine(run_engine),
      out(options.out_dir),
      scene_hash(fmt::format("{:016x}", fnv1a(scene_text.data(), scene_text.size()))),
      checkpoint_path((fs::path(options.out_dir) / "checkpoint.json").string()),
      wall_start(start),
      progress(options.progress ? options.progress_stream : nullptr),
      run_totals(scene.joint_sets.size(), scene.analysis.type == AnalysisType::static_analysis),
      recorded_step(run_engine.step_count()) {
  for (int b = 0; b < engine.block_count(); ++b) {
    const auto v = engine.vertices(b);
    initial.emplace_back(v.begin(), v.end());
  }
  frame_times = run_output_times(a);
  row_times = frame_times;
  for (const StageDescription& st : s.stages)
    if (st.start == StageStart::at) row_times.push_back(st.at);
  std::sort(row_times.begin(), row_times.end());
  note_rows_state();
  for (std::size_t j = 0; j < s.joint_sets.size(); ++j)
    if (s.joint_sets[j].record) recorded.push_back(static_cast<int>(j));
  history_header = make_history_header(s);
  model_size = scene::model_size(initial);
  inputs_text = scene_json_text(s);
  scene_text_json = nlohmann::ordered_json(scene_text).dump();
}

std::size_t index_after(const std::vector<double>& times, double t) {
  std::size_t k = 0;
  while (k < times.size() && times[k] <= t + 1e-12 * std::max(1.0, std::abs(times[k]))) ++k;
  return k;
}

std::size_t Run::next_output(double t) const { return index_after(frame_times, t); }

void Run::note_rows_state() {
  rows_reached = index_after(row_times, engine.time());
  events_seen = engine.events().size();
  failures_seen = 0;
  for (const contact::CreepCounters& c : contacts.creep_counters()) failures_seen += c.failures;
}

RunResult run_scene(const SceneDescription& s, const std::string& scene_text, const RunOptions& opt) {
  const auto wall_start = Clock::now();
  RunResult result;
  const std::string out = opt.out_dir;
  check_memory(s);
  BuiltScene built = build_scene(s);
  result.warnings = built.warnings;
  const AssembledScene assembled = assemble_scene(s, built);
  const std::string checkpoint_path = (fs::path(out) / "checkpoint.json").string();
  if (opt.resume) check_resumable(out, checkpoint_path);
  refuse_resume_with_bolts(s, opt);
  // Only now that the model is accepted: a refused scene leaves nothing behind.
  make_output_folder(out);
  const FolderLock lock(out);  // one run per folder at a time (held until this function returns)
  if (!opt.resume) forget_earlier_run(out, checkpoint_path);

  Run run(s, opt, result, *assembled.contacts, *assembled.engine, scene_text, wall_start);
  run.law_stresses_done = !detail::law_stresses_checked(s);
  run.engine.add_observer([&run](const core::Engine& e, const core::StepReport&) { check_law_stresses(run, e, false); });
  run.engine.add_observer([&run](const core::Engine& e, const core::StepReport& r) { record_step(run, e, r); });
  // Within a step's cycles (the explicit step's thousands): a signal, or the tests' scripted
  // stop; not while steps are run again to write a lost frame (resume_run), which record_step
  // does not stop either.
  run.engine.set_stop_request([&run] {
    const RunOptions& o = run.opt;
    return run.mode == Run::Mode::record &&
           ((o.stop && *o.stop) || (o.stop_within_step >= 0 && run.engine.step_count() >= o.stop_within_step));
  });
  if (!s.stages.empty()) {  // docs/reference/stages.md
    if (opt.resume)
      throw std::invalid_argument("--resume: a scene with stages cannot be resumed yet (docs/reference/stages.md); run it again");
    start_stages(run);
    run.engine.add_observer([&run](const core::Engine& e, const core::StepReport&) { watch_settling(run, e); });
  }
  if (opt.resume)
    resume_run(run);
  else
    create_csv_files(run);
  run.progress.start(run);
  bool stopped = false;
  try {
    if (s.stages.empty())
      run_to_end(run);
    else
      run_staged_to_end(run);
  } catch (const StopAfterStep&) {
    stopped = true;
  } catch (const core::StepInterrupted&) {  // within a step's cycles: the engine is at the step before
    stopped = true;
  } catch (const NonFinite& e) {
    // Nothing of the bad step was written; the last checkpoint (at the last frame)
    // stays the one to resume from.
    const std::string msg = fmt::format(
        "{}: the run stops with the outputs of the steps before it kept (a step, penalty or parameter at the "
        "limit of double precision? see docs/reference/outputs.md, \"Runs that stop\")",
        e.what());
    try {
      write_summary(run, "failed", msg);
    } catch (const std::exception&) {
    }
    throw std::runtime_error(msg);
  } catch (const std::exception& e) {
    fail(run, e);
  }
  if (stopped) {
    run.progress.end(run, "interrupted");
    write_checkpoint(run);
    write_summary(run, "interrupted", "");
    result.status = RunStatus::interrupted;
    return result;
  }
  run.progress.end(run, "completed");
  write_checkpoint(run);
  collect_totals(run);
  check_law_stresses(run, run.engine, true);
  add_end_warnings(run);
  write_summary(run, "completed", "");
  return result;
}

}  // namespace rheodda::scene
