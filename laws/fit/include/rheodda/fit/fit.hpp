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
#include <functional>
#include <limits>
#include <map>
#include <optional>
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

/// What the user sets on one parameter of a fit, as lmfit's Parameter
/// (docs/guide/fitting.md, "Initial values, bounds, fixed parameters and weights").
/// All in the parameter's registry unit.
struct ParameterSetting {
  /// Initial value (an extra start, tried first); with vary = false the value
  /// the parameter is held at. Must lie within [min, max].
  std::optional<double> value;
  bool vary = true;  ///< false: held at `value` (`--fix NAME=VALUE`)
  /// Lower bound (`--bounds NAME=MIN:MAX`); 0: none beyond positivity.
  double min = 0.0;
  double max = std::numeric_limits<double>::infinity();  ///< upper bound; inf: none
  /// lmfit's `expr`: the parameter is this expression of the others (numbers,
  /// parameter names, + - * / ^ or **, parentheses), e.g. "12*E2"; not varied,
  /// and then value, vary = false and bounds are refused. Empty: none.
  std::string expr;

  /// Nothing set: the parameter is fitted as without a setting.
  bool is_default() const {
    return !value && vary && min == 0.0 && max == std::numeric_limits<double>::infinity() && expr.empty();
  }
};

/// Knobs of a fit; the defaults are what `rheodda fit` uses.
struct FitOptions {
  int restarts = 4;               ///< extra starts besides the one derived from the curve
  /// Per start, for GSL's iterations and again for the bounded refinement
  /// (`rheodda fit --max-iterations`).
  int max_iterations = 500;
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
  /// Settings by parameter name (registry names of the law fitted); a name the
  /// law does not have is a FitError. Bounds act in the log of the parameter
  /// through the transforms of MINUIT/lmfit (docs/guide/fitting.md).
  std::map<std::string, ParameterSetting> parameters;
  /// true (lmfit's scale_covar, curve_fit's absolute_sigma=False): standard
  /// errors scaled by the residual standard deviation sqrt(chi^2/(n - k));
  /// false (`--absolute-sigma`): sigma is the measurement error in absolute
  /// terms and the covariance is (J^T J)^-1 of the residuals divided by sigma.
  /// false needs sigma in the data.
  bool scale_covariance = true;
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
  bool vary = true;      ///< false: held at its given value (ParameterSetting::vary); std_error 0
  /// The fit ended on a bound ("min" or "max"; empty if not): the value is the
  /// bound and, as for a fixed parameter, std_error is 0 and the others'
  /// errors are those with it held there.
  std::string at_bound;
  double min = 0.0;  ///< lower bound of the fit [unit]
  double max = std::numeric_limits<double>::infinity();  ///< upper bound of the fit [unit]
  /// The expression of the other parameters that gives it (ParameterSetting::expr;
  /// vary is then false); its std_error is propagated from theirs by its gradient.
  std::string expr;
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
  /// sum ((d_model - d)/sigma)^2 [-] with measurement sigma (CreepData::sigma);
  /// equal to rss [length^2] without. AIC and BIC are computed from it.
  double chi_square = 0.0;
  double reduced_chi_square = 0.0;  ///< chi_square / (n - k)
  int varying = 0;          ///< k: parameters fitted (not held by vary = false)
  bool weighted = false;    ///< the data carried sigma
  bool scale_covariance = true;  ///< as FitOptions::scale_covariance
  double r2 = 0.0;         ///< 1 - RSS/TSS [-]; NaN (undefined) when the data have no spread (TSS ~ 0)
  double rmse = 0.0;       ///< sqrt(RSS/n) [length]
  double aic = 0.0;        ///< n ln(chi_square/n) + 2k [-] (k = varying)
  double bic = 0.0;        ///< n ln(chi_square/n) + k ln n [-]
  int iterations = 0;      ///< of the best start
  int starts = 0;          ///< starts tried
  int starts_agreeing = 0; ///< starts that reached the best RSS (relative 1e-6)
  int structured_starts = 0;  ///< of `starts`, those from the variable-projection search
  /// The best start met GSL's step tolerance; with settings (FitOptions::parameters,
  /// sigma) only where the optimality conditions hold at the point reported:
  /// the gradient of chi^2 zero in the free parameters, pointing out of the box
  /// at a bound (cosine below 1e-6, docs/guide/fitting.md).
  bool converged = false;
  /// The largest violation of the optimality conditions at the point reported
  /// (a cosine, as above); 0 without settings.
  double optimality = 0.0;
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
  /// chi_square reached by each start polished on all points, in the order
  /// tried (variable-projection starts first) [as chi_square].
  std::vector<double> start_minima;

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
/// the law at all (fewer points than varying parameters + 1, a parameter that
/// may be negative, no nonzero stress, a displacement that is zero everywhere)
/// or when options.parameters is wrong (an unknown name, a value outside its
/// bounds, min >= max, vary = false without a value, nothing left to vary).
FitResult fit_law(const laws::LawInfo& law, const CreepData& data, const FitOptions& options = {});

/// Model comparison criterion.
enum class Criterion { aic, bic };

/// Fits every law of the registry and returns the results sorted best first by
/// the criterion. Laws that cannot be fitted are left out, their reasons
/// appended to `skipped` ("law: reason"). `on_law` (when set) is told of each
/// law before it is fitted: its name, index and the number of laws (a progress display).
std::vector<FitResult> fit_all(const laws::LawRegistry& registry, const CreepData& data,
                               Criterion criterion, std::vector<std::string>& skipped,
                               const FitOptions& options = {},
                               const std::function<void(const std::string& law, std::size_t index,
                                                        std::size_t count)>& on_law = {});

// ---- The choice of a law (model_choice.cpp; docs/guide/fitting.md, "The verdict") ----

/// Model weights of criterion values (one per law, any order):
///   w_i = exp(-Delta_i/2) / sum_j exp(-Delta_j/2),  Delta_i = c_i - min_j c_j.
/// On AIC these are the Akaike weights (Burnham & Anderson 2002, Model Selection and
/// Multimodel Inference, 2nd ed., Springer, ch. 2, "Akaike weights"): the weight of
/// evidence for each law among those fitted; on BIC, approximate posterior probabilities
/// of the laws under equal prior ones (same book, ch. 6). Sum 1 [-].
std::vector<double> model_weights(const std::vector<double>& criterion);

/// Delta limits of the verdict (Burnham & Anderson 2002, p. 70: Delta <= 2 substantial
/// support, 4-7 considerably less, > 10 essentially none): a law within kSupportedDelta of
/// the best is supported (evidence ratio exp(Delta/2) <= e), beyond kUnsupportedDelta it is
/// not (ratio above exp(5) = 148) [-].
inline constexpr double kSupportedDelta = 2.0;
inline constexpr double kUnsupportedDelta = 10.0;

/// The names of the parameters a fit leaves undetermined: varying, not on a bound, not
/// given by an expression, and not identifiable (ParameterEstimate::identifiable).
std::vector<std::string> unidentified_parameters(const FitResult& r);

/// What a fit's data cover: the lowest and highest |stress| of the stages that load
/// [stress], and the test's duration from the first stage's start to the last reading [time].
struct TestedRange {
  double stress_min = 0.0, stress_max = 0.0;
  double duration = 0.0;
};
TestedRange tested_range(const CreepData& data);

}  // namespace rheodda::fit
