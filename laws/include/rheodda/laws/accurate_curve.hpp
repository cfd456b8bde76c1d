// A law curve that is accurate or refused: the layer behind `rheodda law curve`
// (docs/reference/laws.md, "Accuracy of a curve").
//
// Why. integrate_curve (history.hpp) takes one step of the scheme per output
// step, which is what the scheme tests need but not what a user reading a curve
// needs: a nonlinear law in relaxation (power-law, n = 20, held displacement)
// drops to a tenth of its exact force at dt = 10 h with the exponential-linear
// scheme, the lagged scheme goes to NaN, and Newton at n = 100 stops short. Here
// each output step is crossed in substeps of the same scheme whose size is
// controlled by step doubling (one step of h against two of h/2; Hairer, Norsett &
// Wanner, "Solving Ordinary Differential Equations I", 2nd ed., sec. II.4): a
// substep is kept when the two differ by at most `tolerance` times the value
// (CurveAccuracy::tolerance), the finer result extrapolated (fine + (fine - coarse)/(2^p - 1), one
// order higher) is kept, and the next size is h (tol/err)^(1/(p+1)) (p the
// scheme's order, 1 or 2). The end-of-step force under a held
// displacement is found by Newton safeguarded by bisection on a bracket, which
// converges whatever the exponent. A damage law's substep lands on its failure.
// Whatever cannot be met (a step below the resolution of time, too many steps,
// a value that is not a finite double) throws CurveError with the reason.
//
// The laws' own step functions are called unchanged: what a run computes is not
// affected by this layer.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rheodda/laws/history.hpp"

namespace rheodda::laws {

/// What "accurate" means for a curve.
struct CurveAccuracy {
  /// Largest difference between one substep and two half substeps in the creep,
  /// relative to the value at the substep's end (|displacement| under force control,
  /// |force|/E1 under displacement control) or to `tolerance` times its largest value
  /// so far, whichever is larger; absolute on the damage D [-].
  double tolerance = 1e-6;
  /// Most substeps of the scheme over the whole curve.
  long long max_steps = 10'000'000;
};

/// The curve and how it was computed.
struct AccurateCurve {
  /// At t = 0, every output step end and every stage start, as integrate_curve's.
  std::vector<CurveSample> samples;
  long long steps = 0;             ///< substeps of the scheme kept (each checked by two half steps)
  double smallest_step = 0.0;      ///< [time]
  double largest_error = 0.0;      ///< largest error estimate of a kept substep, relative [-]
  std::optional<double> failure_time;  ///< when the damage reached 1 [time]; a substep ends there
  /// The law's creep is infinite at failure (damage-burgers with n >= r + 1): the samples
  /// end at the last output time before failure_time.
  bool ends_at_failure = false;
};

/// The curve cannot be computed to the tolerance (the message says why, where and what to change).
class CurveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Integrates `law` under the staged history as integrate_curve does (same output
/// times, same columns), to `accuracy`. After a damage law fails its creep stays at
/// its value at failure (as its closed form's does). Throws LawError on bad arguments
/// (those integrate_curve refuses, and a tolerance outside [1e-12, 1e-2]) and
/// CurveError when the tolerance cannot be met or a value is not finite.
AccurateCurve integrate_curve_accurate(const ContactRheology& law, Control control, const StagedHistory& history,
                                       double t_end, double dt, Scheme scheme, const CurveAccuracy& accuracy = {});

/// First sample (in order) whose force, displacement or damage is not a finite number,
/// or samples.size(); integrate_curve's output, checked by its callers.
std::size_t first_non_finite(const std::vector<CurveSample>& samples);

}  // namespace rheodda::laws
