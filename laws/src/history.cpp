#include "rheodda/laws/history.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "rheodda/laws/power_law.hpp"
#include "rheodda/laws/series_law.hpp"

namespace rheodda::laws {

// ---- StagedHistory -----------------------------------------------------------
StagedHistory::StagedHistory(std::vector<Stage> stages) : stages_(std::move(stages)) {
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    const auto& s = stages_[i];
    if (!std::isfinite(s.t) || !std::isfinite(s.value))
      throw LawError("history", fmt::format("stage {}: time and value must be finite numbers", i + 1));
    if (s.t < 0.0)
      throw LawError("history", fmt::format("stage {}: time {:g} is negative", i + 1, s.t));
    if (i > 0 && s.t <= stages_[i - 1].t)
      throw LawError("history", fmt::format("stage {}: time {:g} does not increase (previous {:g})",
                                            i + 1, s.t, stages_[i - 1].t));
  }
}

namespace {
double parse_number(std::string_view text, std::string_view what, std::string_view item) {
  double v = 0.0;
  const char* b = text.data();
  const char* e = text.data() + text.size();
  auto [p, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || p != e || text.empty())
    throw LawError(std::string(what), fmt::format("{}: '{}' in '{}' is not a number", what, text, item));
  return v;
}
}  // namespace

StagedHistory StagedHistory::parse(std::string_view text, std::string_view what) {
  std::vector<Stage> stages;
  std::size_t pos = 0;
  if (text.empty()) throw LawError(std::string(what), fmt::format("{}: empty history; expected T:V[,T:V...]", what));
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    const std::string_view item = text.substr(pos, comma - pos);
    const std::size_t colon = item.find(':');
    if (colon == std::string_view::npos)
      throw LawError(std::string(what),
                     fmt::format("{}: '{}' is not of the form T:V (time:value)", what, item));
    stages.push_back({parse_number(item.substr(0, colon), what, item),
                      parse_number(item.substr(colon + 1), what, item)});
    pos = comma + 1;
  }
  try {
    return StagedHistory(std::move(stages));
  } catch (const LawError& e) {
    throw LawError(std::string(what), fmt::format("{}: {}", what, e.what()));
  }
}

double StagedHistory::at(double t) const {
  double v = 0.0;
  for (const auto& s : stages_) {
    if (s.t <= t) v = s.value;
    else break;
  }
  return v;
}

// ---- Exact responses -----------------------------------------------------------
std::optional<double> exact_displacement(const ContactRheology& law, const StagedHistory& force,
                                         double t) {
  if (law.is_linear()) {
    // Boltzmann superposition d(t) = sum dF_i J(t - t_i) (seed eqs. 4-6).
    double d = 0.0, prev = 0.0;
    for (const auto& s : force.stages()) {
      if (s.t > t) break;
      d += law.displacement_closed_form(s.value - prev, t - s.t);
      prev = s.value;
    }
    return d;
  }
  // A series law with a threshold: spring and Kelvin parts superpose, the
  // Bingham part integrates <|F| - Fs> exactly over each constant stage.
  const auto* series = dynamic_cast<const SeriesLaw*>(&law);
  if (!series) {
    // Other nonlinear laws: the closed form under a force held from t = 0.
    const auto& st = force.stages();
    if (st.size() == 1 && st[0].t == 0.0) return law.displacement_closed_form(st[0].value, t);
    return std::nullopt;
  }
  const auto& stages = force.stages();
  const auto e1 = law.instantaneous_stiffness();
  double d = e1 ? force.at(t) / *e1 : 0.0;
  for (const auto& el : series->elements()) {
    double prev = 0.0;
    for (std::size_t i = 0; i < stages.size() && stages[i].t <= t; ++i) {
      const double f = stages[i].value;
      const double end = (i + 1 < stages.size()) ? std::min(stages[i + 1].t, t) : t;
      switch (el.kind) {
        case CreepElement::Kind::kelvin:
          d += (f - prev) / el.E * kelvin_b(el.E * (t - stages[i].t) / el.eta);
          break;
        case CreepElement::Kind::dashpot: d += f * (end - stages[i].t) / el.eta; break;
        case CreepElement::Kind::bingham: {
          const double excess = f > el.threshold ? f - el.threshold
                                : f < -el.threshold ? f + el.threshold : 0.0;
          d += excess * (end - stages[i].t) / el.eta;
          break;
        }
      }
      prev = f;
    }
  }
  return d;
}

