// The user's settings of a fit (fit.hpp, FitOptions): fixed parameters, bounds,
// initial values and measurement sigma, checked against the law and each other
// and turned into the mapping GSL works through (gsl_solver.hpp). fit_law
// (fit.cpp) reads them first.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gsl_solver.hpp"
#include "rheodda/fit/fit.hpp"

namespace rheodda::fit::detail {

/// The settings as the fit uses them.
struct Constraints {
  bool active = false;              // any setting or sigma: GSL works through `mapping`
  std::optional<Mapping> mapping;   // the free parameters and their log bounds
  std::vector<char> fixed;          // per parameter: vary = false
  std::vector<std::string> expr;    // per parameter: the expression that gives it (lmfit's expr), or empty
  std::vector<std::optional<double>> initial;  // per parameter: the user's value
  std::vector<double> min, max;     // per parameter [its unit]
  std::vector<double> weight;       // 1/sigma per point; empty without sigma [1/length]
  std::size_t varying = 0;          // k
};

/// Every setting checked against the law and itself (fit.hpp, fit_law); FitError otherwise.
Constraints read_settings(const laws::LawInfo& info, const CreepData& data, const FitOptions& options);

}  // namespace rheodda::fit::detail
