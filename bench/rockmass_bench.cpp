// Rock masses from joint sets (docs/guide/rockmass.md, docs/notes/performance.md "Rock masses"):
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
//   ... --halve          # every static step control halved (dt, dt_max, creep_tolerance,
//                        # max_displacement_ratio, collapse_dt; the dynamic stages' dt held):
//                        # the convergence check of docs/notes/performance.md, "Rock masses that run"
//   ... --write-scenes DIR --creep 1000 --max-wall 0   # only write the scaled scene files
//   ... --max-cpu 600    # stop each run after 600 s of CPU time (not wall time)
//   ... --duration 10    # the analysis's duration instead of the scene's (the convergence
//                        # check at a time both runs reach)
//   ... --example tunnel --rest-tolerance 1e-5   # its dynamic settling stage ended at rest
// Per run: simulated time reached, steps, cuts, wall and CPU seconds, the
// dynamic stages (events.csv) and the first measurement point's displacement.
// Prints figures; asserts nothing.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <filesystem>
#include <regex>
#include <string>
#include <sys/time.h>
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

/// The scene text with every static step control halved: the analysis's dt,
/// dt_max, creep_tolerance and max_displacement_ratio (keys of the analysis
/// block, two spaces in) and the collapse stages' collapse_dt; the dynamic
/// stages' own dt and max_displacement_ratio are held, as
/// `rheodda check --refine --hold settle.dt,settle.max_displacement_ratio`
/// does (docs/guide/choosing-step-controls.md).
std::string halved(const std::string& text) {
  std::string out = text;
  auto halve = [&](const std::regex& re) {
    std::string next;
    std::size_t at = 0;
    for (auto it = std::sregex_iterator(out.begin(), out.end(), re); it != std::sregex_iterator(); ++it) {
      next += out.substr(at, it->position() - at);
      next += fmt::format("{}{:.8g}", (*it)[1].str(), std::stod((*it)[2]) / 2.0);
      at = it->position() + it->length();
    }
    out = next + out.substr(at);
  };
  halve(std::regex("(\\n  (?:dt|dt_max|creep_tolerance|max_displacement_ratio): )([0-9.eE+-]+)"));
  halve(std::regex("(collapse_dt: )([0-9.eE+-]+)"));
  return out;
}

/// The last row of `dir`/history.csv: the first measurement point's
/// displacement magnitude [length] (NaN when the scene has none).
double first_point_displacement(const std::filesystem::path& dir) {
  std::ifstream in(dir / "history.csv");
  std::string line, header, last;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) header = line; else last = line;
  }
  auto split = [](const std::string& l) {
    std::vector<std::string> v;
    std::stringstream ss(l);
    for (std::string f; std::getline(ss, f, ',');) v.push_back(f);
    return v;
  };
  const auto h = split(header), r = split(last);
  for (std::size_t k = 0; k + 1 < h.size() && k + 1 < r.size(); ++k)
    if (h[k].size() > 2 && h[k].ends_with(".u") && h[k + 1].ends_with(".v"))
      return std::hypot(std::stod(r[k]), std::stod(r[k + 1]));
  return std::numeric_limits<double>::quiet_NaN();
}

/// Dynamic stages by kind from `dir`/events.csv: "settling 1, mechanism 3".
std::string stages(const std::filesystem::path& dir) {
  std::ifstream in(dir / "events.csv");
  std::string line;
  std::map<std::string, int> count;
  for (bool first = true; std::getline(in, line); first = false)
    if (!first && !line.empty()) ++count[line.substr(0, line.find(','))];
  std::string out;
  for (const auto& [kind, n] : count) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", kind, n);
  return out.empty() ? "none" : out;
}

