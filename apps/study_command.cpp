// `rheodda study`: a base scene and its variations run as parallel cases (docs/guide/studies.md).
// Sample runs:
//   rheodda study examples/studies/toppling-phi.yaml -o out/toppling-phi -j 2
//   mpirun -np 3 rheodda study examples/studies/toppling-phi.yaml -o out/toppling-phi   (2 worker ranks)
#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rheodda/study/study.hpp"
#ifdef RHEODDA_WITH_MPI
#include "mpi_study.hpp"
#endif

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
  bool quiet = false;
  std::string case_program;
};

/// Runs the study with `opt` (local processes, or MPI ranks through opt.executor) and reports.
void run_and_report(const StudyArgs& args, const study::StudyDescription& s, study::StudyOptions opt) {
  std::vector<study::CaseResult> results;
  const auto start = std::chrono::steady_clock::now();
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
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("{}: {} cases, {} completed, {} failed, wall time {:.3f} s\n  results in {}/study.csv{}, cases in {}/cases/\n",
             s.title, results.size(), results.size() - failed, failed, wall, opt.out_dir,
             opt.plot ? (s.parameters.empty() ? ", study.png" : ", study.png, study_sweep.png") : "", opt.out_dir);
  for (const auto& r : results)
    if (r.status != "completed") fmt::print("  {} {}: {}\n", r.status, r.name, r.message);
  if (failed > 0) throw CLI::RuntimeError(1);
}

study::StudyOptions options_of(const StudyArgs& args) {
  study::StudyOptions opt;
  opt.out_dir = args.out.empty() ? "out/" + std::filesystem::path(args.file).stem().string() : args.out;
  opt.jobs = args.jobs;
  opt.progress = !args.quiet;
  opt.plot = !args.no_plot;
  opt.resume = args.resume;
  opt.stop = &g_study_stop;
  if (!args.case_program.empty()) {
    if (::access(args.case_program.c_str(), X_OK) != 0)
      throw std::invalid_argument(fmt::format("--case-program {}: not an executable file: {}", args.case_program,
                                              std::strerror(errno)));
    opt.rheodda_binary = std::filesystem::absolute(args.case_program).string();
  }
  return opt;
}

#ifdef RHEODDA_WITH_MPI
/// Under mpirun/srun: rank 0 dispatches and gathers, the other ranks run cases.
void study_over_mpi(const StudyArgs& args) {
  on_stop_signals(on_study_stop);
  if (args.jobs != 0)
    throw std::invalid_argument(fmt::format(
        "-j {}: under MPI each worker rank runs one case at a time; start one rank per core "
        "(mpirun -np CORES+1: rank 0 only dispatches)", args.jobs));
  const study::StudyOptions base = options_of(args);
  study::mpi::run_over_ranks(study::case_binary(base), &g_study_stop, [&](study::CaseExecutor* ranks) {
    require_readable(args.file);
    const study::StudyDescription s = study::load_study(args.file);
    study::StudyOptions opt = base;
    opt.executor = ranks;
    if (ranks != nullptr)
      fmt::print(stderr, "rheodda study: {} cases over {} MPI worker ranks (rank 0 dispatches)\n", s.cases.size(),
                 ranks->capacity());
    run_and_report(args, s, opt);
  });
}
#endif

void study_command(const StudyArgs& args) {
#ifdef RHEODDA_WITH_MPI
  if (study::mpi::launched_by_mpi()) return study_over_mpi(args);
#endif
  require_readable(args.file);
  const study::StudyDescription s = study::load_study(args.file);
  const study::StudyOptions opt = options_of(args);
  // Ctrl-C or kill: the running cases stop after their step (with a checkpoint),
  // study.csv says where each case is, and --resume continues.
  on_stop_signals(on_study_stop);
  run_and_report(args, s, opt);
}

}  // namespace

void add_study_command(CLI::App& app) {
  auto args = std::make_shared<StudyArgs>();
  auto* st = app.add_subcommand("study", "Run a base scene's variations as parallel cases (docs/guide/studies.md)");
  st->add_option("STUDY", args->file, "Study file (YAML)")->required();
  st->add_option("-o,--out", args->out, "Output directory (default out/<study name>)")->type_name("OUTDIR");
  st->add_option("-j,--jobs", args->jobs, "Cases run at once; 0 (the default): the machine's hardware threads")
      ->check(CLI::NonNegativeNumber);
  st->add_flag("--no-plot", args->no_plot, "Do not draw study.png (nor the sweep pictures)");
  st->add_option("--case-program", args->case_program,
                 "Program run per case as `PROGRAM run SCENE -o DIR [--resume]` (default: this rheodda; "
                 "e.g. a wrapper script on a cluster, or a stand-in in benchmarks)")
      ->type_name("PROGRAM");
  st->add_flag("--resume", args->resume,
               "Continue a stopped study in OUTDIR: completed cases are kept, interrupted ones resumed");
  add_quiet_flag(*st, args->quiet);
  st->callback([args] { study_command(*args); });

  // `rheodda plot OUTDIR` of a study's folder (study.json) draws the study's pictures
  // (histories, outputs against the swept parameters) instead of a run's. The hook sits
  // on the plot command of apps/run_commands.cpp, registered before this one (main.cpp).
  CLI::App* plot = nullptr;
  for (CLI::App* sub : app.get_subcommands([](CLI::App* a) { return a->get_name() == "plot"; })) plot = sub;
  if (plot == nullptr) return;
  plot->parse_complete_callback([plot] {
    const std::string dir = plot->get_option("OUTDIR")->as<std::string>();
    if (!study::is_study_dir(dir)) return;  // a run's folder: the plot command's own callback
    for (const char* opt : {"--times", "--scale", "--format"})
      if (plot->get_option(opt)->count() > 0)
        throw std::invalid_argument(fmt::format("{} is a study's folder: {} applies to a run's pictures "
                                                "(plot a case: rheodda plot {}/cases/NAME)", dir, opt, dir));
    std::vector<std::string> pictures;
    try {
      pictures = study::plot_study_dir(dir);
    } catch (const std::invalid_argument&) {
      throw;  // not a study's record: exit 2
    } catch (const std::exception& e) {
      fmt::print(stderr, "rheodda: error: {}\n", e.what());
      throw CLI::RuntimeError(kExitFailure);
    }
    for (const auto& f : pictures) fmt::print("{}\n", f);
    throw CLI::RuntimeError(0);  // done: the run plot's callback does not run
  });
}

}  // namespace rheodda::apps
