// Load histories and the law-alone integrator behind `rheodda law curve`,
// the verification tests and the fits.
//
// A staged history holds a value from each time on: "0:0.232,100:0.5,150:0"
// is 0.232 from t = 0, 0.5 from t = 100, 0 from t = 150. For linear laws the
// exact response is the Boltzmann superposition d(t) = sum dF_i J(t - t_i)
// (rheology.md; the seed's eqs. 4-6); for Nishihara under staged force it is
// superposition of the linear part plus the exact Bingham integral.
#pragma once

#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::laws {

/// A piecewise-constant history: value[i] holds from time[i] on; 0 before time[0].
class StagedHistory {
 public:
  struct Stage {
    double t;      ///< start time of the stage [time]
    double value;  ///< value from t on [force or length]
  };
  StagedHistory() = default;
  /// Stages must have strictly increasing, finite, non-negative times; throws LawError.
  explicit StagedHistory(std::vector<Stage> stages);
  /// Parses "T:V[,T:V...]"; throws LawError naming `what` (e.g. "--force").
  static StagedHistory parse(std::string_view text, std::string_view what);

  double at(double t) const;  ///< value at t (the new value at a stage start)
  const std::vector<Stage>& stages() const { return stages_; }

 private:
  std::vector<Stage> stages_;
};

/// What the history prescribes.
enum class Control { force, displacement };

/// One output row of a law curve.
struct CurveSample {
  double t = 0.0;             ///< [time]
  double force = 0.0;         ///< [force]
  double displacement = 0.0;  ///< total: instantaneous spring + creep [length]
  std::optional<double> exact{};  ///< closed-form displacement (force control) or force (displacement control)
  double damage = 0.0;  ///< damage D of a damage law at t [-] (1: failed; 0 for other laws)
};

/// Exact total displacement at t under a staged force history, where the law has one.
std::optional<double> exact_displacement(const ContactRheology& law, const StagedHistory& force,
                                         double t);
/// Exact force at t under a staged displacement history, where the law has one.
std::optional<double> exact_force(const ContactRheology& law, const StagedHistory& displacement,
                                  double t);

/// The output times of a curve: 0, the multiples of dt, every stage start and t_end
/// (a multiple within 1e-9 dt of a stage start or of t_end is replaced by it) [time].
std::vector<double> curve_times(const StagedHistory& history, double t_end, double dt);

/// Throws LawError unless dt and t_end are positive finite times and the law can be
/// driven by the control (a held displacement needs an instantaneous spring E1).
void check_curve_arguments(const ContactRheology& law, Control control, double t_end, double dt);

/// Integrates the law alone from t = 0 to t_end with step dt (steps are split
/// so that every stage start is a step boundary), returning the state after
/// each step and at every stage start. Throws LawError on bad arguments
/// (dt <= 0, displacement control for a law without instantaneous spring).
std::vector<CurveSample> integrate_curve(const ContactRheology& law, Control control,
                                         const StagedHistory& history, double t_end, double dt,
                                         Scheme scheme);

/// Force at the end of a step of a spring k [force/length] in series with the
/// law's creep, when the total displacement d_end [length] is prescribed:
/// solves F = k (d_end - q_old - (h + c F)) on the law's affine pieces.
double solve_series_force(const ContactRheology& law, const StepConstants& k_step,
                          const RheologyState& old, double stiffness, double d_end,
                          double force_start);

/// Force history given by a function (for ramps in tests and benches).
using ForceFunction = std::function<double(double)>;
/// Integrates under force control with F(t) from a function; returns the total
/// displacement at t_end. Force at a step's start and end are f(t_n), f(t_n+1);
/// steps are dt long, the last one shorter if t_end is not a multiple of dt.
/// Throws LawError if dt <= 0 or t_end < 0 (or either is not finite).
double integrate_force_function(const ContactRheology& law, const ForceFunction& f, double t_end,
                                double dt, Scheme scheme);

}  // namespace rheodda::laws
