// A law curve to a tolerance (accurate_curve.hpp): substeps of the scheme chosen by
// step doubling, a bracketed Newton for the force under a held displacement,
// substeps landing on a damage law's failure.
#include "rheodda/laws/accurate_curve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace rheodda::laws {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

bool finite_state(const RheologyState& s) {
  for (double q : s.q)
    if (!std::isfinite(q)) return false;
  return std::isfinite(s.damage);
}

/// The state of the law and its force at one time.
struct Point {
  RheologyState state;
  double force = 0.0;  ///< [force]
  bool finite() const { return finite_state(state) && std::isfinite(force); }
};

class Integrator {
 public:
  Integrator(const ContactRheology& law, Control control, Scheme scheme)
      : law_(law), control_(control), scheme_(scheme), e1_(law.instantaneous_stiffness().value_or(0.0)) {}

  /// One step of the scheme of length h from `from` under the stage's value v (the
  /// force held, or the total displacement held) [time].
  Point step(const Point& from, double v, double h) {
    const StepConstants& k = constants(h);
    Point to;
    const double fe = control_ == Control::force ? v : end_force(k, from, v);
    law_.advance(k, from.state, from.force, fe, to.state);
    to.force = fe;
    return to;
  }

  /// Time from `from` within a step of h at which the law fails (the scheme's force), if it does.
  std::optional<double> failure_within(const Point& from, const Point& to, double h) {
    return law_.failure_in_step(constants(h), from.state, from.force, to.force);
  }

 private:
  const StepConstants& constants(double h) {
    // A substep size repeats (kept sizes, their halves): a small cache saves the exponentials.
    for (auto& c : cache_)
      if (c.dt == h) return c;
    cache_[next_] = law_.step_constants(h, scheme_);
    const StepConstants& k = cache_[next_];
    next_ = (next_ + 1) % cache_.size();
    return k;
  }

  /// The force at the step's end under a held total displacement d: the root of
  ///     R(F) = F - E1 (d - q_old - Delta d_c(F)),
  /// Delta d_c from the law's advance(). Delta d_c never decreases with F, so R rises
  /// at least as fast as F: the root is unique and lies within |R(g)| of any guess g.
  /// Newton on the law's tangent (linearize, its eq. 1') inside that bracket, with
  /// bisection whenever Newton would leave it; converged when the bracket is a few
  /// ulps wide or R vanishes. (solve_series_force, the plain Newton of the scheme
  /// tests, stops after 100 iterations: too few at n = 100.)
  double end_force(const StepConstants& k, const Point& from, double d) {
    const double base = d - from.state.creep();
    RheologyState scratch;
    auto residual = [&](double f) { return f - e1_ * (base - law_.advance(k, from.state, from.force, f, scratch)); };
    double x = from.force, r = residual(x);
    if (!std::isfinite(r)) x = 0.0, r = residual(x);
    if (!std::isfinite(r) || r == 0.0) return r == 0.0 ? x : std::numeric_limits<double>::quiet_NaN();
    double lo = r > 0.0 ? x - r : x, hi = r > 0.0 ? x : x - r;
    // Rounding may leave the far end a hair short: widen until it brackets.
    for (int i = 0; i < 64; ++i) {
      const double rl = residual(lo), rh = residual(hi);
      if (rl <= 0.0 && rh >= 0.0) break;
      const double w = hi - lo;
      if (rl > 0.0) lo -= w;
      if (rh < 0.0) hi += w;
    }
    double best = x, best_r = std::abs(r);
    for (int it = 0; it < 4000; ++it) {
      const Linearization l = law_.linearize(k, from.state, from.force, x);
      const double slope = 1.0 + e1_ * l.c;  // R'(x)
      double next = std::isfinite(slope) && slope > 0.0 ? x - r / slope : kInf;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (next == x) break;
      x = next;
      r = residual(x);
      if (std::abs(r) < best_r) best = x, best_r = std::abs(r);
      if (r == 0.0) break;
      (r < 0.0 ? lo : hi) = x;
      if (hi - lo <= 4.0 * kEps * std::max(std::abs(lo), std::abs(hi))) break;
    }
    return best;
  }