namespace {
/// Force at t of `power-law` (spring E1 + Norton dashpot) under a staged displacement.
/// Within a stage the force obeys F' = -E1 A sign(F) (|F|/tau_ref)^n, whose solution
/// from F_s at the stage start is (docs/reference/laws.md, "power-law")
///     |F|^(1-n) = |F_s|^(1-n) + (n - 1) E1 A (t - t_s) / tau_ref^n      (n > 1)
///     F = F_s exp(-E1 A (t - t_s) / tau_ref)                               (n = 1),
/// never crossing zero; a stage's displacement jump adds E1 times the jump to F.
/// Written as F = F_s (1 + w)^(-1/(n-1)), w = (n-1) E1 A dt/tau_ref (|F_s|/tau_ref)^(n-1),
/// with ln(1 + w) from ln w when w would overflow, so any exponent stays finite.
double power_law_relaxation(const ParameterValues& p, const StagedHistory& displacement, double t) {
  const double E1 = p.at("E1"), A = p.at("A"), tau_ref = p.at("tau_ref"), n = p.at("n");
  double f = 0.0, prev = 0.0, since = 0.0;
  auto relax = [&](double f_s, double duration) {
    if (f_s == 0.0 || duration <= 0.0) return f_s;
    if (n == 1.0) return f_s * std::exp(-E1 * A * duration / tau_ref);
    const double log_w = std::log((n - 1.0) * E1 * A * duration / tau_ref) + (n - 1.0) * std::log(std::abs(f_s) / tau_ref);
    const double log1p_w = log_w > 30.0 ? log_w + std::log1p(std::exp(-log_w)) : std::log1p(std::exp(log_w));
    return f_s * std::exp(-log1p_w / (n - 1.0));
  };
  for (const auto& s : displacement.stages()) {
    if (s.t > t) break;
    f = relax(f, s.t - since) + E1 * (s.value - prev);
    prev = s.value;
    since = s.t;
  }
  return relax(f, t - since);
}
}  // namespace

std::optional<double> exact_force(const ContactRheology& law, const StagedHistory& displacement,
                                  double t) {
  if (dynamic_cast<const PowerLaw*>(&law)) return power_law_relaxation(law.parameters(), displacement, t);
  if (!law.relaxation_modulus(0.0)) return std::nullopt;
  // F(t) = sum dd_i G(t - t_i) (Boltzmann superposition of the relaxation
  // modulus) over the stages that started at or before `time` (`inclusive`)
  // or strictly before it (the left limit, just before a stage starts).
  auto force_at = [&](double time, bool inclusive) {
    double f = 0.0, prev = 0.0;
    for (const auto& s : displacement.stages()) {
      if (inclusive ? s.t > time : s.t >= time) break;
      f += (s.value - prev) * *law.relaxation_modulus(time - s.t);
      prev = s.value;
    }
    return f;
  };
  const double f = force_at(t, true);
  const double limit = law.linear_limit();
  if (std::isfinite(limit)) {
    // Below the threshold the law is a standard linear solid (one relaxation
    // time), whose force moves monotonically within a stage: the extremes of
    // |F| over [0, t] are at t and at both ends of each stage that started.
    if (std::abs(f) > limit) return std::nullopt;
    for (const auto& s : displacement.stages())
      if (s.t <= t && (std::abs(force_at(s.t, true)) > limit || std::abs(force_at(s.t, false)) > limit))
        return std::nullopt;
  }
  return f;
}

// ---- Integration -------------------------------------------------------------
double solve_series_force(const ContactRheology& law, const StepConstants& k_step,
                          const RheologyState& old, double stiffness, double d_end,
                          double force_start) {
  // F = k (d_end - q_old - h - c F)  =>  F = k (d_end - q_old - h) / (1 + k c).
  // The creep increment is nondecreasing in F, so the root is unique; for a
  // piecewise law try the piece of the guess, then the piece of the answer.
  const double base = d_end - old.creep();
  double guess = force_start;
  double f = guess;
  if (law.linearity() == Linearity::nonlinear) {
    // Newton on R(F) = F - k (base - Delta d_c(F)) with the law's tangent (1')
    // (contact_rheology.hpp): F_{j+1} = k (base - h_j)/(1 + k c_j), the update
    // the contact layer makes (docs/reference/rheology-in-dda.md, "Nonlinear laws").
    // Converged when the step changes F by <= 1e-14 of |F| (a few ulps), or
    // after 100 iterations (the tangent is monotone, so Newton converges).
    for (int it = 0; it < 100; ++it) {
      const Linearization l = law.linearize(k_step, old, force_start, guess);
      f = stiffness * (base - l.h) / (1.0 + stiffness * l.c);
      if (std::abs(f - guess) <= 1e-14 * std::abs(f) || f == guess) return f;
      guess = f;
    }
    return f;
  }
  for (int attempt = 0; attempt < 4; ++attempt) {
    const Linearization l = law.linearize(k_step, old, force_start, guess);
    f = stiffness * (base - l.h) / (1.0 + stiffness * l.c);
    const Linearization check = law.linearize(k_step, old, force_start, f);
    if (check.h == l.h && check.c == l.c) return f;
    guess = f;
  }
  // No piece is consistent: the root sits on the kink at the threshold.
  return std::copysign(law.linear_limit(), f);
}

