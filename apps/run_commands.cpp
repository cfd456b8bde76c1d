// `rheodda run`, `rheodda plot`: scenes from YAML files (`rheodda check`: check_command.cpp).
// Sample runs:
//   rheodda run examples/shear-creep-test.yaml -o out/shear-creep
//   rheodda plot out/shear-creep
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <csignal>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/run.hpp"

#include <omp.h>

namespace rheodda::apps {
namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop_signal(int signo) { g_stop = signo; }

struct RunArgs {
  std::string scene;
  std::string out;
  bool resume = false;
  bool quiet = false;  ///< no progress (docs/reference/cli.md, "Progress")
  int threads = 0;  ///< OpenMP threads of the explicit step's cycles; 0: OMP_NUM_THREADS or every core
};

void run_command(const RunArgs& args) {
  require_readable(args.scene);
  // The explicit step's cycles (docs/reference/explicit-step.md) give the same bits whatever the count.
  if (args.threads > 0) omp_set_num_threads(args.threads);
  const std::string text = scene::read_scene_text(args.scene);
  const scene::SceneDescription s = scene::parse_scene(text, args.scene);
  scene::RunOptions opt;
  opt.out_dir = args.out.empty()
                    ? (std::filesystem::path("out") / std::filesystem::path(args.scene).stem()).string()
                    : args.out;
  opt.resume = args.resume;
  opt.progress = !args.quiet;  // a redrawn line on a terminal, plain lines in a log
  opt.stop = &g_stop;
  // Stop between two steps on Ctrl-C or kill: files stay consistent, the run can be resumed.
  on_stop_signals(on_stop_signal);

  scene::RunResult r;
  try {
    r = scene::run_scene(s, text, opt);
  } catch (const scene::SceneError&) {
    throw;
  } catch (const std::invalid_argument&) {
    throw;  // bad arguments (e.g. --resume on another scene): exit 2
  } catch (const std::exception& e) {
    fmt::print(stderr, "rheodda: error: {}\n", e.what());
    throw CLI::RuntimeError(1);
  }
  for (const auto& w : r.warnings) fmt::print(stderr, "rheodda: warning: {}\n", w);
  const char* status = r.status == scene::RunStatus::completed ? "completed" : "interrupted";
  fmt::print("{}: {} at t = {:g} of {:g} {}: {} steps ({} cuts of dt){}, {} frames, largest penetration {:g} {}, "
             "wall time {:.2f} s\n  outputs in {}/ (history.csv, contacts.csv, blocks.pvd, summary.json)\n",
             s.title, status, r.time, s.analysis.duration, s.units.time, r.steps, r.cuts,
             r.resumed_from_step >= 0
                 ? fmt::format(", resumed from step {} ({} computed now)", r.resumed_from_step, r.steps_computed)
                 : "",
             r.frames, r.max_penetration, s.units.length, r.wall_seconds, opt.out_dir);
  for (const auto& c : r.creep)
    fmt::print("  creep on joint set {}: {} contacts, {:g} {} of contact-time{}\n", c.joint_set, c.contacts,
               c.contact_time, s.units.time,
               c.failures > 0 ? fmt::format("; {} contacts failed (damage 1), the first at t = {:g} {}", c.failures,
                                            c.first_failure_time, s.units.time)
                              : std::string());
  if (const auto& cs = r.mechanism.collapse_stages; !cs.empty())
    fmt::print("  collapse stages (docs/reference/engine.md, \"Collapse stages\"): {}, starting at t = {:.6g} {}\n", cs.size(),
               fmt::join(cs, ", "), s.units.time);
  if (!r.events.empty()) {
    int settling = 0, mechanisms = 0, at_rest = 0;
    double dissipated = 0.0;
    for (const auto& e : r.events) {
      (e.kind == core::StageKind::settling ? settling : mechanisms) += 1;
      at_rest += e.at_rest ? 1 : 0;
      dissipated += e.energy_dissipated;
    }
    fmt::print("  dynamic stages (events.csv; docs/reference/engine.md, \"Dynamic stages\"): {} settling, {} mechanism, {} "
               "ended at rest; {:.4g} {}*{} dissipated in them\n",
               settling, mechanisms, at_rest, dissipated, s.units.force, s.units.length);
  }
  if (r.status == scene::RunStatus::interrupted) {
    fmt::print("  resume with: rheodda run {} -o {} --resume\n", args.scene, opt.out_dir);
    throw CLI::RuntimeError(128 + (g_stop ? static_cast<int>(g_stop) : SIGINT));
  }
}

}  // namespace