  const ContactRheology& law_;
  Control control_;
  Scheme scheme_;
  double e1_;
  std::array<StepConstants, 4> cache_{};
  std::size_t next_ = 0;
};

std::string time_text(double t) { return fmt::format("{:.10g}", t); }

}  // namespace

std::size_t first_non_finite(const std::vector<CurveSample>& samples) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    if (!std::isfinite(s.force) || !std::isfinite(s.displacement) || !std::isfinite(s.damage)) return i;
  }
  return samples.size();
}

AccurateCurve integrate_curve_accurate(const ContactRheology& law, Control control, const StagedHistory& history,
                                       double t_end, double dt, Scheme scheme, const CurveAccuracy& accuracy) {
  if (!(accuracy.tolerance >= 1e-12 && accuracy.tolerance <= 1e-2))
    throw LawError("tolerance", fmt::format("--tolerance must be in [1e-12, 1e-2], got {:g}", accuracy.tolerance));
  check_curve_arguments(law, control, t_end, dt);
  const std::vector<double> times = curve_times(history, t_end, dt);
  const auto e1 = law.instantaneous_stiffness();
  const double tol = accuracy.tolerance;
  const int order = scheme == Scheme::exponential_linear ? 2 : 1;

  AccurateCurve out;
  out.smallest_step = kInf;
  Point now;
  double scale = 0.0;  // the curve's scale in displacement [length] (CurveAccuracy::tolerance)
  // Displacement [length] that measures the error: the total one under force control,
  // force/E1 under displacement control.
  auto measure = [&](const Point& p, double v) {
    return control == Control::force ? std::abs((e1 ? v / *e1 : 0.0) + p.state.creep()) : std::abs(p.force) / *e1;
  };
  auto sample = [&](double t, const Point& p) {
    CurveSample s;
    s.t = t;
    s.damage = p.state.damage;
    if (control == Control::force) {
      s.force = history.at(t);
      s.displacement = (e1 ? s.force / *e1 : 0.0) + p.state.creep();
      s.exact = exact_displacement(law, history, t);
    } else {
      s.displacement = history.at(t);
      s.force = *e1 * (s.displacement - p.state.creep());
      s.exact = exact_force(law, history, t);
    }
    if (s.exact && !std::isfinite(*s.exact)) s.exact.reset();  // a closed form that overflows: no reference
    if (!std::isfinite(s.force) || !std::isfinite(s.displacement))
      throw CurveError(fmt::format(
          "at t = {} the {} is not a finite number (beyond the range of a double): smaller loads or parameters",
          time_text(t), std::isfinite(s.force) ? "displacement" : "force"));
    return s;
  };

  out.samples.push_back(sample(0.0, now));
  Integrator step(law, control, scheme);
  double h = dt;
  long long trials = 0;
  for (std::size_t n = 0; n + 1 < times.size(); ++n) {
    const double a = times[n], b = times[n + 1];
    const double v = history.at(a);  // the stage's force or displacement over [a, b)
    now.force = out.samples.back().force;  // after the stage's jump at a
    scale = std::max(scale, measure(now, v));
    double t = a;
    while (t < b && !out.failure_time) {
      if (++trials > 4 * accuracy.max_steps || out.steps >= accuracy.max_steps)
        throw CurveError(fmt::format(
            "the {} scheme needs more than {} substeps to hold --tolerance {:g} (at t = {} of {}): a larger "
            "--tolerance or a shorter --t-end",
            scheme_name(scheme), accuracy.max_steps, tol, time_text(t), time_text(t_end)));
      const double rest = b - t;
      if (h >= rest * (1.0 - 1e-9)) h = rest;
      // Below this a step no longer moves the time (a few ulps of t) [time].
      const double h_min = std::max(16.0 * kEps * t, std::numeric_limits<double>::min());
      // Under a force held over the step the law fails after time_to_failure, exactly
      // for the three schemes: the substep ends there ("lands").
      bool landing = false;
      if (control == Control::force) {
        const double ttf = law.time_to_failure(now.state, now.force);
        if (ttf <= h) h = ttf < h_min ? 0.0 : ttf, landing = true;
      }
      Point coarse = now, fine = now;
      if (h > 0.0) {
        coarse = step.step(now, v, h);
        fine = step.step(step.step(now, v, 0.5 * h), v, 0.5 * h);
      }
      if (!landing && (coarse.state.failed() || fine.state.failed())) {
        // Fails within the step (a displacement held): the substep ends at the failure.
        const auto theta = step.failure_within(now, coarse, h);
        if (theta && *theta < h * (1.0 - 1e-12) && *theta >= h_min) {
          h = *theta;
          continue;
        }
        landing = true;
      }
      if (landing && !std::isfinite(fine.state.creep())) {
        // The law's creep is infinite at failure (damage-burgers with n >= r + 1).
        out.failure_time = t + h;
        out.ends_at_failure = true;
        break;
      }
      double err = kInf;
      if (coarse.finite() && fine.finite()) {
        // Relative to the value at the step's end, down to tol times the curve's scale:
        // a relaxing force stays accurate to its own size (and keeps its sign), not
        // only to the size of the force it started from.
        const double dq = std::abs(fine.state.creep() - coarse.state.creep());
        const double size = std::max({measure(fine, v), tol * scale, std::numeric_limits<double>::min()});
        err = std::max(dq == 0.0 ? 0.0 : dq / size, std::abs(fine.state.damage - coarse.state.damage));
      }
      if (err <= tol) {
        now = fine;
        if (!landing) {
          // Local extrapolation (Hairer, Norsett & Wanner, sec. II.4): fine + (fine -
          // coarse)/(2^p - 1) is one order higher, and the estimate that kept the step
          // bounds its error with room to spare, so the global error stays near the
          // tolerance (measured in tests/laws/accurate_curve_test.cpp). The damage is
          // the fine one's: extrapolated, it could pass 1 without failing.
          // Where the correction would carry a relaxing force past zero (a force below
          // the tolerance's floor), the fine result stays: relaxation never changes sign.
          const double w = 1.0 / ((1 << order) - 1);
          Point extrapolated = fine;
          for (std::size_t i = 0; i < extrapolated.state.q.size(); ++i)
            extrapolated.state.q[i] += w * (fine.state.q[i] - coarse.state.q[i]);
          if (control == Control::displacement) extrapolated.force = *e1 * (v - extrapolated.state.creep());
          if (control == Control::force || std::signbit(extrapolated.force) == std::signbit(fine.force) ||
              fine.force == 0.0)
            now = extrapolated;
        }
        t = h == rest ? b : t + h;
        ++out.steps;
        if (h > 0.0) out.smallest_step = std::min(out.smallest_step, h);
        out.largest_error = std::max(out.largest_error, err);
        scale = std::max(scale, measure(now, v));
        if (landing) {
          now.state.damage = 1.0;  // failed: from now on the creep stays at its value at failure
          out.failure_time = t;
        }
        const double grow = err == 0.0 ? 4.0 : 0.9 * std::pow(tol / err, 1.0 / (order + 1));
        h = std::max(h, h_min) * std::min(4.0, grow);
        continue;
      }
      const double shrink = std::isfinite(err) ? 0.9 * std::pow(tol / err, 1.0 / (order + 1)) : 0.1;
      h *= std::clamp(shrink, 0.1, 0.9);
      if (h < h_min)
        throw CurveError(fmt::format(
            "the {} scheme cannot hold --tolerance {:g} at t = {}: its substeps fell below {:.3g} (the resolution "
            "of time there) with {}; a larger --tolerance, or loads and parameters that keep the law's rates "
            "within a double",
            scheme_name(scheme), tol, time_text(t), h_min,
            std::isfinite(err) ? fmt::format("an error estimate of {:.3g}", err)
                               : std::string("a creep increment that is not a finite number")));
    }
    if (out.ends_at_failure) break;
    out.samples.push_back(sample(b, now));
  }
  if (out.steps == 0) out.smallest_step = 0.0;
  return out;
}

}  // namespace rheodda::laws
