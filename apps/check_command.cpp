// `rheodda check`: a scene validated and described without running it; with --refine,
// its step controls measured: the scene run at them and with each of them halved,
// level after level, as the parallel cases of a study (rheodda/study/refinement.hpp,
// docs/guide/choosing-step-controls.md "Checking a scene's step controls").
// Sample runs:
//   rheodda check examples/shear-creep-test.yaml
//   rheodda check examples/goodman-toppling-creep.yaml --refine -j 2
//   rheodda check examples/sliding-block.yaml --refine=5 --until 0.5 -o out/sliding-refine
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rheodda/scene/assemble.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/integrator_choice.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/study/refinement.hpp"

namespace rheodda::apps {
namespace {

volatile std::sig_atomic_t g_check_stop = 0;
extern "C" void on_check_stop(int signo) { g_check_stop = signo; }

struct CheckArgs {
  std::string scene;
  int levels = 0;  ///< --refine: levels of the refinement study (0: no refinement)
  std::string out;
  int jobs = 0;
  std::string until;  ///< --until: a time, bare in the scene's unit or with its own ("100 d")
  double tolerance = 0.05;
  std::vector<std::string> hold;
  bool quiet = false;  ///< --refine: no progress
};

void refine(const CheckArgs& args, const scene::Units& units) {
  study::RefinementOptions o;
  o.levels = args.levels;
  if (!args.until.empty()) {
    o.until = option_quantity("--until", args.until, "time", units);
    if (!(*o.until > 0.0))
      throw std::invalid_argument(fmt::format("--until {}: a time > 0", args.until));
  }
  o.tolerance = args.tolerance;
  o.hold = args.hold;
  const std::string out_dir =
      args.out.empty() ? (std::filesystem::path("out") / (std::filesystem::path(args.scene).stem().string() + "-refine")).string()
                       : args.out;
  std::filesystem::create_directories(out_dir);
  const std::string study_file = (std::filesystem::path(out_dir) / "refinement.yaml").string();
  const study::RefinementStudy r = study::refinement_study(args.scene, study_file, o);
  scene::write_file_atomic(study_file, r.study_text);

  study::StudyOptions opt;
  opt.out_dir = out_dir;
  opt.jobs = args.jobs;
  opt.progress = !args.quiet;
  opt.stop = &g_check_stop;
  on_stop_signals(on_check_stop);
  fmt::print("\nmeasuring the step controls: {} levels, each with every step control{} halved (the last costs "
             "about {} times a run); cases in {}/cases/\n",
             o.levels, o.hold.empty() ? std::string() : fmt::format(" but {}", fmt::join(o.hold, ", ")),
             1 << (o.levels - 1), out_dir);
  std::fflush(stdout);
  std::vector<study::CaseResult> results;
  try {
    results = study::run_study(r.study, opt);
  } catch (const study::SceneError&) {
    throw;
  } catch (const std::exception& e) {
    fmt::print(stderr, "rheodda: error: {}\n", e.what());
    throw CLI::RuntimeError(kExitFailure);
  }
  if (g_check_stop) {
    fmt::print("stopped: the refinement is incomplete; resume its cases with: rheodda study {} -o {} --resume\n",
               study_file, out_dir);
    throw CLI::RuntimeError(128 + static_cast<int>(g_check_stop));
  }
  const study::RefinementAssessment as = study::assess_refinement(r, results, o);
  const std::string report = study::refinement_report(r, results, as, o);
  scene::write_file_atomic((std::filesystem::path(out_dir) / "refinement.txt").string(), report);
  scene::write_file_atomic((std::filesystem::path(out_dir) / "refinement.json").string(),
                           study::refinement_json(r, results, as, o));
  fmt::print("{}  the table: {}/refinement.txt (and .json); the levels' histories: {}/study.png; rerun: rheodda "
             "study {}\n",
             report, out_dir, out_dir, study_file);
  switch (as.verdict) {
    case study::RefinementVerdict::fine: return;
    case study::RefinementVerdict::incomplete: throw CLI::RuntimeError(kExitFailure);
    default:
      fmt::print(stderr, "rheodda: warning: {}\n", as.message);
      throw CLI::RuntimeError(kExitStepControls);
  }
}

/// A block's name in the scene, or its index where the scene did not list it (a rock mass's).
std::string block_name(const scene::SceneDescription& s, int b) {
  const auto k = static_cast<std::size_t>(b);
  return k < s.blocks.size() ? "'" + s.blocks[k].name + "'" : fmt::format("{}", b);
}

/// How the blocks' own cycles spread (Engine::block_cycles): a few small blocks setting the
/// scene's cycle far below the others' are what rock_mass.sliver_area and stage_cycles are for
/// (docs/reference/explicit-step.md, "Small blocks").
std::string block_cycles_text(const scene::SceneDescription& s, core::Engine& e) {
  const std::vector<double> h = e.block_cycles();
  std::vector<int> order;
  for (std::size_t k = 0; k < h.size(); ++k)
    if (std::isfinite(h[k])) order.push_back(static_cast<int>(k));
  if (order.empty()) return {};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return h[a] < h[b] || (h[a] == h[b] && a < b); });
  // Nearest rank: the value below which the share q of the blocks' cycles lies.
  auto rank = [&](double q) {
    return h[order[static_cast<std::size_t>(std::floor(q * static_cast<double>(order.size() - 1)))]];
  };
  std::string shortest;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, order.size()); ++i)
    shortest += fmt::format("{}{} ({:.3g} {}, area {:.3g} {}^2)", i ? ", " : "", block_name(s, order[i]),
                            h[order[i]], s.units.time, e.area(order[i]), s.units.length);
  return fmt::format("  the blocks' cycles ({} blocks): smallest {:.3g} {}, 1st percentile {:.3g}, median {:.3g}; "
                     "the shortest: {}\n",
                     order.size(), rank(0.0), s.units.time, rank(0.01), rank(0.5), shortest);
}

