// `rheodda study`: a base scene and its variations run as parallel cases (docs/studies.md).
// Sample run:
//   rheodda study examples/studies/toppling-phi.yaml -o out/toppling-phi -j 2
#include <fmt/format.h>

#include <csignal>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "rheodda/study/study.hpp"

namespace rheodda::apps {
namespace {

volatile std::sig_atomic_t g_study_stop = 0;
extern "C" void on_study_stop(int signo) { g_study_stop = signo; }

struct StudyArgs {
  std::string file;
  std::string out;
  int jobs = 0;
  bool no_plot = false;
  bool resume = false;
};

void study_command(const StudyArgs& args) {
  require_readable(args.file);
  const study::StudyDescription s = study::load_study(args.file);
  study::StudyOptions opt;
  opt.out_dir = args.out.empty() ? "out/" + std::filesystem::path(args.file).stem().string() : args.out;
  opt.jobs = args.jobs;
  opt.progress = true;
  opt.plot = !args.no_plot;
  opt.resume = args.resume;
  opt.stop = &g_study_stop;
  // Ctrl-C or kill: the running cases stop after their step (with a checkpoint),
  // study.csv says where each case is, and --resume continues.
  on_stop_signals(on_study_stop);
  std::vector<study::CaseResult> results;
  try {
    results = study::run_study(s, opt);
  } catch (const study::SceneError&) {
    throw;  // a bad study: exit 2
  } catch (const std::exception& e) {
    fmt::print(stderr, "rheodda: error: {}\n", e.what());
    throw CLI::RuntimeError(1);
  }
  if (g_study_stop) {
    int completed = 0;
    for (const auto& r : results) completed += r.status == "completed";
    fmt::print("{}: stopped with {} of {} cases completed; study.csv says where each case is\n"
               "  resume with: rheodda study {} -o {} --resume\n",
               s.title, completed, results.size(), args.file, opt.out_dir);
    throw CLI::RuntimeError(128 + static_cast<int>(g_study_stop));
  }
  int failed = 0;
  for (const auto& r : results) failed += r.status != "completed";
  fmt::print("{}: {} cases, {} completed, {} failed\n  results in {}/study.csv{}, cases in {}/cases/\n", s.title,
             results.size(), results.size() - failed, failed, opt.out_dir, opt.plot ? ", study.png" : "", opt.out_dir);
  if (failed > 0) throw CLI::RuntimeError(1);
}

}  // namespace

void add_study_command(CLI::App& app) {
  auto args = std::make_shared<StudyArgs>();
  auto* st = app.add_subcommand("study", "Run a base scene's variations as parallel cases (docs/studies.md)");
  st->add_option("STUDY", args->file, "Study file (YAML)")->required();
  st->add_option("-o,--out", args->out, "Output directory (default out/<study name>)")->type_name("OUTDIR");
  st->add_option("-j,--jobs", args->jobs, "Cases run at once (default: the machine's hardware threads)")
      ->check(CLI::NonNegativeNumber);
  st->add_flag("--no-plot", args->no_plot, "Do not draw study.png");
  st->add_flag("--resume", args->resume,
               "Continue a stopped study in OUTDIR: completed cases are kept, interrupted ones resumed");
  st->callback([args] { study_command(*args); });
}

}  // namespace rheodda::apps
