// Internal to rheodda_fit: what a fit can work on (fit_input.cpp): the law's
// parameters positive, more points than varying parameters, stages that cover
// them, a load and a displacement; the scale the residuals are divided by.
#pragma once

#include "fit_settings.hpp"
#include "rheodda/fit/creep_data.hpp"
#include "rheodda/laws/registry.hpp"

namespace rheodda::fit::detail {

/// The data's scale.
struct DataScale {
  double dmax = 0.0;  // largest |displacement|
  double mean = 0.0;  // mean displacement (for R^2)
  // residuals are divided by this: dmax, with sigma max|d/sigma|
  double scale = 1.0, inv_scale = 1.0;
};

/// Checks the input of a fit of `info` to `data` under the constraints `c` (throws
/// FitError naming the law) and gives its scale.
DataScale check_input(const laws::LawInfo& info, const CreepData& data, const Constraints& c);

}  // namespace rheodda::fit::detail
