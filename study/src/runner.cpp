// Running a study: one case per executor task (local_executor.cpp's child
// `rheodda run` processes, at most `jobs` at once, or MPI ranks); then study.csv,
// study.json (study_report.cpp) and the overlay plot (study_plots.cpp) (docs/guide/studies.md).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "rheodda/scene/progress.hpp"
#include "study_internal.hpp"

namespace rheodda::study {
namespace fs = std::filesystem;
using detail::read_text;
using detail::write_study_csv;
using detail::write_study_json;
namespace {

/// The last non-empty line of a log (the child's error message).
std::string last_line(const std::string& text) {
  std::istringstream in(text);
  std::string l, last;
  while (std::getline(in, l))
    if (!l.empty()) last = l;
  return last;
}

void collect(const StudyDescription& study, const fs::path& dir, CaseResult& r) {
  const fs::path summary = dir / "summary.json";
  std::string summary_status;
  if (fs::exists(summary)) {
    try {
      const auto j = nlohmann::json::parse(read_text(summary));
      r.steps = j.value("steps", 0);
      if (j.contains("static_mechanism") && j["static_mechanism"].is_object())
        r.inertia_share = j["static_mechanism"].value("inertia_share", 0.0);
      summary_status = j.value("status", "");
      if (j.contains("error") && j["error"].is_string()) r.message = j["error"].get<std::string>();
    } catch (const std::exception& e) {
      r.message = fmt::format("unreadable summary.json: {}", e.what());
    }
  }
  const bool ok = r.exit_code == 0 && summary_status == "completed";
  r.status = ok ? "completed" : "failed";
  if (summary_status == "interrupted") {
    r.status = "interrupted";
    r.message = "stopped with the study; `rheodda study ... --resume` continues it";
  }
  if (!ok && r.message.empty() && r.status != "interrupted") {
    const std::string l = last_line(read_text(dir / "log.txt"));
    if (r.exit_code < 0) r.message = l.empty() ? "killed by a signal" : "killed by a signal; " + l;
    else r.message = l.empty() ? fmt::format("exit code {}", r.exit_code) : l;
  }
  if (ok) r.message.clear();
  r.values.assign(study.outputs.size() * study.times.size(), std::nullopt);
  if (!fs::exists(dir / "history.csv")) return;
  for (std::size_t i = 0; i < study.outputs.size(); ++i) {
    try {
      const auto series = read_history_series((dir / "history.csv").string(), study.outputs[i]);
      for (std::size_t k = 0; k < study.times.size(); ++k)
        r.values[i * study.times.size() + k] = value_at(series, study.times[k]);
    } catch (const std::exception& e) {
      if (r.message.empty()) r.message = e.what();
    }
  }
}

/// The progress of a study (docs/reference/cli.md, "Progress"): the cases done,
/// running and waiting, and the time left from the mean wall time of the cases
/// finished in this session (the cases' own progress is in their log.txt).
class StudyProgress {
 public:
  using Clock = std::chrono::steady_clock;
  StudyProgress(bool on, std::size_t cases, std::size_t at_once)
      : display(on ? stderr : nullptr), cases_(cases), at_once_(at_once) {}
  void started(std::size_t i) { running_[i] = Clock::now(); }
  /// A case has ended: its line (when it ran in this session) and the counts.
  void ended(std::size_t i, const CaseResult& r, bool ran) {
    ++done_;
    failed_ += r.status != "completed";
    if (!ran) return;
    running_.erase(i);
    ++finished_;
    finished_wall_ += r.wall_seconds;
    display.note(fmt::format("[{}/{}] {}: {} ({:.1f} s, {} steps){}", done_, cases_, r.name, r.status,
                             r.wall_seconds, r.steps, r.message.empty() ? "" : ": " + r.message));
  }
  void update(std::size_t waiting, const char* how = nullptr) {
    if (how == nullptr && !display.due()) return;
    const bool term = display.terminal();
    const std::string sep = term ? "  " : ", ";
    std::string t = term ? "" : "rheodda study: ";
    if (how) t += std::string(how) + sep;
    t += fmt::format("{} of {} cases done", done_, cases_);
    if (failed_ > 0) t += fmt::format(" ({} failed)", failed_);
    t += fmt::format("{}{} running{}{} waiting{}wall {}", sep, running_.size(), sep, waiting, sep,
                     scene::duration_text(display.elapsed()));
    if (how == nullptr && done_ < cases_) {
      if (finished_ == 0) {
        t += sep + (term ? std::string("time left: after a case") : std::string("time left: known once a case has finished"));
      } else {
        // What is left of the running cases and the waiting ones at the mean case's wall time, `at_once` at a time.
        const double mean = finished_wall_ / static_cast<double>(finished_);
        double work = mean * static_cast<double>(waiting);
        for (const auto& [i, since] : running_)
          work += std::max(0.0, mean - std::chrono::duration<double>(Clock::now() - since).count());
        const double slots = static_cast<double>(std::max<std::size_t>(1, std::min(at_once_, running_.size() + waiting)));
        const std::string left = scene::duration_text(work / slots), per_case = scene::duration_text(mean);
        if (term)
          t += fmt::format("{}~{} left (mean case {}, {} at a time)", sep, left, per_case, at_once_);
        else
          t += fmt::format("{}time left about {} (from the mean wall time {} of the {} finished, {} at a time)", sep,
                           left, per_case, finished_ == 1 ? std::string("case") : fmt::format("{} cases", finished_),
                           at_once_);
      }
    }
    display.show(t, how != nullptr);
    if (how && std::string(how) != "start") display.finish();
  }
  scene::Progress display;

