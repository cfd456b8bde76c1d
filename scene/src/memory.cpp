#include "rheodda/scene/memory.hpp"

#include "rheodda/core/solver.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace rheodda::scene {
namespace {

// Measured peak RSS of `rheodda run` (release build; docs/notes/performance.md,
// "Memory"): stacked walls of 1e4 and 1e5 blocks 140 MB and 1.29 GB with the amg
// solver (12.9 KB per block), a running-bond wall of 1e5 blocks with outputs
// 1.67 GB (16.7 KB per block), the 1e4 stacked wall with cholmod 274 MB (27 KB
// per block). The estimate takes the larger figures and lets the factor of the
// sparse Cholesky grow like log N beyond 1e4 blocks (nested-dissection fill of
// a planar graph, O(N log N); George, SIAM J. Numer. Anal. 10 (1973) 345-363).
constexpr double kBaseBytes = 20e6;           // program, libraries, scene [bytes]
constexpr double kPerBlockIterative = 17e3;   // amg and pcg [bytes per block]
constexpr double kPerBlockCholmod = 28e3;     // cholmod at 1e4 blocks [bytes per block]

std::optional<double> read_number(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return std::nullopt;
  try {
    return std::stod(text);
  } catch (...) {
    return std::nullopt;
  }
}

}  // namespace

MemoryEstimate estimate_memory(const SceneDescription& scene) {
  const double n = static_cast<double>(scene.blocks.size());
  const core::SolverKind solver =
      core::LinearSolver::resolve(scene.analysis.solver, static_cast<int>(scene.blocks.size()));
  MemoryEstimate e;
  e.solver = std::string(core::linear_solver_entry(solver).word);
  const double per_block = solver == core::SolverKind::cholmod
                               ? kPerBlockCholmod * std::max(1.0, std::log10(std::max(n, 1.0)) / 4.0)
                               : kPerBlockIterative;
  e.bytes = kBaseBytes + per_block * n;
  return e;
}

std::optional<double> available_memory() {
  std::optional<double> best;
  auto take = [&](double v) { best = best ? std::min(*best, v) : v; };
  {
    std::ifstream in("/proc/meminfo");
    std::string key, unit;
    double value = 0.0;
    while (in >> key >> value) {
      std::getline(in, unit);
      if (key == "MemAvailable:") {
        take(value * 1024.0);  // kB
        break;
      }
    }
  }
  if (auto max = read_number("/sys/fs/cgroup/memory.max")) {
    const double current = read_number("/sys/fs/cgroup/memory.current").value_or(0.0);
    take(std::max(*max - current, 0.0));
  }
  rlimit lim{};
  if (getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY)
    take(static_cast<double>(lim.rlim_cur));
  return best;
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.1f} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.0f} MB", bytes / 1e6);
  return fmt::format("{:.0f} kB", bytes / 1e3);
}

}  // namespace rheodda::scene
