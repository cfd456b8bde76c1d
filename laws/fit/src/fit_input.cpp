// The input of a fit (fit_input.hpp).
#include "fit_input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "rheodda/fit/fit.hpp"

namespace rheodda::fit::detail {

// The law must be fittable with positive parameters, the data hold more points
// than varying parameters, stages that cover them, a load and a displacement.
DataScale check_input(const laws::LawInfo& info, const CreepData& data, const Constraints& c) {
  const std::size_t n = data.t.size(), np = c.varying;
  for (const auto& spec : info.parameters)
    if (spec.min < 0.0)
      throw FitError(info.name, fmt::format("law '{}': parameter {} may be negative (range {}); fits "
                                            "work on positive parameters only",
                                            info.name, spec.name, spec.range_text()));
  if (n < np + 1)
    throw FitError(info.name,
                   fmt::format("{}: too few points for law '{}': {} {}parameters need at least {} "
                               "points, the data has {}",
                               data.source, info.name, np, np < info.parameters.size() ? "varying " : "", np + 1, n));
  // CreepData built in code (not by parse_creep_csv) must hold the same invariants.
  std::size_t covered = 0;
  for (const auto& s : data.stages) {
    if (s.count == 0 || s.first != covered)
      throw FitError(info.name, fmt::format("{}: stage at t = {:g} has no data points", data.source, s.t));
    covered += s.count;
  }
  if (covered != n || data.displacement.size() != n || data.stages.empty())
    throw FitError(info.name, fmt::format("{}: the stages do not cover the {} data points", data.source, n));
  bool loaded = false;
  for (const auto& s : data.stages) loaded = loaded || s.stress != 0.0;
  if (!loaded)
    throw FitError(info.name, fmt::format("{}: the applied stress is zero in every stage; nothing "
                                          "to fit", data.source));
  DataScale sc;
  for (double d : data.displacement) {
    sc.dmax = std::max(sc.dmax, std::abs(d));
    sc.mean += d / static_cast<double>(n);
  }
  if (sc.dmax == 0.0)
    throw FitError(info.name,
                   fmt::format("{}: the displacement is zero everywhere; nothing to fit", data.source));
  sc.scale = sc.dmax;
  if (!c.weight.empty()) {
    sc.scale = 0.0;
    for (std::size_t j = 0; j < n; ++j) sc.scale = std::max(sc.scale, std::abs(data.displacement[j] * c.weight[j]));
  }
  sc.inv_scale = 1.0 / sc.scale;
  return sc;
}

}  // namespace rheodda::fit::detail
