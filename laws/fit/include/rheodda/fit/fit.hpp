// Fitting registered laws to creep curves by nonlinear least squares (GSL
// gsl_multifit_nlinear, trust-region Levenberg-Marquardt), and ranking the
// laws by information criteria. See docs/guide/fitting.md.
//
// What is minimized: RSS = sum_i (d_model(t_i) - d_i)^2 over every point of
// every stage at once, where d_model is the exact response of the law to the
// staged stress history: Boltzmann superposition d(t) = sum dF_i J(t - t_i)
// for linear laws (the seed's eqs. 4-6), plus the exact Bingham integral for
// Nishihara (laws::exact_displacement). Parameters are fitted as their
// logarithms, so they stay positive.
//
// How the minimum is found: a variable-projection search (Golub & Pereyra
// 1973, 2003) over a log-spaced grid of retardation times, the compliances and
// the Nishihara threshold solved exactly at each node, gives the starts; GSL
// polishes them on the full parameter set; the classic multi-start search
// (FitOptions::restarts) runs as a reference. Identifiability comes from the
// singular value decomposition of the Jacobian (docs/guide/fitting.md).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "rheodda/fit/creep_data.hpp"
#include "rheodda/laws/registry.hpp"

namespace rheodda::fit {

/// A law the data cannot constrain, or a law that cannot be fitted at all.
class FitError : public std::runtime_error {
 public:
  FitError(std::string law, const std::string& message)
      : std::runtime_error(message), law_(std::move(law)) {}
  const std::string& law() const { return law_; }

 private:
  std::string law_;
};

/// Knobs of a fit; the defaults are what `rheodda fit` uses.
struct FitOptions {
  int restarts = 4;               ///< extra starts besides the one derived from the curve
  int max_iterations = 500;       ///< per start
  double correlation_limit = 0.99;      ///< |corr| above this: warning
  double relative_error_limit = 1.0;    ///< std. error / value above this: warning
  double retardation_factor = 3.0;      ///< test shorter than this * eta/E: warning
  /// Starts from the variable-projection grid search (docs/guide/fitting.md, "How the
  /// minimum is found"); false: only the classic multi-start search.
  bool structured_search = true;
  int grid_per_decade = 10;  ///< grid nodes per decade of retardation time
  /// A singular value of the Jacobian below this fraction of the largest: the
  /// curve does not depend on that direction of the (log) parameters.
  double null_tolerance = 1e-7;
};

/// One fitted parameter.
struct ParameterEstimate {
  std::string name;  ///< registry name, e.g. "eta1"
  std::string unit;  ///< registry dimension, e.g. "stress*time/length"
  double value = 0.0;
  double std_error = 0.0;  ///< delta method from the log-space covariance; 0 if not identifiable
  /// false when the parameter has a significant weight in a direction of the
  /// (log) parameters that the data do not fix (docs/guide/fitting.md, "Identifiability")
  bool identifiable = true;
  std::string reason;  ///< why it is not identifiable; empty if it is
};

/// A combination of parameters that the data fix although some of its parts
/// are not identifiable, e.g. (F - Fs)/eta3 of Nishihara under one stress F.
struct FixedCombination {
  std::string expression;  ///< e.g. "(0.232 - Fs)/eta3"
  std::string unit;        ///< dimension, e.g. "length/time"
  double value = 0.0;
  double std_error = 0.0;  ///< delta method from the log-space covariance
  std::vector<std::string> parameters;  ///< the parameters it involves
};

/// The result of fitting one law.
struct FitResult {
  std::string law;                          ///< registry name
  std::vector<ParameterEstimate> parameters;  ///< in registry order
  /// Correlation matrix of the (log) parameters, row-major, parameters.size()^2;
  /// NaN in the rows and columns of parameters that are not identifiable.
  std::vector<double> correlation;
  std::size_t points = 0;  ///< n
  double rss = 0.0;        ///< residual sum of squares [length^2]
  double r2 = 0.0;         ///< 1 - RSS/TSS [-]; NaN (undefined) when the data have no spread (TSS ~ 0)
  double rmse = 0.0;       ///< sqrt(RSS/n) [length]
  double aic = 0.0;        ///< n ln(RSS/n) + 2k [-]
  double bic = 0.0;        ///< n ln(RSS/n) + k ln n [-]
  int iterations = 0;      ///< of the best start
  int starts = 0;          ///< starts tried
  int starts_agreeing = 0; ///< starts that reached the best RSS (relative 1e-6)
  int structured_starts = 0;  ///< of `starts`, those from the variable-projection search
  bool converged = false;  ///< the best start met the step tolerance
  /// false when the minimum was reached by one start only, or when the
  /// multi-start reference found a lower one than the variable-projection search
  bool minimum_certain = true;
  std::string minimum_note;  ///< why the minimum is not certain; empty if it is
  /// Singular values of the Jacobian of the residuals with respect to the log
  /// parameters divided by the residual standard deviation, largest first:
  /// 1/value is the standard error of ln p along that direction [-].
  std::vector<double> singular_values;
  std::vector<FixedCombination> combinations;  ///< combinations fixed by the data
  std::vector<std::string> warnings;  ///< identifiability and convergence warnings
  std::vector<double> fitted;         ///< d_model at each data point [length]

  laws::ParameterValues values() const;
  bool r2_defined() const { return std::isfinite(r2); }
  double correlation_at(std::size_t i, std::size_t j) const {
    return correlation[i * parameters.size() + j];
  }
};

/// d_model(t) of a law with given parameters under the data's stress history [length].
std::vector<double> predict(const laws::ContactRheology& law, const laws::StagedHistory& history,
                            const std::vector<double>& times);

/// Fits one registered law. Throws FitError when the data cannot constrain
/// the law at all (fewer points than parameters + 1, a parameter that may be
/// negative, no nonzero stress, a displacement that is zero everywhere).
FitResult fit_law(const laws::LawInfo& law, const CreepData& data, const FitOptions& options = {});

/// Model comparison criterion.
enum class Criterion { aic, bic };

/// Fits every law of the registry and returns the results sorted best first by
/// the criterion. Laws that cannot be fitted are left out, their reasons
/// appended to `skipped` ("law: reason").
std::vector<FitResult> fit_all(const laws::LawRegistry& registry, const CreepData& data,
                               Criterion criterion, std::vector<std::string>& skipped,
                               const FitOptions& options = {});

}  // namespace rheodda::fit
