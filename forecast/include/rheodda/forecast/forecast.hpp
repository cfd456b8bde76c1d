// `rheodda forecast` (docs/guide/forecast.md): a scene's histories with the uncertainty of
// a fitted law. The law parameters of one joint set are sampled from the covariance
// that `rheodda fit --json` reports (a multivariate normal on their logarithms), the
// ensemble runs as a study, and the percentiles of every history column are taken
// across its members at each time.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/laws/parameters.hpp"

namespace rheodda::forecast {

/// One law of a `rheodda fit --json` report (docs/guide/fitting.md).
struct FittedLaw {
  std::string file;                 ///< the report's path
  std::string law;                  ///< registry name, e.g. "burgers"
  std::vector<std::string> names;   ///< parameters in registry order
  std::vector<std::string> units;   ///< each parameter's unit as the report spells it, e.g. "MPa/mm"
  std::vector<std::string> dimensions;  ///< registry dimension, e.g. "stress/length"
  std::vector<double> values;       ///< fitted values [units]
  std::vector<bool> identifiable;   ///< false: the data do not fix it (docs/guide/fitting.md, "Identifiability")
  /// Standard error of ln p (std_error / value, the delta method the fit used) [-]; 0 when not identifiable.
  std::vector<double> log_std;
  std::vector<double> correlation;  ///< of the ln p, row-major; NaN in rows/columns of unidentified parameters
  std::string stress_unit, length_unit, time_unit;  ///< the report's units ("" when it gave none)
  /// Every law of the report with its weight of evidence on the report's ranking criterion
  /// (fit::model_weights: Akaike weights with rank_by aic), the report's order; one entry
  /// when it fitted one law.
  std::vector<std::pair<std::string, double>> weights;
  std::string rank_by;  ///< "aic" or "bic"
};

/// Reads the fit of `law` (empty: the report's best) from a `rheodda fit --json` file.
/// Throws scene::SceneError naming the file and key.
FittedLaw read_fit_report(const std::string& path, const std::string& law);

/// How parameters the data do not fix are sampled (they have no finite variance).
struct Unidentified {
  /// 0: held at the fitted value. F > 1: drawn log-uniformly in [value/F, value*F],
  /// independently of the others.
  double spread = 0.0;
};

/// The drawn parameter sets.
struct Samples {
  std::vector<laws::ParameterValues> accepted;  ///< in the report's units
  std::size_t drawn = 0;                         ///< accepted + rejected
  std::map<std::string, std::size_t> rejected;   ///< reason (the law's range check) -> count
  std::vector<std::string> held;                 ///< unidentified parameters held at the fitted value
  std::vector<std::string> spread;               ///< unidentified parameters drawn in a range
};

/// Draws `count` accepted parameter sets: ln p = ln p_fit + L z, z ~ N(0, I), L L^T the
/// covariance of the ln p of the identifiable parameters (C_ij = r_ij s_i s_j), taken
/// through its eigen-decomposition (negative eigenvalues of a rounded matrix clipped
/// to 0); unidentified parameters as `u` says. A set the law refuses (its parameter
/// ranges, LawRegistry::create) is rejected and counted; drawing stops with an error
/// after 100 x count draws. The same seed gives the same samples (std::mt19937_64,
/// Box-Muller).
Samples draw_samples(const FittedLaw& fit, std::size_t count, std::uint64_t seed, const Unidentified& u);

/// What the forecast's band covers and what it does not (docs/guide/forecast.md, "What the
/// band covers"): the parameters drawn, the unidentified ones held or spread and what their
/// value decides, the other laws the report's data support (the law's form is not sampled:
/// a forecast runs one law). Lines ending in newlines (coverage.cpp).
std::string band_coverage(const FittedLaw& fit, const Samples& drawn, const Unidentified& u);

/// Factor that converts a parameter of `dimension` (e.g. "stress*time/length") from the
/// report's units to a scene's (length, force, time labels; stress = force/length^2), by
/// UDUNITS-2 (rheodda::units). Throws std::invalid_argument for a unit it does not know.
double unit_factor(const std::string& dimension, const FittedLaw& fit, const std::string& length,
                   const std::string& force, const std::string& time);

/// Percentile p (0..100) of `values` by linear interpolation between order statistics
/// (Hyndman & Fan 1996, definition 7, as numpy's default). `values` is sorted in place.
double percentile(std::vector<double>& values, double p);

/// A history.csv as columns (numbers; NaN for an empty field), with its header order.
struct History {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  ///< rows[k][c]
  std::string units_line;                 ///< "# units: ..." (empty when absent)
};
History read_history(const std::string& path);

/// Linear interpolation of column c of `h` at time t (the column "time"); NaN outside the run.
double history_at(const History& h, std::size_t time_column, std::size_t c, double t);

}  // namespace rheodda::forecast
