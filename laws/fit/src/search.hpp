// Internal to rheodda_fit: the search for the best minimum over the starts
// (search.cpp): the variable-projection starts (varpro.hpp) polished on all
// points, then the classic starts (starts.hpp) as a reference.
#pragma once

#include <gsl/gsl_errno.h>

#include <cmath>
#include <limits>
#include <vector>

#include "fit_settings.hpp"
#include "gsl_solver.hpp"
#include "rheodda/fit/creep_data.hpp"
#include "rheodda/fit/fit.hpp"
#include "rheodda/laws/registry.hpp"
#include "starts.hpp"

namespace rheodda::fit::detail {

struct Search {
  // Sums of squares closer than `floor` are the same: a scaled residual of
  // 1e-10 rms (1e-10 of the largest displacement) is rounding, not fit.
  double floor = 0.0;
  std::vector<double> best_x;
  double best_rss = std::numeric_limits<double>::infinity();
  double structured_rss = std::numeric_limits<double>::infinity();
  int best_iter = 0, best_status = GSL_FAILURE, structured = 0, starts_total = 0, agreeing_sample = 0;
  std::vector<double> rss_full;  // final RSS of the starts run on all points
  bool reference_lower = false;  // a classic start found a lower minimum than the structured search

  bool consider(const Solver::Outcome& o, bool first) {
    // A later start must improve by more than rounding.
    if (std::isfinite(o.rss) && (first || o.rss < best_rss * (1.0 - 1e-9) - floor)) {
      best_rss = o.rss;
      best_iter = o.iterations;
      best_status = o.status;
      best_x = o.position;
      return true;
    }
    return false;
  }
};

// The starts of the variable-projection search, then the classic starts as a
// reference, each polished by `full` (all points) or on a subsample.
Search search_minimum(const laws::LawInfo& info, const CreepData& data, Solver& full,
                      const CurveFeatures& features, double dmax, const FitOptions& options,
                      const Constraints& constraints);

}  // namespace rheodda::fit::detail