 private:
  std::size_t cases_, at_once_;
  std::size_t done_ = 0, failed_ = 0, finished_ = 0;
  double finished_wall_ = 0.0;  ///< wall time of the cases finished in this session [s]
  std::map<std::size_t, Clock::time_point> running_;
};

}  // namespace

std::vector<CaseResult> run_study(const StudyDescription& study, const StudyOptions& options) {
  auto stop_requested = [&] { return options.stop && *options.stop != 0; };
  // A bad study throws before anything runs; a stop while the cases are prepared
  // (20 000 of them take seconds) returns before anything is written.
  const std::vector<std::string> texts = prepare_cases(study, options.stop);
  std::vector<CaseResult> results(study.cases.size());
  auto not_started = [&](std::size_t from) {
    for (std::size_t i = from; i < results.size(); ++i) {
      results[i].name = study.cases[i].name;
      results[i].status = "not started";
      results[i].message = "the study was stopped before this case started; `rheodda study ... --resume` runs it";
      results[i].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
    }
  };
  if (stop_requested()) {
    not_started(0);
    return results;
  }
  const fs::path out_dir = options.out_dir;
  std::unique_ptr<CaseExecutor> own;
  CaseExecutor* exec = options.executor;
  if (exec == nullptr) {
    const int jobs = options.jobs > 0 ? options.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    own = local_executor(case_binary(options), static_cast<std::size_t>(jobs));
    exec = own.get();
  }

  // What each case needs: run, resume (an interrupted run of the same scene), or
  // nothing (a completed run of the same scene, under options.resume). "The same
  // scene" is the same scene text below the header comment, which names the study
  // and the base scene by the paths as typed: another spelling, another working
  // directory or a moved folder is the same case (the kept scene.yaml is not
  // rewritten, so `rheodda run --resume` finds the scene its checkpoint hashed).
  enum class Todo { run, resume, keep };
  std::vector<Todo> todo(study.cases.size(), Todo::run);
  for (std::size_t i = 0; i < study.cases.size(); ++i) {
    if (stop_requested()) {  // the folders of 20 000 cases take seconds too
      not_started(0);
      return results;
    }
    const fs::path dir = out_dir / "cases" / study.cases[i].name;
    results[i].name = study.cases[i].name;
    if (options.resume && fs::exists(dir / "scene.yaml") &&
        case_scene_body(read_text(dir / "scene.yaml")) == case_scene_body(texts[i])) {
      std::string status;
      try {
        status = nlohmann::json::parse(read_text(dir / "summary.json")).value("status", "");
      } catch (const std::exception&) {
      }
      if (status == "completed") todo[i] = Todo::keep;
      else if (fs::exists(dir / "checkpoint.json")) todo[i] = Todo::resume;
    }
    if (todo[i] != Todo::run) continue;
    fs::remove_all(dir);  // a case folder holds one run only
    fs::create_directories(dir);
    std::ofstream(dir / "scene.yaml", std::ios::binary) << texts[i];
  }

  std::size_t next = 0, done = 0;
  bool stopping = false;
  StudyProgress progress(options.progress, results.size(), exec->capacity());
  if (progress.display.on())
    progress.display.show(fmt::format("{}start, {} cases, {} at a time (each case's progress in its log.txt)",
                                      progress.display.terminal() ? "" : "rheodda study: ", results.size(),
                                      exec->capacity()),
                          true);
  while (done < results.size()) {
    progress.update(results.size() - next);
    if (stop_requested() && !stopping) {
      // Stop the running cases (each stops after its step, keeping a checkpoint);
      // start no more.
      stopping = true;
      exec->stop_all();
    }
    while (!stopping && next < results.size() && exec->running() < exec->capacity()) {
      const fs::path dir = out_dir / "cases" / results[next].name;
      if (todo[next] == Todo::keep) {
        results[next].exit_code = 0;
        collect(study, dir, results[next]);
        try {
          results[next].wall_seconds =
              nlohmann::json::parse(read_text(dir / "summary.json")).value("wall_seconds", 0.0);
        } catch (const std::exception&) {
        }
        ++done;
        progress.ended(next, results[next], false);
        ++next;
        continue;
      }
      try {
        exec->start({next, dir.string(), todo[next] == Todo::resume});
        progress.started(next);
      } catch (const std::exception& e) {
        results[next].status = "failed";
        results[next].exit_code = -1;
        results[next].message = e.what();
        results[next].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
        ++done;
        progress.ended(next, results[next], false);
      }
      ++next;
    }
    if (exec->running() == 0) {
      if (stopping || done == results.size()) break;
      continue;
    }
    const std::optional<CaseOutcome> o = exec->poll();
    if (!o) continue;  // nothing finished yet (a stop request is handled at the top of the loop)
    CaseResult& res = results[o->index];
    res.wall_seconds = o->wall_seconds;
    res.exit_code = o->exit_code;
    collect(study, out_dir / "cases" / res.name, res);
    const std::string killed = "killed by a signal";
    if (o->signal != 0 && res.message.rfind(killed, 0) == 0)
      res.message = fmt::format("killed by signal {} ({}){}", o->signal, strsignal(o->signal), res.message.substr(killed.size()));
    if (!o->error.empty()) res.message = o->error;
    ++done;
    progress.ended(o->index, res, true);
  }
  progress.update(results.size() - next, stopping ? "stopped" : "end");
  not_started(next);
  write_study_csv(study, results, out_dir / "study.csv");
  write_study_json(study, out_dir / "study.json");
  if (stopping) return results;
  if (options.plot) {
    const scene::ProgressPhase phase(progress.display, "rheodda study: drawing study.png");
    (void)plot_study_dir(out_dir.string());
  }
  return results;
}

}  // namespace rheodda::study