/// The explicit step's cycle on the scene's initial state (docs/reference/explicit-step.md):
/// its length, the block that sets it, the cycles a simulated time unit costs.
std::string explicit_cycle_text(const scene::SceneDescription& s) {
  const std::string& tu = s.units.time;
  std::string statics;
  if (s.analysis.static_force_ratio > 0.0)
    statics = fmt::format("  integrator explicit: static steps by cycles from rest to an unbalanced-force ratio of "
                          "{:g} (at most {} cycles, local damping {:g}; docs/reference/explicit-step.md, \"Static "
                          "steps by cycles\")\n",
                          s.analysis.static_force_ratio, s.analysis.static_max_cycles, s.analysis.static_local_damping);
  if (!s.analysis.has_dynamic_steps()) return statics;
  const scene::BuiltScene built = scene::build_scene(s);
  scene::AssembledScene a = scene::assemble_scene(s, built);
  const core::Engine::StableCycle c = a.engine->stable_cycle();
  if (c.block < 0)
    return statics + fmt::format("  integrator explicit: nothing stiff holds a block at the start; its cycles are "
                                 "set once contacts close\n");
  // The dynamic steps are the analysis's own in a dynamic analysis, the stages' in a static one.
  const bool staged = s.analysis.type != scene::AnalysisType::dynamic_analysis && s.analysis.has_settle();
  const double dt = staged ? s.analysis.settle.dt : s.analysis.dt;
  const auto cycles = static_cast<long long>(std::ceil(dt / c.cycle - 1e-9));
  std::string text = fmt::format(
      "  integrator explicit: dynamic steps in cycles of {:.3g} {} (explicit_safety {:g} of the stable cycle at the "
      "start, set by block {}), about {:.3g} cycles per simulated {}; its {}steps of dt {:g} {} take {} cycles each",
      c.cycle, tu, s.analysis.explicit_safety, block_name(s, c.block), 1.0 / c.cycle, tu,
      staged ? "dynamic stages' " : "", dt, tu, cycles);
  if (staged && s.analysis.stage_cycles > 0 && cycles > s.analysis.stage_cycles)
    text += fmt::format(", {} with the blocks' masses scaled (stage_cycles)", s.analysis.stage_cycles);
  return statics + text + " (docs/reference/explicit-step.md)\n" + block_cycles_text(s, *a.engine);
}

}  // namespace

void add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  auto* check = app.add_subcommand(
      "check", "Validate a scene file and print what will be modelled, without running it; with --refine, "
               "measure whether its step controls are fine enough");
  check->add_option("SCENE", args->scene, "Scene file (YAML, docs/reference/scene-format.md)")->required();
  auto* refine_flag = check->add_flag(
      "--refine{4}", args->levels,
      "Run the scene at its step controls and with them halved, LEVELS levels in all (default 4), and say whether "
      "its answer is within --tolerance of the finest level and converges (docs/guide/choosing-step-controls.md); exit 3 when not");
  refine_flag->type_name("LEVELS");
  check->add_option("-o,--out", args->out, "--refine: output directory (default out/<scene name>-refine)")
      ->type_name("OUTDIR")
      ->needs(refine_flag);
  check->add_option("-j,--jobs", args->jobs, "--refine: levels run at once; 0 (the default): the hardware threads")
      ->check(CLI::NonNegativeNumber)
      ->needs(refine_flag);
  check->add_option("--until", args->until,
                    "--refine: run each level to this time (the scene's time unit, or with a unit: \"100 d\") "
                    "instead of the scene's duration")
      ->type_name("TIME")
      ->needs(refine_flag);
  check->add_option("--tolerance", args->tolerance,
                    "--refine: largest relative difference allowed between the scene's own level and the finest "
                    "(default 0.05)")
      ->needs(refine_flag);
  check->add_option("--hold", args->hold,
                    "--refine: step controls kept at the scene's value on every level, by their key under "
                    "analysis (e.g. settle.dt,settle.max_displacement_ratio): controls whose own refinement is "
                    "shown converged elsewhere")
      ->delimiter(',')
      ->type_name("KEY,...")
      ->needs(refine_flag);
  add_quiet_flag(*check, args->quiet);
  check->callback([args] {
    require_readable(args->scene);
    const scene::SceneDescription s = scene::load_scene(args->scene);
    fmt::print("{}", scene::describe_scene(s));
    const scene::IntegratorChoice choice = scene::choose_integrator(s);  // integrator_choice.hpp
    if (s.analysis.integrator == core::Integrator::automatic) fmt::print("  integrator {}\n", choice.reason);
    if (choice.integrator == core::Integrator::explicit_step) fmt::print("{}", explicit_cycle_text(s));
    fmt::print("scene OK\n");
    if (args->levels > 0)
      refine(*args, s.units);
    else
      fmt::print("step controls: not measured (rheodda check {} --refine: whether the answer is within 5 % of "
                 "that of finer controls)\n",
                 args->scene);
  });
}

}  // namespace rheodda::apps
