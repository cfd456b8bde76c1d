// Internal to rheodda_fit: which parameters the data fix, with their standard
// errors and correlations, from the SVD of the Jacobian at the fit
// (identifiability.cpp; docs/guide/fitting.md, "Identifiability").
#pragma once

#include <gsl/gsl_matrix.h>

#include <string>
#include <vector>

#include "rheodda/fit/creep_data.hpp"
#include "rheodda/fit/fit.hpp"
#include "series_structure.hpp"

namespace rheodda::fit::detail {

// ---- Identifiability: what the data fix and what they do not ----------------
// A combination of parameters whose value the data may fix when its parts are
// not identifiable: value q and gradient dq/dln p.
struct Candidate {
  std::string expression, unit;
  double value = 0.0;
  std::vector<double> grad;
};

/// The combinations of parameters that a series law's curve can depend on when
/// single parameters drop out, at the fitted values `p`.
std::vector<Candidate> combination_candidates(const SeriesStructure& s,
                                              const std::vector<ParameterEstimate>& p,
                                              const CreepData& data);

/// Identifiability, standard errors (res.parameters), fixed combinations
/// (res.combinations), singular values and warnings from the SVD of `jac`, the
/// Jacobian of the scaled residuals at the fit (overwritten); `s` the residual
/// standard deviation; `cov` receives the covariance of the log parameters.
void identify(FitResult& res, gsl_matrix* jac, double s, const std::vector<Candidate>& candidates,
              const FitOptions& options, std::vector<double>& cov);

}  // namespace rheodda::fit::detail