void add_scene_commands(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  auto* run = app.add_subcommand("run", "Run a scene; outputs go to OUTDIR (docs/reference/outputs.md)");
  run->add_option("SCENE", args->scene, "Scene file (YAML, docs/reference/scene-format.md)")->required();
  run->add_option("-o,--out", args->out, "Output directory (default out/<scene name>)")->type_name("OUTDIR");
  run->add_flag("--resume", args->resume, "Continue an interrupted run from OUTDIR/checkpoint.json");
  add_quiet_flag(*run, args->quiet);
  run->add_option("--threads", args->threads,
                  "Threads of the explicit step's cycles (docs/reference/explicit-step.md); default "
                  "OMP_NUM_THREADS or every core. The results are the same whatever the number")
      ->check(CLI::NonNegativeNumber)
      ->type_name("N");
  run->callback([args] { run_command(*args); });

  auto plot = std::make_shared<scene::PlotOptions>();
  auto* p = app.add_subcommand("plot", "Draw the blocks and their contacts at chosen times, joint stress against strength, and the history curves (gnuplot)");
  p->add_option("OUTDIR", plot->out_dir, "Output directory of a run or a study, or a scene file (its blocks coloured by joint set)")->required();
  // The times as text: bare in the run's time unit, or with their own ("10 d"), converted
  // once the run's units are known (its summary.json).
  struct PlotTimes {
    std::vector<std::string> times;
    std::string from, to;
  };
  auto texts = std::make_shared<PlotTimes>();
  p->add_option("--times", texts->times,
                "Times to draw the blocks at, in the run's time unit or with their own (\"10 d\"); default: first, "
                "middle, last frame")
      ->delimiter(',');
  p->add_option("--format", plot->format, "png or svg")->check(CLI::IsMember({"png", "svg"}))->capture_default_str();
  p->add_option("--scale", plot->scale,
                "Displacement magnification of the block pictures (default: automatic, shown in the title)");
  p->add_option("--contact-column", plot->contact_column,
                "The contacts.csv column the contacts pictures colour the contacts by")
      ->check(CLI::IsMember(scene::contact_colour_columns()))
      ->capture_default_str();
  p->add_option("--from", texts->from, "Start of the time window: the history's axis, the default frames")->type_name("T");
  p->add_option("--to", texts->to, "End of the time window")->type_name("T");
  plot->warn = [](const std::string& w) { fmt::print(stderr, "rheodda: warning: {}\n", w); };
  p->callback([plot, texts] {
    if (!texts->times.empty() || !texts->from.empty() || !texts->to.empty()) {
      // The run's units (a folder without summary.json is refused by plot_run: bare numbers only).
      scene::Units u;
      const std::filesystem::path summary = std::filesystem::path(plot->out_dir) / "summary.json";
      if (std::filesystem::is_regular_file(summary)) {
        const auto units = nlohmann::json::parse(scene::read_file(summary.string())).at("units");
        u = {units.at("length"), units.at("force"), units.at("time")};
      }
      for (const auto& t : texts->times) plot->times.push_back(option_quantity("--times", t, "time", u));
      if (!texts->from.empty()) plot->from = option_quantity("--from", texts->from, "time", u);
      if (!texts->to.empty()) plot->to = option_quantity("--to", texts->to, "time", u);
    }
    std::vector<std::string> pictures;
    try {
      pictures = scene::plot_run(*plot);
    } catch (const std::invalid_argument&) {
      throw;  // not a run directory: exit 2
    } catch (const std::exception& e) {
      fmt::print(stderr, "rheodda: error: {}\n", e.what());  // gnuplot missing or failing, a file unreadable
      throw CLI::RuntimeError(kExitFailure);
    }
    for (const auto& f : pictures) fmt::print("{}\n", f);
  });
}

}  // namespace rheodda::apps
