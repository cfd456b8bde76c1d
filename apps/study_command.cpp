// `rheodda study`: a base scene and its variations run as parallel cases (docs/studies.md).
// Sample run:
//   rheodda study examples/studies/toppling-phi.yaml -o out/toppling-phi -j 2
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "commands.hpp"
#include "rheodda/study/study.hpp"

namespace rheodda::apps {
namespace {

struct StudyArgs {
  std::string file;
  std::string out;
  int jobs = 0;
  bool no_plot = false;
};

void study_command(const StudyArgs& args) {
  require_readable(args.file);
  const study::StudyDescription s = study::load_study(args.file);
  study::StudyOptions opt;
  opt.out_dir = args.out.empty() ? "out/" + std::filesystem::path(args.file).stem().string() : args.out;
  opt.jobs = args.jobs;
  opt.progress = true;
  opt.plot = !args.no_plot;
  std::vector<study::CaseResult> results;
  try {
    results = study::run_study(s, opt);
  } catch (const study::SceneError&) {
    throw;  // a bad study: exit 2
  } catch (const std::exception& e) {
    fmt::print(stderr, "rheodda: error: {}\n", e.what());
    throw CLI::RuntimeError(1);
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
  st->callback([args] { study_command(*args); });
}

}  // namespace rheodda::apps
