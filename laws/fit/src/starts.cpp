// The classic starting values of a fit, from the curve itself (starts.hpp).
#include "starts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rheodda::fit::detail {

CurveFeatures analyse_curve(const CreepData& data) {
  CurveFeatures c;
  // The first stage that changes the stress and has enough points.
  std::size_t k = 0;
  for (std::size_t i = 0; i < data.stages.size(); ++i) {
    const double df = data.stages[i].stress - (i ? data.stages[i - 1].stress : 0.0);
    c.f_max = std::max(c.f_max, std::abs(data.stages[i].stress));
    if (c.df == 0.0 && df != 0.0 && data.stages[i].count >= 3) {
      k = i;
      c.df = df;
    }
  }
  if (c.df == 0.0) {  // fall back on the first loaded stage, whatever its size
    for (std::size_t i = 0; i < data.stages.size(); ++i)
      if (data.stages[i].stress != (i ? data.stages[i - 1].stress : 0.0)) {
        k = i;
        c.df = data.stages[i].stress - (i ? data.stages[i - 1].stress : 0.0);
        break;
      }
  }
  const auto& st = data.stages[k];
  const double prev = k ? data.displacement[st.first - 1] : 0.0;  // displacement before the step
  std::vector<double> tau, comp;
  for (std::size_t j = st.first; j < st.first + st.count; ++j) {
    tau.push_back(data.t[j] - st.t);
    comp.push_back((data.displacement[j] - prev) / c.df);
  }
  const std::size_t m = tau.size();
  c.c0 = comp.front();
  c.c_last = comp.back();
  for (double v : comp) c.c_max = std::max(c.c_max, std::abs(v));
  c.duration = tau.back();
  // Late line: least squares over the last third of the stage.
  const std::size_t from = m >= 6 ? m - m / 3 : (m >= 2 ? m - 2 : 0);
  double st_ = 0, sc = 0, stt = 0, stc = 0, cnt = 0;
  for (std::size_t j = from; j < m; ++j) {
    st_ += tau[j];
    sc += comp[j];
    stt += tau[j] * tau[j];
    stc += tau[j] * comp[j];
    cnt += 1;
  }
  const double den = cnt * stt - st_ * st_;
  c.slope = den > 0 ? (cnt * stc - st_ * sc) / den : 0.0;
  c.intercept = cnt > 0 ? (sc - c.slope * st_) / cnt : c.c_last;
  // Time to 63% of the transient above the jump and below the late line.
  const double amp = c.intercept - c.c0;
  c.t63 = c.duration / 3.0;
  if (amp > 0)
    for (std::size_t j = 0; j < m; ++j)
      if (comp[j] - c.c0 - std::max(c.slope, 0.0) * tau[j] >= (1.0 - std::exp(-1.0)) * amp) {
        c.t63 = tau[j];
        break;
      }
  if (!(c.t63 > 0)) c.t63 = c.duration > 0 ? c.duration / 100.0 : 1.0;
  if (!(c.duration > 0)) c.duration = data.t.back() > 0 ? data.t.back() : 1.0;
  return c;
}

// Start derived from the curve: jump -> E1, late slope -> dashpot viscosity,
// late intercept minus jump -> Kelvin compliance 1/E2, time to 63% of the
// transient -> retardation time eta2/E2.
std::vector<double> series_start(const SeriesStructure& s, std::size_t np, const CurveFeatures& c) {
  std::vector<double> v(np, 1.0);
  const double cmax = c.c_max > 0 ? c.c_max : 1.0;
  const double j0 = s.spring >= 0 ? (c.c0 > 0.01 * cmax ? c.c0 : 0.5 * cmax) : 0.0;
  if (s.spring >= 0) v[s.spring] = 1.0 / j0;
  bool flow = false;
  int kelvins = 0;
  for (const auto& el : s.elements) {
    flow = flow || el.kind != Kind::kelvin;
    kelvins += el.kind == Kind::kelvin;
  }
  const double rate = c.slope > 0.01 * cmax / c.duration ? c.slope : 0.1 * cmax / c.duration;
  double amp = (flow ? c.intercept : c.c_last) - j0;
  if (!(amp > 0.02 * cmax)) amp = 0.1 * cmax;
  int kelvin_index = 0;
  for (const auto& el : s.elements) {
    if (el.kind == Kind::kelvin) {
      // Split the transient among the Kelvin elements, retardation times spread around t63.
      const double e = kelvins / amp;
      const double spread = kelvins == 1 ? 1.0 : std::pow(9.0, kelvin_index - 0.5 * (kelvins - 1));
      v[el.E] = e;
      v[el.eta] = e * c.t63 * spread;
      ++kelvin_index;
    } else if (el.kind == Kind::dashpot) {
      v[el.eta] = 1.0 / rate;
    } else {
      const double fs = 0.5 * c.f_max;
      v[el.threshold] = fs;
      v[el.eta] = std::max(c.f_max - fs, 0.1 * c.f_max) / (c.f_max * rate);
    }
  }
  return v;
}

// Without a series structure: a start from each parameter's dimension.
std::vector<double> generic_start(const laws::LawInfo& info, const CurveFeatures& c) {
  std::vector<double> v;
  const double cmax = c.c_max > 0 ? c.c_max : 1.0;
  for (const auto& spec : info.parameters) {
    if (spec.unit == "stress/length") v.push_back(1.0 / cmax);
    else if (spec.unit == "stress*time/length") v.push_back(c.duration / cmax);
    else if (spec.unit == "stress") v.push_back(0.5 * c.f_max);
    else if (spec.unit == "time") v.push_back(c.duration / 3.0);
    else v.push_back(1.0);
  }
  return v;
}

// Restart r >= 1: the retardation times, the Kelvin compliances and the
// threshold scaled by fixed factors, then log-uniform factors in [1/10, 10]
// from a fixed-seed generator (the fit is deterministic).
std::vector<double> restart_start(const std::vector<double>& base, const std::optional<SeriesStructure>& s,
                                  int r, double f_max) {
  std::vector<double> v = base;
  static constexpr double tau_f[] = {0.1, 10.0, 0.3, 3.0};
  static constexpr double amp_f[] = {1.0, 1.0, 2.0, 0.5};
  static constexpr double fs_f[] = {0.3, 1.5, 0.6, 1.2};
  if (s && r <= 4) {
    for (const auto& el : s->elements) {
      if (el.kind == Kind::kelvin) {
        v[el.E] /= amp_f[r - 1];
        v[el.eta] *= tau_f[r - 1] / amp_f[r - 1];
      } else if (el.kind == Kind::bingham) {
        v[el.threshold] = std::min(v[el.threshold] * fs_f[r - 1], 0.95 * f_max);
      }
    }
    return v;
  }
  std::uint64_t state = 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(r + 1);
  for (auto& x : v) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
    x *= std::pow(10.0, 2.0 * u - 1.0);
  }
  return v;
}

}  // namespace rheodda::fit::detail
