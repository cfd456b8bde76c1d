// Synthetic creep curves for the fit tests: the exact staged response of a
// registered law (laws::exact_displacement), optionally with Gaussian noise
// from a seeded generator.
#pragma once

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "rheodda/fit/creep_data.hpp"
#include "rheodda/laws/registry.hpp"

namespace rheodda::fit::test {

/// The seed's Table 1: shear stress tau [MPa] and Burgers parameters
/// E1, E2 [MPa/mm per unit area], eta1, eta2 [MPa*h/mm] of the four stress states.
struct Table1Row {
  double tau, E1, E2, eta1, eta2;
};
inline constexpr Table1Row kTable1[] = {
    {0.232, 26.87, 192.43, 34807.72, 2141.23},
    {0.424, 40.13, 249.33, 101760.29, 3236.41},
    {0.439, 29.45, 260.76, 52869.39, 3771.63},
    {0.512, 33.65, 305.53, 23051.02, 5736.91},
};

inline laws::ParameterValues burgers_values(const Table1Row& r) {
  return {{"E1", r.E1}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}};
}

/// Times 0, dt, 2 dt, ..., t_end plus every stage start.
inline std::vector<double> sample_times(double t_end, double dt,
                                        const laws::StagedHistory& history) {
  std::vector<double> t;
  for (int i = 0; i * dt <= t_end + 1e-9; ++i) t.push_back(i * dt);
  for (const auto& s : history.stages()) t.push_back(s.t);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

/// Builds CreepData as parse_creep_csv would, from the law's exact response
/// plus noise of standard deviation `noise` [length] (none if 0).
inline CreepData synthetic_curve(const std::string& law, const laws::ParameterValues& values,
                                 const laws::StagedHistory& history, const std::vector<double>& t,
                                 double noise = 0.0, unsigned seed = 1) {
  const auto model = laws::LawRegistry::builtin().create(law, values);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise > 0 ? noise : 1.0);
  CreepData data;
  data.source = "synthetic-" + law;
  data.history = history;
  data.time_column = "t";
  data.displacement_column = "displacement";
  for (std::size_t j = 0; j < t.size(); ++j) {
    data.t.push_back(t[j]);
    data.displacement.push_back(*laws::exact_displacement(*model, history, t[j]) +
                                (noise > 0 ? gauss(rng) : 0.0));
    data.line.push_back(j + 2);
  }
  const auto& hs = history.stages();
  std::size_t j = 0;
  for (std::size_t i = 0; i < hs.size(); ++i) {
    StageInfo s{hs[i].t, hs[i].value, j, 0};
    const double end = i + 1 < hs.size() ? hs[i + 1].t : 1e300;
    while (j < t.size() && t[j] < end) ++j;
    s.count = j - s.first;
    data.stages.push_back(s);
  }
  return data;
}

}  // namespace rheodda::fit::test
