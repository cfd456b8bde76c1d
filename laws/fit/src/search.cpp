// The search for the best minimum of a fit (search.hpp).
#include "search.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "varpro.hpp"

namespace rheodda::fit::detail {

namespace {

std::vector<double> logs(const std::vector<double>& v) {
  std::vector<double> l(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) l[k] = std::log(v[k]);
  return l;
}

}  // namespace

Search search_minimum(const laws::LawInfo& info, const CreepData& data, Solver& full,
                      const CurveFeatures& features, double dmax, const FitOptions& options,
                      const Constraints& constraints) {
  const Problem& pr = full.pr;
  const std::size_t n = pr.n, np = pr.np;
  const std::vector<double> base = pr.structure ? series_start(*pr.structure, np, features)
                                                : generic_start(info, features);
  // The exact re-solve after the polish matters where GSL cannot settle: on a
  // kink of the curve in the threshold (a Bingham element). Elsewhere GSL's
  // minimum is the exact linear solution already (step tolerance 1e-10).
  bool has_bingham = false;
  if (pr.structure)
    for (const auto& el : pr.structure->elements) has_bingham = has_bingham || el.kind == Kind::bingham;
  // (Not with constraints: the exact re-solve knows neither fixed values, bounds nor weights.)
  const bool refine = options.structured_search && has_bingham && !constraints.active;
  const bool structured_search = pr.structure && options.structured_search;

  Search sr;
  sr.floor = static_cast<double>(n) * 1e-20;
  const double floor = sr.floor;
  sr.best_x.resize(np);

  // 1. The starts of the variable-projection search (varpro.hpp), polished on all points.
  if (structured_search) {
    detail::VarProSettings vs;
    vs.per_decade = std::max(options.grid_per_decade, 1);
    for (auto& v : detail::varpro_starts(*pr.structure, np, data, 1.0 / dmax, vs)) {
      const auto o = full.polish(logs(v.values), sr.starts_total > 0 ? sr.best_rss : -1.0, floor, options, refine);
      sr.consider(o, sr.starts_total == 0);
      ++sr.starts_total;
      ++sr.structured;
      sr.rss_full.push_back(o.rss);
      if (std::isfinite(o.rss)) sr.structured_rss = std::min(sr.structured_rss, o.rss);
    }
  }
  // 2. The classic starts (the curve-derived one and `restarts` variations of
  // it): a reference. On more than kReferencePoints points they run on an even
  // subsample (every stride-th point of each stage, about kReferenceSample in
  // all), against the best minimum polished on that subsample; a start that
  // finds a lower one there is then polished on all points. (Why these sizes,
  // between a subsample that misses the reference's minimum and one that
  // costs the fit its speed: docs/notes/fitting.md, "Speed".)
  const int classic = 1 + std::max(options.restarts, 0);
  std::vector<std::vector<double>> classic_starts;
  // The user's initial values (ParameterSetting::value), the others from the curve: tried first.
  std::vector<double> given = base;
  bool any_given = false;
  for (std::size_t k = 0; k < np; ++k)
    if (constraints.initial[k] && !constraints.fixed[k]) {
      given[k] = *constraints.initial[k];
      any_given = true;
    }
  if (any_given) classic_starts.push_back(logs(given));
  for (int r = 0; r < classic; ++r)
    classic_starts.push_back(logs(r == 0 ? base : restart_start(base, pr.structure, r, features.f_max)));
  constexpr std::size_t kReferencePoints = 500, kReferenceSample = 200;
  if (sr.structured > 0 && std::isfinite(sr.best_rss) && n > kReferencePoints && !constraints.active) {
    const CreepData sub = subsample(data, kReferenceSample);
    Solver small(info, sub, pr.structure, 1.0 / dmax);
    const double floor_sub = static_cast<double>(sub.t.size()) * 1e-20;
    const double level = small.polish(sr.best_x, -1.0, floor_sub, options, refine).rss;
    for (const auto& start : classic_starts) {
      const auto o = small.polish(start, level, floor_sub, options, refine);
      ++sr.starts_total;
      if (std::abs(o.rss - level) <= 1e-6 * level + floor_sub) ++sr.agreeing_sample;
      else if (o.rss < level * (1.0 - 1e-6) - floor_sub) {
        const auto o2 = full.polish(o.position, -1.0, floor, options, refine);
        sr.rss_full.push_back(o2.rss);
        sr.reference_lower = sr.consider(o2, false) || sr.reference_lower;
      }
    }
  } else {
    for (const auto& start : classic_starts) {
      const auto o = full.polish(start, sr.starts_total > 0 ? sr.best_rss : -1.0, floor, options, refine);
      sr.rss_full.push_back(o.rss);
      const bool lower = sr.consider(o, sr.starts_total == 0);
      sr.reference_lower = sr.reference_lower || (lower && sr.structured > 0);
      ++sr.starts_total;
    }
  }
  if (!std::isfinite(sr.best_rss))
    throw FitError(info.name, fmt::format("law '{}': no start gave a finite fit", info.name));
  return sr;
}

}  // namespace rheodda::fit::detail
