// Rock masses from joint sets (docs/rockmass.md, docs/performance.md "Rock masses"):
//  1. generation: three joint sets (persistent bedding, two non-persistent sets)
//     cutting a 100 x 100 m square into about 1e3, 1e4, 1e5 blocks: wall time of
//     the trace generation and of the exact cut (target: 1e5 blocks in <= 10 s);
//  2. creep: examples/rockmass/jointed-slope.yaml with its joint spacings (and
//     trace lengths, gaps, sliver area) scaled to give about 1e3 (and, on
//     request, 1e4) blocks, run static for 100 days with its adaptive steps:
//     wall time, steps, cuts.
// Sample runs:
//   build/bench/rockmass_bench                       # generation, then creep at ~1e3 blocks
//   build/bench/rockmass_bench --creep 1000,10000 --max-wall 1200 --solver cholmod
//   build/bench/rockmass_bench --no-generation --example tunnel --creep 1000
//   build/bench/rockmass_bench --no-generation --scene bench/scenes/jointed-slope-cohesionless.yaml --creep 1000
//                                                    # any scene with a rock_mass, scaled the same way
// Prints figures; asserts nothing.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <regex>
#include <string>
#include <unistd.h>
#include <vector>

#include "rheodda/rockmass/cut.hpp"
#include "rheodda/rockmass/generate.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/run.hpp"

using namespace rheodda;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// The three sets at a characteristic spacing s [m].
std::vector<rockmass::JointSetGeneration> sets(double s) {
  rockmass::JointSetGeneration bedding, a, b;
  bedding.tag = 0, bedding.dip = 20, bedding.dips_right = false, bedding.spacing = s;
  bedding.spacing_distribution = rockmass::SpacingDistribution::normal, bedding.spacing_deviation = 0.2 * s;
  a.tag = 1, a.dip = 70, a.spacing = s, a.spacing_distribution = rockmass::SpacingDistribution::log_normal;
  a.spacing_deviation = 0.3 * s, a.trace_length = 4 * s, a.gap = s, a.dip_spread = 3;
  b.tag = 2, b.dip = 45, b.dips_right = false, b.spacing = 2 * s;
  b.spacing_distribution = rockmass::SpacingDistribution::exponential, b.trace_length = 3 * s, b.gap = 3 * s;
  return {bedding, a, b};
}

struct Generated {
  std::size_t traces = 0, blocks = 0;
  double generate_s = 0.0, cut_s = 0.0, area_error = 0.0;
  int extended = 0;
};

Generated generate(double s) {
  const rockmass::Region region{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {}};
  Generated g;
  auto t0 = Clock::now();
  std::vector<rockmass::Trace> traces;
  int index = 0;
  for (const auto& set : sets(s)) {
    const auto t = rockmass::generate_traces(set, {0, 0, 100, 100}, 2026, index++);
    traces.insert(traces.end(), t.begin(), t.end());
  }
  g.generate_s = seconds_since(t0);
  t0 = Clock::now();
  const auto r = rockmass::cut_blocks(region, traces, {0.01 * s * s});
  g.cut_s = seconds_since(t0);
  g.traces = traces.size();
  g.blocks = r.blocks.size();
  g.area_error = r.area_error;
  g.extended = r.extended_traces;
  return g;
}

volatile std::sig_atomic_t g_stop = 0;
void on_alarm(int) { g_stop = 1; }

