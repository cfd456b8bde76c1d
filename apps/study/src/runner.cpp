// Running a study: one case per executor task (local_executor.cpp's child
// `rheodda run` processes, at most `jobs` at once, or MPI ranks); then study.csv,
// study.json (study_report.cpp) and the overlay plot (study_plots.cpp) (docs/guide/studies.md).
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

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
  while (done < results.size()) {
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
        ++next;
        continue;
      }
      try {
        exec->start({next, dir.string(), todo[next] == Todo::resume});
      } catch (const std::exception& e) {
        results[next].status = "failed";
        results[next].exit_code = -1;
        results[next].message = e.what();
        results[next].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
        ++done;
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
    if (options.progress)
      fmt::print(stderr, "[{}/{}] {}: {} ({:.1f} s, {} steps){}\n", done, results.size(), res.name, res.status,
                 res.wall_seconds, res.steps, res.message.empty() ? "" : ": " + res.message);
  }
  not_started(next);
  write_study_csv(study, results, out_dir / "study.csv");
  write_study_json(study, out_dir / "study.json");
  if (stopping) return results;
  if (options.plot) (void)plot_study_dir(out_dir.string());
  return results;
}

}  // namespace rheodda::study
