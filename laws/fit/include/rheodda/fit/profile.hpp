// Confidence intervals of a fit's parameters by profile likelihood
// (docs/guide/fitting.md, "Confidence intervals by profile likelihood"): for each
// varying parameter, the range of values where the minimum of chi^2 with the
// parameter held there (the others refitted) stays within the level's
// quantile of the best chi^2 — lmfit's conf_interval (Newville et al., lmfit
// documentation, "Calculation of confidence intervals"; Venzon & Moolgavkar,
// Appl. Statist. 37, 1988, 87-94, for profile-likelihood intervals).
#pragma once

#include <string>
#include <vector>

#include "rheodda/fit/fit.hpp"

namespace rheodda::fit {

/// One end pair of a parameter's interval at one level.
struct ProfileLevel {
  double sigma = 1.0;        ///< the level in standard deviations of a normal law
  double probability = 0.0;  ///< erf(sigma/sqrt 2): 0.6827 for 1, 0.9545 for 2
  double chi_square = 0.0;   ///< the chi^2 at the ends [as FitResult::chi_square]
  double lower = 0.0, upper = 0.0;  ///< the ends [the parameter's unit]
  /// false where chi^2 stays below the level up to the parameter's bound
  /// (the end is that bound) or beyond 1e6 times the value (0 or inf).
  bool lower_found = true, upper_found = true;
};

/// A parameter's profile intervals, one per level, in the order asked.
struct ProfileInterval {
  std::string name;
  double value = 0.0;  ///< the best fit's value
  std::vector<ProfileLevel> levels;
  int fits = 0;        ///< refits made
};

/// Profile intervals of `names` (default: every varying parameter; fixed,
/// derived ones are refused) of `best`, the fit_law result of (law, data,
/// options), at the levels `sigmas`. The level's chi^2: with
/// options.scale_covariance (standard errors from the residual spread, lmfit's
/// default) lmfit's F test, chi^2 = chi^2_best (1 + F^-1(P; 1, n - k)/(n - k));
/// with absolute sigma chi^2_best + chi2^-1(P; 1) (Wilks). Each end is a root of
/// chi^2_profile(v) - level in ln v, bracketed outward from the value and found
/// by Brent's method (GSL) to 1e-9 in ln v; each chi^2_profile(v) is a fit_law
/// with the parameter fixed at v and the others started from `best`.
std::vector<ProfileInterval> profile_intervals(const laws::LawInfo& law, const CreepData& data,
                                               const FitOptions& options, const FitResult& best,
                                               const std::vector<double>& sigmas,
                                               const std::vector<std::string>& names = {});

}  // namespace rheodda::fit