/// The slope's scene text with every length of its joint generation times f.
std::string scaled_slope(const std::string& text, double f) {
  std::string out = text;
  for (const char* key : {"spacing", "spacing_deviation", "trace_length", "gap"}) {
    const std::regex re(std::string("\\b") + key + ": ([0-9.eE+-]+)");
    std::string next;
    auto it = std::sregex_iterator(out.begin(), out.end(), re);
    std::size_t at = 0;
    for (; it != std::sregex_iterator(); ++it) {
      next += out.substr(at, it->position() - at);
      next += fmt::format("{}: {:.6g}", key, std::stod((*it)[1]) * f);
      at = it->position() + it->length();
    }
    out = next + out.substr(at);
  }
  const std::regex sliver("sliver_area: ([0-9.eE+-]+)");
  std::smatch m;
  if (std::regex_search(out, m, sliver))
    out.replace(m.position(), m.length(), fmt::format("sliver_area: {:.6g}", std::stod(m[1]) * f * f));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> creep{1000};
  double max_wall = 900.0;
  bool generation = true;
  std::string solver;  // empty: the scene's (automatic)
  std::string example = "jointed-slope";
  std::string scene_path;  // --scene: overrides --example
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--creep" && i + 1 < argc) {
      creep.clear();
      std::string list = argv[++i];
      for (std::size_t p = 0; p < list.size();) {
        const std::size_t q = std::min(list.find(',', p), list.size());
        if (q > p) creep.push_back(std::stoi(list.substr(p, q - p)));
        p = q + 1;
      }
    } else if (a == "--max-wall" && i + 1 < argc) {
      max_wall = std::stod(argv[++i]);
    } else if (a == "--example" && i + 1 < argc) {
      example = argv[++i];
    } else if (a == "--scene" && i + 1 < argc) {
      scene_path = argv[++i];
    } else if (a == "--solver" && i + 1 < argc) {
      solver = argv[++i];
    } else if (a == "--no-generation") {
      generation = false;
    } else {
      fmt::print(stderr, "usage: rockmass_bench [--creep N,N...] [--max-wall SECONDS] [--solver automatic|cholmod|pcg|amg] [--example jointed-slope|tunnel] [--scene FILE] "
                           "[--no-generation]\n");
      return 2;
    }
  }

  if (generation) {
    fmt::print("generation: 100 x 100 m square, 3 joint sets (bedding persistent; two non-persistent), seed 2026\n");
    fmt::print("{:>8} {:>9} {:>8} {:>11} {:>9} {:>9} {:>10} {:>9}\n", "target", "spacing", "traces", "blocks",
               "gen [s]", "cut [s]", "area err", "extended");
    // Calibrated once: blocks ~ c / s^2.
    const Generated probe = generate(4.0);
    const double c = double(probe.blocks) * 16.0;
    for (int target : {1000, 10000, 100000}) {
      const double s = std::sqrt(c / target);
      const Generated g = generate(s);
      fmt::print("{:>8} {:>9.4f} {:>8} {:>11} {:>9.3f} {:>9.3f} {:>10.2g} {:>9}\n", target, s, g.traces, g.blocks,
                 g.generate_s, g.cut_s, g.area_error, g.extended);
      std::fflush(stdout);
    }
  }

  const std::string slope_file =
      scene_path.empty() ? std::string(RHEODDA_SOURCE_DIR) + "/examples/rockmass/" + example + ".yaml" : scene_path;
  if (!scene_path.empty()) example = std::filesystem::path(scene_path).stem().string();
  const std::string slope = scene::read_scene_text(slope_file);
  const std::size_t base_blocks = scene::parse_scene(slope, slope_file).rock_mass->block_count;
  std::signal(SIGALRM, on_alarm);
  for (int target : creep) {
    const double f = std::sqrt(double(base_blocks) / target);
    std::string text = scaled_slope(slope, f);
    if (!solver.empty()) text.replace(text.find("analysis:\n"), 10, "analysis:\n  solver: " + solver + "\n");
    auto t0 = Clock::now();
    const scene::SceneDescription s = scene::parse_scene(text, "jointed-slope-scaled.yaml");
    const double load_s = seconds_since(t0);
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("rockmass-bench-{}-{}", target, getpid());
    std::filesystem::remove_all(dir);
    scene::RunOptions o;
    o.out_dir = dir.string();
    o.stop = &g_stop;
    g_stop = 0;
    alarm(static_cast<unsigned>(max_wall));
    scene::RunResult r;
    try {
      r = scene::run_scene(s, text, o);
    } catch (const std::exception& e) {
      alarm(0);
      fmt::print("creep: {}, lengths x {:.3f}: {} blocks, solver {}: run failed: {}\n", example, f,
                 s.rock_mass->block_count, solver.empty() ? "of the scene" : solver, e.what());
      std::filesystem::remove_all(dir);
      continue;
    }
    alarm(0);
    fmt::print("creep: {}, lengths x {:.3f}: {} blocks, solver {} (scene loaded and cut in {:.2f} s); "
               "{} at t = {:g} of {:g} d: {} steps, {} cuts, {} redone, wall {:.1f} s{}\n",
               example, f, s.rock_mass->block_count, solver.empty() ? "of the scene" : solver, load_s, r.status == scene::RunStatus::completed ? "completed" : "stopped",
               r.time, s.analysis.duration, r.steps, r.cuts, r.redone, r.wall_seconds,
               r.status == scene::RunStatus::completed ? "" : fmt::format(" (stopped at --max-wall {:g} s)", max_wall));
    std::fflush(stdout);
    std::filesystem::remove_all(dir);
  }
  return 0;
}