double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> creep{1000};
  double max_wall = 900.0;
  double max_cpu = 0.0;    // --max-cpu: stop each run after this much CPU time instead [s]
  double duration = 0.0;   // --duration: the analysis's duration instead of the scene's [time]
  double rest = 0.0;       // --rest-tolerance: the dynamic settling stage ends at rest [-]
  bool generation = true;
  std::string solver;  // empty: the scene's (automatic)
  std::string example = "jointed-slope";
  std::string scene_path;  // --scene: overrides --example
  bool halve = false;      // --halve: every static step control halved
  std::string write_dir;   // --write-scenes: where the scaled scenes go
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
    } else if (a == "--max-cpu" && i + 1 < argc) {
      max_cpu = std::stod(argv[++i]);
    } else if (a == "--duration" && i + 1 < argc) {
      duration = std::stod(argv[++i]);
    } else if (a == "--rest-tolerance" && i + 1 < argc) {
      rest = std::stod(argv[++i]);
    } else if (a == "--example" && i + 1 < argc) {
      example = argv[++i];
    } else if (a == "--scene" && i + 1 < argc) {
      scene_path = argv[++i];
    } else if (a == "--solver" && i + 1 < argc) {
      solver = argv[++i];
    } else if (a == "--no-generation") {
      generation = false;
    } else if (a == "--halve") {
      halve = true;
    } else if (a == "--write-scenes" && i + 1 < argc) {
      write_dir = argv[++i];
    } else {
      fmt::print(stderr, "usage: rockmass_bench [--creep N,N...] [--max-wall SECONDS] [--solver automatic|cholmod|pcg|amg] [--example jointed-slope|tunnel] [--scene FILE] "
                           "[--no-generation] [--halve] [--write-scenes DIR] [--max-cpu SECONDS] [--duration T] [--rest-tolerance R]\n");
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
  std::signal(SIGPROF, on_alarm);
  // Each run is stopped after max_wall seconds of wall time, or with --max-cpu
  // after that much CPU time of this process (a loaded machine's figure).
  auto arm = [&](bool on) {
    if (max_cpu > 0.0) {
      itimerval t{};
      if (on) t.it_value.tv_sec = static_cast<time_t>(max_cpu);
      setitimer(ITIMER_PROF, &t, nullptr);
    } else {
      alarm(on ? static_cast<unsigned>(max_wall) : 0u);
    }
  };
  for (int target : creep) {
    const double f = std::sqrt(double(base_blocks) / target);
    std::string text = scaled_slope(slope, f);
    if (!solver.empty()) text.replace(text.find("analysis:\n"), 10, "analysis:\n  solver: " + solver + "\n");
    if (halve) text = halved(text);
    if (rest > 0.0) {
      // The scene's dynamic settling stage ends at rest, its `until` its longest
      // (docs/reference/engine.md, "Dynamic stages").
      const std::size_t at = text.find("settle: {");
      if (at == std::string::npos) {
        fmt::print(stderr, "rockmass_bench: --rest-tolerance: {} has no `settle: {{...}}` flow map\n", slope_file);
        return 2;
      }
      text.insert(at + 9, fmt::format("rest_tolerance: {:g}, ", rest));
    }
    if (duration > 0.0) {
      const std::regex d("\\n  duration: [0-9.eE+-]+");
      std::smatch m;
      if (std::regex_search(text, m, d))
        text.replace(static_cast<std::size_t>(m.position()), static_cast<std::size_t>(m.length()),
                     fmt::format("\n  duration: {:g}", duration));
    }
    if (!write_dir.empty()) {
      std::filesystem::create_directories(write_dir);
      const auto file = std::filesystem::path(write_dir) / fmt::format("{}-{}{}.yaml", example, target, halve ? "-halved" : "");
      std::ofstream(file) << fmt::format("# {} with its joint lengths x {:.4f} (rockmass_bench){}\n", example, f,
                                         halve ? ", every static step control halved" : "")
                          << text;
      fmt::print("wrote {}\n", file.string());
      if (max_wall <= 0.0) continue;
    }
    auto t0 = Clock::now();
    const scene::SceneDescription s = scene::parse_scene(text, "jointed-slope-scaled.yaml");
    const double load_s = seconds_since(t0);
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("rockmass-bench-{}-{}", target, getpid());
    std::filesystem::remove_all(dir);
    scene::RunOptions o;
    o.out_dir = dir.string();
    o.stop = &g_stop;
    g_stop = 0;
    arm(true);
    scene::RunResult r;
    const double cpu0 = cpu_seconds();
    try {
      r = scene::run_scene(s, text, o);
    } catch (const std::exception& e) {
      arm(false);
      fmt::print("creep: {}, lengths x {:.3f}: {} blocks, solver {}: run failed: {}\n", example, f,
                 s.rock_mass->block_count, solver.empty() ? "of the scene" : solver, e.what());
      std::filesystem::remove_all(dir);
      continue;
    }
    arm(false);
    fmt::print("creep: {}, lengths x {:.3f}: {} blocks, solver {} (scene loaded and cut in {:.2f} s); "
               "{} at t = {:g} of {:g} d: {} steps, {} cuts, {} redone, wall {:.1f} s, CPU {:.1f} s{}; "
               "dynamic stages: {}; first measurement point displaced {:.6g}\n",
               example + std::string(halve ? " (static controls halved)" : "") +
                   (rest > 0.0 ? fmt::format(" (settling stage ended at rest, rest_tolerance {:g})", rest) : ""),
               f, s.rock_mass->block_count,
               solver.empty() ? "of the scene" : solver, load_s,
               r.status == scene::RunStatus::completed ? "completed" : "stopped", r.time, s.analysis.duration, r.steps,
               r.cuts, r.redone, r.wall_seconds, cpu_seconds() - cpu0,
               r.status == scene::RunStatus::completed ? "" : (max_cpu > 0.0 ? fmt::format(" (stopped at --max-cpu {:g} s)", max_cpu)
                                                                 : fmt::format(" (stopped at --max-wall {:g} s)", max_wall)),
               stages(dir), first_point_displacement(dir));
    std::fflush(stdout);
    std::filesystem::remove_all(dir);
  }
  return 0;
}