// Step boundaries: multiples of dt, every stage start and t_end. A multiple of
// dt within round-off (1e-9 dt) of a stage start or of t_end is replaced by
// that exact time, so a load change never falls a sliver after a boundary.
std::vector<double> curve_times(const StagedHistory& history, double t_end, double dt) {
  std::vector<double> exact_times;
  for (const auto& s : history.stages())
    if (s.t > 0.0 && s.t < t_end) exact_times.push_back(s.t);
  exact_times.push_back(t_end);
  const double tol = 1e-9 * dt;
  auto near_exact = [&](double t) {
    auto it = std::lower_bound(exact_times.begin(), exact_times.end(), t - tol);
    return it != exact_times.end() && *it <= t + tol;
  };
  std::vector<double> grid{0.0};
  const auto n = static_cast<long long>(std::floor(t_end / dt + 1e-9));
  grid.reserve(static_cast<std::size_t>(n) + exact_times.size() + 1);
  for (long long i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) * dt;
    if (t < t_end && !near_exact(t)) grid.push_back(t);
  }
  grid.insert(grid.end(), exact_times.begin(), exact_times.end());
  std::sort(grid.begin(), grid.end());
  return grid;
}

void check_curve_arguments(const ContactRheology& law, Control control, double t_end, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw LawError("dt", fmt::format("--dt must be a positive finite time step, got {:g}", dt));
  if (!(t_end > 0.0) || !std::isfinite(t_end))
    throw LawError("t-end", fmt::format("--t-end must be a positive finite time, got {:g}", t_end));
  if (control == Control::displacement && !law.instantaneous_stiffness())
    throw LawError("displacement",
                   fmt::format("law '{}' has no instantaneous spring, so a held displacement would "
                               "need an infinite force; use --force, or a law with E1",
                               law.name()));
}

std::vector<CurveSample> integrate_curve(const ContactRheology& law, Control control,
                                         const StagedHistory& history, double t_end, double dt,
                                         Scheme scheme) {
  check_curve_arguments(law, control, t_end, dt);
  const auto e1 = law.instantaneous_stiffness();

  const std::vector<double> grid = curve_times(history, t_end, dt);
  std::vector<CurveSample> out;
  out.reserve(grid.size());
  RheologyState state, next;

  // The instantaneous response at a time: the spring carries the jump.
  auto sample = [&](double t) {
    CurveSample s;
    s.t = t;
    s.damage = state.damage;
    if (control == Control::force) {
      s.force = history.at(t);
      s.displacement = (e1 ? s.force / *e1 : 0.0) + state.creep();
      s.exact = exact_displacement(law, history, t);
    } else {
      s.displacement = history.at(t);
      s.force = *e1 * (s.displacement - state.creep());
      s.exact = exact_force(law, history, t);
    }
    return s;
  };

  out.push_back(sample(0.0));
  double last_dt = -1.0;
  StepConstants k;
  for (std::size_t n = 0; n + 1 < grid.size(); ++n) {
    const double h = grid[n + 1] - grid[n];
    if (h != last_dt) {  // constants once per step size, not per step
      k = law.step_constants(h, scheme);
      last_dt = h;
    }
    const double f_start = out.back().force;
    double f_end = f_start;  // staged force: constant within the step
    if (control == Control::displacement)
      f_end = solve_series_force(law, k, state, *e1, history.at(grid[n]), f_start);
    law.advance(k, state, f_start, f_end, next);
    state = next;
    out.push_back(sample(grid[n + 1]));
  }
  return out;
}

double integrate_force_function(const ContactRheology& law, const ForceFunction& f, double t_end,
                                double dt, Scheme scheme) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw LawError("dt", fmt::format("dt must be a positive finite time step, got {:g}", dt));
  if (!(t_end >= 0.0) || !std::isfinite(t_end))
    throw LawError("t-end", fmt::format("t_end must be a finite time >= 0, got {:g}", t_end));
  // Whole steps of dt, then one shorter last step if t_end is not a multiple of dt.
  const auto n = static_cast<long long>(std::floor(t_end / dt + 1e-9));
  const StepConstants k = law.step_constants(dt, scheme);
  RheologyState state, next;
  double t0 = 0.0;
  for (long long i = 0; i < n; ++i) {
    t0 = static_cast<double>(i) * dt;
    const double t1 = i + 1 == n && std::abs(t_end - static_cast<double>(n) * dt) <= 1e-9 * dt
                          ? t_end
                          : static_cast<double>(i + 1) * dt;
    law.advance(k, state, f(t0), f(t1), next);
    state = next;
    t0 = t1;
  }
  if (t_end - t0 > 1e-9 * dt) {
    const StepConstants last = law.step_constants(t_end - t0, scheme);
    law.advance(last, state, f(t0), f(t_end), next);
    state = next;
  }
  const auto e1 = law.instantaneous_stiffness();
  return (e1 ? f(t_end) / *e1 : 0.0) + state.creep();
}

}  // namespace rheodda::laws
