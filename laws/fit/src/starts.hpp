// Internal to rheodda_fit: the classic starting values of a fit, derived from
// the curve itself (starts.cpp); the variable-projection starts are varpro.hpp's.
#pragma once

#include <optional>
#include <vector>

#include "rheodda/fit/creep_data.hpp"
#include "rheodda/laws/registry.hpp"
#include "series_structure.hpp"

namespace rheodda::fit::detail {

// ---- Starting values from the curve itself ----------------------------------
struct CurveFeatures {
  double df = 0.0;     // stress step of the analysed stage [stress]
  double c0 = 0.0;     // compliance at the first point (instantaneous jump) [length/stress]
  double slope = 0.0;  // late compliance rate [length/(stress*time)]
  double intercept = 0.0;  // late line extrapolated to the stage start [length/stress]
  double c_last = 0.0, c_max = 0.0;
  double duration = 0.0;   // of the stage [time]
  double t63 = 0.0;        // time to 63% of the transient [time]
  double f_max = 0.0;      // largest |stress| [stress]
};

/// The features of the first stage that changes the stress (with enough points).
CurveFeatures analyse_curve(const CreepData& data);

/// Start derived from the curve for a series law (parameters in registry order).
std::vector<double> series_start(const SeriesStructure& s, std::size_t np, const CurveFeatures& c);

/// Without a series structure: a start from each parameter's dimension.
std::vector<double> generic_start(const laws::LawInfo& info, const CurveFeatures& c);

/// Restart r >= 1: a deterministic variation of `base`.
std::vector<double> restart_start(const std::vector<double>& base, const std::optional<SeriesStructure>& s,
                                  int r, double f_max);

}  // namespace rheodda::fit::detail
