// DDA engine: assembly and solve time per step against the number of blocks.
//
// A generated wall of N rectangular bricks (1.0 m x 0.5 m, running bond) on a
// base block held by two fixed points; no contacts, static analysis under
// gravity (every brick independent). For N = 1e2, 1e3, 1e4, 1e5 it prints the
// mean assembly and solve time per step (first step, with CHOLMOD's symbolic
// analysis, reported apart) for CHOLMOD and PCG, and the growth exponent
// (slope of log time against log N).
//
// Run: build-*/bench/engine_bench            (about a minute in Release)
//      build-*/bench/engine_bench 1000 10000 (chosen N only)
//      build-*/bench/engine_bench --help      (options: --solver, --steps)
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rheodda/core/engine.hpp"

using namespace rheodda::core;

namespace {

Model wall(int n, SolverKind solver) {
  Model m;
  m.settings.dt = 1e-3;
  m.settings.dynamic_ratio = 0.0;
  m.settings.solver = solver;
  const int columns = std::max(1, static_cast<int>(std::sqrt(2.0 * n)));
  const double w = 1.0, h = 0.5;
  BlockDef base;
  base.vertices = {{-1.0, -1.0}, {columns * w + 1.0, -1.0}, {columns * w + 1.0, 0.0}, {-1.0, 0.0}};
  m.blocks.push_back(base);
  m.fixed_points.push_back({0, {-1.0, -1.0}});
  m.fixed_points.push_back({0, {columns * w + 1.0, -1.0}});
  for (int k = 0; k + 1 < n; ++k) {
    const int row = k / columns, col = k % columns;
    const double x = col * w + (row % 2 ? 0.5 * w : 0.0), y = row * h;
    BlockDef b;
    b.vertices = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
    m.blocks.push_back(b);
  }
  return m;
}

struct Timing {
  double first_assembly, first_solve, assembly, solve, build;
};

Timing measure(int n, SolverKind solver, int steps) {
  const auto t0 = std::chrono::steady_clock::now();
  Engine e(wall(n, solver));
  const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Timing t{0, 0, 0, 0, build};
  for (int k = 0; k <= steps; ++k) {
    const StepReport r = e.step();
    if (k == 0) {
      t.first_assembly = r.assembly_seconds;
      t.first_solve = r.solve_seconds;
    } else {
      t.assembly += r.assembly_seconds / steps;
      t.solve += r.solve_seconds / steps;
    }
  }
  return t;
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    mx += std::log(x[k]) / static_cast<double>(x.size());
    my += std::log(y[k]) / static_cast<double>(y.size());
  }
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (std::log(x[k]) - mx) * (std::log(y[k]) - my);
    sxx += (std::log(x[k]) - mx) * (std::log(x[k]) - mx);
  }
  return sxy / sxx;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "engine_bench: DDA engine assembly and solve time per step of a brick wall without contacts, "
      "against the number of blocks (docs/notes/performance.md)"};
  std::vector<int> sizes{100, 1000, 10000, 100000};
  std::string solver_name = "both";
  int steps_given = 0;
  app.add_option("BLOCKS", sizes, "Numbers of blocks N of the walls (default: 100 1000 10000 100000)")
      ->check(CLI::Range(2, 10000000));
  app.add_option("--solver", solver_name, "Solver to time")
      ->check(CLI::IsMember({"cholmod", "pcg", "both"}))
      ->capture_default_str();
  app.add_option("--steps", steps_given, "Timed steps per wall after the first (default: 2e6/N within 5..2000)")
      ->check(CLI::Range(1, 1000000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;  // 2: bad arguments, as the rheodda command
  }
  std::vector<SolverKind> solvers;
  if (solver_name != "pcg") solvers.push_back(SolverKind::cholmod);
  if (solver_name != "cholmod") solvers.push_back(SolverKind::pcg);
  for (SolverKind solver : solvers) {
    const char* name = solver == SolverKind::cholmod ? "cholmod" : "pcg";
    std::printf("solver %s\n", name);
    std::printf("%8s %10s %14s %14s %16s %16s\n", "blocks", "build_s", "assembly_ms", "solve_ms",
                "first_assembly_ms", "first_solve_ms");
    std::vector<double> ns, assembly, solve;
    for (int n : sizes) {
      const int steps = steps_given > 0 ? steps_given : std::clamp(2000000 / n, 5, 2000);
      const Timing t = measure(n, solver, steps);
      std::printf("%8d %10.3f %14.4f %14.4f %16.4f %16.4f\n", n, t.build, 1e3 * t.assembly,
                  1e3 * t.solve, 1e3 * t.first_assembly, 1e3 * t.first_solve);
      std::fflush(stdout);
      ns.push_back(n);
      assembly.push_back(t.assembly);
      solve.push_back(t.solve);
    }
    if (ns.size() >= 2)
      std::printf("growth exponent (time ~ N^p): assembly p = %.2f, solve p = %.2f\n\n",
                  slope(ns, assembly), slope(ns, solve));
  }
  return 0;
}
