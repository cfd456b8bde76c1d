// Fit time of `rheodda fit` for Burgers on synthetic Table 1 row 1 curves
// (tau 0.232; E1 26.87, E2 192.43, eta1 34807.72, eta2 2141.23; 200 h) with
// Gaussian noise of 2e-5 mm, on 1e3 and 1e5 points. Times are thread CPU
// time (the machine is shared; wall time counts other processes' turns) per
// fit_law() call, one core. Prints figures, asserts nothing.
// Sample run: build-NAME/bench/fit_bench
#include <fmt/format.h>

#include <algorithm>
#include <ctime>
#include <random>
#include <vector>

#include "rheodda/fit/fit.hpp"
#include "rheodda/laws/registry.hpp"

namespace {

using namespace rheodda;

double thread_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

fit::CreepData table1_row1(std::size_t points) {
  const laws::StagedHistory h({{0.0, 0.232}});
  const auto law = laws::LawRegistry::builtin().create(
      "burgers", {{"E1", 26.87}, {"E2", 192.43}, {"eta1", 34807.72}, {"eta2", 2141.23}});
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 2e-5);
  fit::CreepData d;
  d.source = fmt::format("table1-row1-{}", points);
  d.history = h;
  for (std::size_t j = 0; j < points; ++j) {
    const double t = 200.0 * static_cast<double>(j) / static_cast<double>(points - 1);
    d.t.push_back(t);
    d.displacement.push_back(*laws::exact_displacement(*law, h, t) + noise(rng));
    d.line.push_back(j + 2);
  }
  d.stages.push_back({0.0, 0.232, 0, points});
  return d;
}

}  // namespace

int main() {
  const auto& burgers = laws::LawRegistry::builtin().get("burgers");
  fmt::print("{:>8} {:>9} {:>11} {:>12} {:>12}\n", "points", "restarts", "iterations", "median [ms]",
             "min [ms]");
  for (const std::size_t n : {std::size_t{1000}, std::size_t{100000}}) {
    const auto data = table1_row1(n);
    for (const int restarts : {0, 4}) {
      fit::FitOptions opt;
      opt.restarts = restarts;
      const int reps = n <= 1000 ? 50 : 5;
      std::vector<double> ms;
      int iterations = 0;
      for (int r = 0; r < reps; ++r) {
        const double t0 = thread_ms();
        const auto res = fit::fit_law(burgers, data, opt);
        ms.push_back(thread_ms() - t0);
        iterations = res.iterations;
      }
      std::sort(ms.begin(), ms.end());
      fmt::print("{:>8} {:>9} {:>11} {:>12.3f} {:>12.3f}\n", n, restarts, iterations, ms[ms.size() / 2],
                 ms.front());
    }
  }
  return 0;
}
