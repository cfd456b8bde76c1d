#include "rheodda/fit/fit.hpp"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <optional>

#include "rheodda/laws/series_law.hpp"
#include "series_structure.hpp"
#include "varpro.hpp"

namespace rheodda::fit {

laws::ParameterValues FitResult::values() const {
  laws::ParameterValues v;
  for (const auto& p : parameters) v[p.name] = p.value;
  return v;
}

std::vector<double> predict(const laws::ContactRheology& law, const laws::StagedHistory& history,
                            const std::vector<double>& times) {
  std::vector<double> out;
  out.reserve(times.size());
  for (double t : times) {
    const auto d = laws::exact_displacement(law, history, t);
    if (!d)
      throw FitError(std::string(law.name()),
                     fmt::format("law '{}' has no exact response to a staged stress history",
                                 law.name()));
    out.push_back(*d);
  }
  return out;
}

namespace {

using detail::Element;
using detail::Kind;
using detail::SeriesStructure;

// ---- The law as a spring plus creep elements, in terms of its parameters ----

// Builds the law once with distinct probe values and matches each constant of
// its spring and elements to the parameter that carries it; this gives the
// analytic model (and its Jacobian) for any registered SeriesLaw. nullopt if
// the law is not a SeriesLaw whose constants are its parameters one to one.
std::optional<SeriesStructure> probe_structure(const laws::LawInfo& info) {
  const std::size_t np = info.parameters.size();
  laws::ParameterValues probe;
  std::vector<double> values(np);
  for (std::size_t k = 0; k < np; ++k) {
    values[k] = 1.5 + 0.75 * static_cast<double>(k);
    probe[info.parameters[k].name] = values[k];
  }
  std::unique_ptr<laws::ContactRheology> law;
  try {
    law = info.make(laws::validate_parameters(info.name, info.parameters, probe));
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const auto* series = dynamic_cast<const laws::SeriesLaw*>(law.get());
  if (!series) return std::nullopt;
  std::vector<int> used(np, 0);
  bool ok = true;
  auto index_of = [&](double v) {
    for (std::size_t k = 0; k < np; ++k)
      if (values[k] == v) {
        ++used[k];
        return static_cast<int>(k);
      }
    ok = false;
    return -1;
  };
  SeriesStructure s;
  if (const auto e1 = series->instantaneous_stiffness()) s.spring = index_of(*e1);
  for (const auto& el : series->elements()) {
    Element e;
    e.kind = el.kind;
    e.eta = index_of(el.eta);
    if (el.kind == Kind::kelvin) e.E = index_of(el.E);
    if (el.kind == Kind::bingham) e.threshold = index_of(el.threshold);
    s.elements.push_back(e);
  }
  if (!ok || s.elements.size() > 8) return std::nullopt;  // evaluate_series holds 8 elements
  for (int u : used)
    if (u != 1) return std::nullopt;
  return s;
}

// ---- The least-squares problem ------------------------------------------------
struct Problem {
  const laws::LawInfo* info = nullptr;
  const CreepData* data = nullptr;
  std::optional<SeriesStructure> structure;
  std::size_t n = 0, np = 0;
  double inv_scale = 1.0;  // residuals are (model - data) / max|data|, so that they are O(1)
  std::vector<double> stage_t, stage_f, flow_before;  // flow_before[k] = sum_{i<k} F_i (t_{i+1} - t_i)
  // Cache: the analytic Jacobian is computed with the residuals, at no extra exp() cost.
  std::vector<double> cached_x, cached_jac;
  std::vector<double> values;  // scratch: exp(x)
  std::vector<double> scratch_f;  // residuals when GSL's f is not contiguous
};

void to_values(const gsl_vector* x, Problem& pr) {
  for (std::size_t k = 0; k < pr.np; ++k)
    pr.values[k] = std::exp(std::clamp(gsl_vector_get(x, k), -700.0, 700.0));
}

// Exact staged response of a series law and its derivatives with respect to
// the log parameters (docs/fitting.md, "What is fitted"):
//   spring   F(t)/E1                                   d/dlnE1 = -F(t)/E1
//   Kelvin   sum_i dF_i/E (1 - e^-r_i), r_i = E (t - t_i)/eta
//            d/dlnE = dF_i/E (r_i e^-r_i - b_i),  d/dlneta = -dF_i/E r_i e^-r_i
//   dashpot  sum_i F_i dt_i/eta                        d/dlneta = -term
//   Bingham  sum_i sign(F_i)<|F_i| - Fs> dt_i/eta      d/dlnFs = -sign(F_i) Fs dt_i/eta
// (the seed's eq. 2 superposed over the stages, eqs. 4-6; laws::exact_displacement).
void evaluate_series(Problem& pr, double* f, double* jac) {
  const auto& s = *pr.structure;
  const auto& data = *pr.data;
  const double* p = pr.values.data();
  const std::size_t np = pr.np;
  const double sc = pr.inv_scale;
  // Per element, once per call: 1/eta, E/eta and 1/E (no division per point),
  // and the sums over the stages before the current one, carried from stage
  // to stage so that a point costs O(1) whatever the number of stages:
  //   Kelvin  S0 = sum_{i<k} dF_i e^-u_i,  S1 = sum_{i<k} dF_i u_i e^-u_i,
  //           u_i = (E/eta)(t_k - t_i); at t in stage k, with v = (E/eta)(t - t_k),
  //           r_i = v + u_i: sum_{i<k} dF_i (1 - e^-r_i) = F_{k-1} - e^-v S0 and
  //           sum_{i<k} dF_i r_i e^-r_i = e^-v (v S0 + S1);
  //           stage k -> k+1 (d = (E/eta)(t_{k+1} - t_k)):
  //           S1 <- e^-d (S1 + d (S0 + dF_k)), S0 <- e^-d (S0 + dF_k);
  //   Bingham G = sum_{i<k} sign(F_i)<|F_i| - Fs> dt_i, D = sum_{i<k, flowing} sign(F_i) dt_i.
  // F_{k-1} - e^-v S0 cancels when every r_i is small, but only to eps |F|/E
  // in absolute terms: rounding of the displacement itself.
  struct Consts {
    double inv_eta, rate, inv_e;
    double s0 = 0.0, s1 = 0.0;  // Kelvin stage sums
    double g = 0.0, d = 0.0;    // Bingham stage sums
  };
  Consts cs[8];
  const std::size_t ne = std::min<std::size_t>(s.elements.size(), 8);
  for (std::size_t m = 0; m < ne; ++m) {
    const auto& el = s.elements[m];
    cs[m].inv_eta = 1.0 / p[el.eta];
    cs[m].rate = el.kind == Kind::kelvin ? p[el.E] / p[el.eta] : 0.0;
    cs[m].inv_e = el.kind == Kind::kelvin ? 1.0 / p[el.E] : 0.0;
  }
  const double inv_e1 = s.spring >= 0 ? 1.0 / p[s.spring] : 0.0;
  for (std::size_t k = 0; k < data.stages.size(); ++k) {
    const auto& stage = data.stages[k];
    const double fk = pr.stage_f[k];
    const double f_before = k > 0 ? pr.stage_f[k - 1] : 0.0;
    const double dfk = fk - f_before;
    const double tk = pr.stage_t[k];
    for (std::size_t j = stage.first; j < stage.first + stage.count; ++j) {
      const double t = data.t[j];
      double model = 0.0;
      double* row = jac + j * np;
      std::fill(row, row + np, 0.0);
      if (s.spring >= 0) {
        const double v = fk * inv_e1;
        model += v;
        row[s.spring] = -v * sc;
      }
      for (std::size_t m = 0; m < ne; ++m) {
        const auto& el = s.elements[m];
        const Consts& c = cs[m];
        if (el.kind == Kind::kelvin) {
          const double v = c.rate * (t - tk);
          // b = 1 - e^-v, through expm1 below v = 0.5 (no cancellation), 1 - exp(-v)
          // above (relative rounding < 2 eps there, and exp is cheaper).
          double b, ev;
          if (v < 0.5) {
            b = -std::expm1(-v);
            ev = 1.0 - b;
          } else {
            ev = std::exp(-v);
            b = 1.0 - ev;
          }
          // Current stage: dF_k (1 - e^-v); earlier ones through S0, S1 (above).
          const double re = dfk * v * ev + ev * (v * c.s0 + c.s1);  // sum dF_i r_i e^-r_i
          const double bb = dfk * b + (f_before - ev * c.s0);       // sum dF_i (1 - e^-r_i)
          model += c.inv_e * bb;
          row[el.E] += c.inv_e * (re - bb) * sc;  // d/dlnE = sum dF_i/E (r_i e^-r_i - b_i)
          row[el.eta] -= c.inv_e * re * sc;       // d/dln eta = -sum dF_i/E r_i e^-r_i
        } else if (el.kind == Kind::dashpot) {
          const double g = (pr.flow_before[k] + fk * (t - tk)) * c.inv_eta;
          model += g;
          row[el.eta] -= g * sc;
        } else {  // Bingham
          const double fs = p[el.threshold];
          double g = c.g, d = c.d;
          if (std::abs(fk) > fs) {
            const double sign = fk > 0.0 ? 1.0 : -1.0;
            g += (fk - sign * fs) * (t - tk);
            d += sign * (t - tk);
          }
          model += g * c.inv_eta;
          row[el.eta] -= g * c.inv_eta * sc;
          row[el.threshold] -= fs * d * c.inv_eta * sc;
        }
      }
      f[j] = (model - data.displacement[j]) * sc;
    }
    if (k + 1 < data.stages.size()) {  // carry the stage sums to stage k+1
      const double dt = pr.stage_t[k + 1] - tk;
      for (std::size_t m = 0; m < ne; ++m) {
        const auto& el = s.elements[m];
        Consts& c = cs[m];
        if (el.kind == Kind::kelvin) {
          const double d = c.rate * dt, e = std::exp(-d);
          c.s1 = e * (c.s1 + d * (c.s0 + dfk));
          c.s0 = e * (c.s0 + dfk);
        } else if (el.kind == Kind::bingham) {
          const double fs = p[el.threshold];
          if (std::abs(fk) > fs) {
            const double sign = fk > 0.0 ? 1.0 : -1.0;
            c.g += (fk - sign * fs) * dt;
            c.d += sign * dt;
          }
        }
      }
    }
  }
}

// Any other registered law: build it and use laws::exact_displacement.
bool evaluate_generic(Problem& pr, double* f) {
  laws::ParameterValues v;
  for (std::size_t k = 0; k < pr.np; ++k) v[pr.info->parameters[k].name] = pr.values[k];
  std::unique_ptr<laws::ContactRheology> law;
  try {
    law = pr.info->make(laws::validate_parameters(pr.info->name, pr.info->parameters, v));
  } catch (const std::exception&) {
    return false;
  }
  for (std::size_t j = 0; j < pr.n; ++j) {
    const auto d = laws::exact_displacement(*law, pr.data->history, pr.data->t[j]);
    if (!d) return false;
    f[j] = (*d - pr.data->displacement[j]) * pr.inv_scale;
  }
  return true;
}

// A residual that is not finite (parameters far out) becomes a large finite
// one, so the trust region rejects the step instead of failing.
void sanitize(double* f, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j)
    if (!std::isfinite(f[j])) f[j] = 1e100;
}

int residual_cb(const gsl_vector* x, void* params, gsl_vector* f) {
  auto& pr = *static_cast<Problem*>(params);
  to_values(x, pr);
  // GSL's finite-difference Jacobian passes a column of J (stride p): work in
  // a contiguous buffer then unless f is contiguous.
  double* out = f->stride == 1 ? f->data : (pr.scratch_f.resize(pr.n), pr.scratch_f.data());
  if (pr.structure) {
    evaluate_series(pr, out, pr.cached_jac.data());
    for (std::size_t k = 0; k < pr.np; ++k) pr.cached_x[k] = gsl_vector_get(x, k);
  } else if (!evaluate_generic(pr, out)) {
    std::fill(out, out + pr.n, 1e100);
  }
  sanitize(out, pr.n);
  if (out != f->data)
    for (std::size_t j = 0; j < pr.n; ++j) gsl_vector_set(f, j, out[j]);
  return GSL_SUCCESS;
}

int jacobian_cb(const gsl_vector* x, void* params, gsl_matrix* jac) {
  auto& pr = *static_cast<Problem*>(params);
  bool same = true;
  for (std::size_t k = 0; k < pr.np; ++k) same = same && pr.cached_x[k] == gsl_vector_get(x, k);
  if (!same) {
    std::vector<double> f(pr.n);
    to_values(x, pr);
    evaluate_series(pr, f.data(), pr.cached_jac.data());
    for (std::size_t k = 0; k < pr.np; ++k) pr.cached_x[k] = gsl_vector_get(x, k);
  }
  for (std::size_t j = 0; j < pr.n; ++j) {
    const double* src = pr.cached_jac.data() + j * pr.np;
    double* dst = jac->data + j * jac->tda;
    for (std::size_t k = 0; k < pr.np; ++k) dst[k] = std::isfinite(src[k]) ? src[k] : 0.0;
  }
  return GSL_SUCCESS;
}

// ---- Starting values from the curve itself ----------------------------------
struct CurveFeatures {
  double df = 0.0;     // stress step of the analysed stage [stress]
  double c0 = 0.0;     // compliance at the first point (instantaneous jump) [length/stress]
  double slope = 0.0;  // late compliance rate [length/(stress*time)]
  double intercept = 0.0;  // late line extrapolated to the stage start [length/stress]
  double c_last = 0.0, c_max = 0.0;
  double duration = 0.0;   // of the stage [time]
  double t63 = 0.0;        // time to 63% of the transient [time]
  double f_max = 0.0;      // largest |stress| [stress]
};

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

struct ErrorHandlerOff {
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  ~ErrorHandlerOff() { gsl_set_error_handler(old); }
};

struct GslFree {
  void operator()(gsl_multifit_nlinear_workspace* w) const { gsl_multifit_nlinear_free(w); }
  void operator()(gsl_vector* v) const { gsl_vector_free(v); }
  void operator()(gsl_matrix* m) const { gsl_matrix_free(m); }
};

std::string fmt_g(double v) { return fmt::format("{:.4g}", v); }

// ---- The nonlinear polish (GSL) on one data set -------------------------------
// Every stride-th point of each stage (its first and last always), at most
// about max_points in all: the data the reference starts run on for long records.
CreepData subsample(const CreepData& d, std::size_t max_points) {
  const std::size_t n = d.t.size();
  const std::size_t stride = (n + max_points - 1) / max_points;
  CreepData s;
  s.source = d.source;
  s.history = d.history;
  s.time_column = d.time_column;
  s.displacement_column = d.displacement_column;
  s.stress_column = d.stress_column;
  for (const auto& st : d.stages) {
    StageInfo si{st.t, st.stress, s.t.size(), 0};
    for (std::size_t j = st.first; j < st.first + st.count; ++j)
      if ((j - st.first) % stride == 0 || j + 1 == st.first + st.count) {
        s.t.push_back(d.t[j]);
        s.displacement.push_back(d.displacement[j]);
        s.line.push_back(j < d.line.size() ? d.line[j] : 0);
      }
    si.count = s.t.size() - si.first;
    s.stages.push_back(si);
  }
  return s;
}

// GSL's trust-region solver (Levenberg-Marquardt steps, modified Cholesky)
// set up for one data set; not copyable (GSL holds a pointer to the problem).
class Solver {
 public:
  Problem pr;

  Solver(const laws::LawInfo& info, const CreepData& data, const std::optional<SeriesStructure>& structure,
         double inv_scale) {
    const std::size_t n = data.t.size(), np = info.parameters.size();
    pr.info = &info;
    pr.data = &data;
    pr.structure = structure;
    pr.n = n;
    pr.np = np;
    pr.inv_scale = inv_scale;
    pr.values.resize(np);
    pr.cached_x.assign(np, std::numeric_limits<double>::quiet_NaN());
    pr.cached_jac.assign(n * np, 0.0);
    double flow = 0.0;
    for (std::size_t k = 0; k < data.stages.size(); ++k) {
      pr.stage_t.push_back(data.stages[k].t);
      pr.stage_f.push_back(data.stages[k].stress);
      pr.flow_before.push_back(flow);
      if (k + 1 < data.stages.size())
        flow += data.stages[k].stress * (data.stages[k + 1].t - data.stages[k].t);
    }
    fdf_.f = residual_cb;
    fdf_.df = pr.structure ? jacobian_cb : nullptr;  // nullptr: GSL's finite differences
    fdf_.fvv = nullptr;
    fdf_.n = n;
    fdf_.p = np;
    fdf_.params = &pr;
    gsl_multifit_nlinear_parameters params = gsl_multifit_nlinear_default_parameters();
    params.trs = gsl_multifit_nlinear_trs_lm;
    // Modified Cholesky on the normal equations: a quarter faster than QR here,
    // and robust when a parameter is unidentifiable (J^T J near singular). The
    // covariance comes from an SVD of J (identify()).
    params.solver = gsl_multifit_nlinear_solver_mcholesky;
    w_.reset(gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, np));
    x_.reset(gsl_vector_alloc(np));
    fv_.reset(gsl_vector_alloc(n));
  }
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  struct Outcome {
    double rss = std::numeric_limits<double>::infinity();  // scaled
    std::vector<double> position;                           // log parameters
    int status = GSL_FAILURE;
    int iterations = 0;
  };

  // From `start` (log parameters): the loop of gsl_multifit_nlinear_driver
  // (step tolerance 1e-10 on the log parameters), except that it stops as soon
  // as the sum of squares reaches stop_at (relative 1e-7, within the 1e-6 at
  // which starts count as agreeing; stop_at < 0: never): the start has found
  // that minimum. With `refine`, the linear part is then
  // re-solved exactly at the polished retardation times (varpro_refine):
  // GSL stops near, not on, a threshold equal to a stress level.
  Outcome polish(const std::vector<double>& start, double stop_at, double floor, const FitOptions& options,
                 bool refine) {
    const std::size_t np = pr.np;
    for (std::size_t k = 0; k < np; ++k) gsl_vector_set(x_.get(), k, start[k]);
    gsl_multifit_nlinear_init(x_.get(), &fdf_, w_.get());
    auto rss_now = [&] {
      const gsl_vector* f = w_->f;  // contiguous: allocated by GSL
      double c = 0.0;
      for (std::size_t j = 0; j < f->size; ++j) c += f->data[j] * f->data[j];
      return c;
    };
    // gsl_multifit_nlinear_test(xtol = 1e-10, gtol = 1e-15) (GSL's
    // multifit_nlinear/convergence.c) with ||f||^2 summed here once for this
    // test and the stop_at one, instead of by the reference CBLAS dnrm2:
    //   (1) |dx_i| <= xtol |x_i| + xtol^2 for all i;
    //   (2) max_i |g_i max(x_i, 1)| <= gtol max(||f||^2/2, 1).
    auto converged = [&](double rss) {
      const gsl_vector *x = w_->x, *dx = w_->dx, *g = w_->g;
      bool small_step = true;
      double gnorm = 0.0;
      for (std::size_t k = 0; k < np; ++k) {
        const double xk = gsl_vector_get(x, k);
        small_step = small_step && std::abs(gsl_vector_get(dx, k)) <= 1e-10 * std::abs(xk) + 1e-20;
        gnorm = std::max(gnorm, std::abs(std::max(xk, 1.0) * gsl_vector_get(g, k)));
      }
      return small_step || gnorm <= 1e-15 * std::max(0.5 * rss, 1.0);
    };
    int status = GSL_CONTINUE;
    for (int iter = 0; iter < options.max_iterations && status == GSL_CONTINUE; ++iter) {
      const int step = gsl_multifit_nlinear_iterate(w_.get());
      if (step == GSL_ENOPROG && iter == 0) {
        status = GSL_ENOPROG;
        break;
      }
      const double rss = rss_now();
      if (converged(rss) || (stop_at >= 0 && rss <= stop_at * (1.0 + 1e-7) + floor)) status = GSL_SUCCESS;
    }
    if (status == GSL_CONTINUE) status = GSL_EMAXITER;
    Outcome o;
    o.rss = rss_now();
    o.status = status;
    o.iterations = static_cast<int>(gsl_multifit_nlinear_niter(w_.get()));
    const gsl_vector* xs = gsl_multifit_nlinear_position(w_.get());
    o.position.resize(np);
    for (std::size_t k = 0; k < np; ++k) o.position[k] = gsl_vector_get(xs, k);
    if (refine && pr.structure) {
      std::vector<double> v(np);
      for (std::size_t k = 0; k < np; ++k) v[k] = std::exp(o.position[k]);
      if (detail::varpro_refine(*pr.structure, *pr.data, pr.inv_scale, v)) {
        for (std::size_t k = 0; k < np; ++k) gsl_vector_set(x_.get(), k, std::log(v[k]));
        residual_cb(x_.get(), &pr, fv_.get());
        double c = 0.0;
        gsl_blas_ddot(fv_.get(), fv_.get(), &c);
        if (c < o.rss) {
          o.rss = c;
          for (std::size_t k = 0; k < np; ++k) o.position[k] = std::log(v[k]);
        }
      }
    }
    return o;
  }

  // The workspace initialised at `position` (log parameters): residuals and Jacobian there.
  gsl_multifit_nlinear_workspace* at(const std::vector<double>& position) {
    for (std::size_t k = 0; k < pr.np; ++k) gsl_vector_set(x_.get(), k, position[k]);
    gsl_multifit_nlinear_init(x_.get(), &fdf_, w_.get());
    return w_.get();
  }

 private:
  gsl_multifit_nlinear_fdf fdf_{};
  std::unique_ptr<gsl_multifit_nlinear_workspace, GslFree> w_;
  std::unique_ptr<gsl_vector, GslFree> x_, fv_;
};

// ---- Identifiability: what the data fix and what they do not ----------------
// A combination of parameters whose value the data may fix when its parts are
// not identifiable: value q and gradient dq/dln p.
struct Candidate {
  std::string expression, unit;
  double value = 0.0;
  std::vector<double> grad;
};

// The combinations that a series law's curve can depend on when single
// parameters drop out (docs/fitting.md, "Identifiability"):
//   (L - Fs)/eta3 for each stress level L > Fs [length/time]: the Bingham rate under L
//     (d/dln eta3 = -q, d/dln Fs = -Fs/eta3);
//   1/E1 + 1/E (spring and a fast Kelvin element merge into one jump), 1/E2 + 1/E3
//     (two Kelvin elements with close retardation times) [length/stress] (d/dln E = -1/E);
//   1/eta1 + 1/eta (a slow Kelvin element acting as a dashpot) [length/(stress*time)];
//   eta/E, the retardation time [time] (d/dln eta = q, d/dln E = -q).
std::vector<Candidate> combination_candidates(const SeriesStructure& s,
                                              const std::vector<ParameterEstimate>& p,
                                              const CreepData& data) {
  const std::size_t np = p.size();
  std::vector<Candidate> out;
  std::vector<const Element*> kelvins;
  const Element* dashpot = nullptr;
  for (const auto& el : s.elements) {
    if (el.kind == Kind::kelvin) kelvins.push_back(&el);
    if (el.kind == Kind::dashpot) dashpot = &el;
    if (el.kind == Kind::bingham) {
      const double eta = p[el.eta].value, fs = p[el.threshold].value;
      std::vector<double> levels;
      for (const auto& st : data.stages)
        if (std::abs(st.stress) > fs) levels.push_back(std::abs(st.stress));
      std::sort(levels.begin(), levels.end());
      levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
      for (double level : levels) {
        Candidate c;
        c.expression = fmt::format("({:g} - {})/{}", level, p[el.threshold].name, p[el.eta].name);
        c.unit = "length/time";
        c.value = (level - fs) / eta;
        c.grad.assign(np, 0.0);
        c.grad[el.eta] = -c.value;
        c.grad[el.threshold] = -fs / eta;
        out.push_back(std::move(c));
      }
    }
  }
  auto inverse_sum = [&](const std::vector<int>& idx, const char* unit) {
    Candidate c;
    c.unit = unit;
    c.grad.assign(np, 0.0);
    for (int k : idx) {
      c.expression += (c.expression.empty() ? "1/" : " + 1/") + p[k].name;
      c.value += 1.0 / p[k].value;
      c.grad[k] = -1.0 / p[k].value;
    }
    out.push_back(std::move(c));
  };
  for (const auto* el : kelvins) {
    if (s.spring >= 0) inverse_sum({s.spring, el->E}, "length/stress");
    if (dashpot) inverse_sum({dashpot->eta, el->eta}, "length/(stress*time)");
  }
  if (kelvins.size() == 2) {
    inverse_sum({kelvins[0]->E, kelvins[1]->E}, "length/stress");
    if (s.spring >= 0) inverse_sum({s.spring, kelvins[0]->E, kelvins[1]->E}, "length/stress");
  }
  for (const auto* el : kelvins) {
    Candidate c;
    c.expression = p[el->eta].name + "/" + p[el->E].name;
    c.unit = "time";
    c.value = p[el->eta].value / p[el->E].value;
    c.grad.assign(np, 0.0);
    c.grad[el->eta] = c.value;
    c.grad[el->E] = -c.value;
    out.push_back(std::move(c));
  }
  return out;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

// Singular value decomposition of the Jacobian J of the scaled residuals with
// respect to the log parameters (GSL, one-sided Jacobi after QR for n >> p):
// J = U S V^T. With s the residual standard deviation, the standard error of
// ln p along direction v_i is s/S_i. A direction with S_i below
// null_tolerance * S_max is one the curve does not depend on: every parameter
// with a weight |v_ki| >= 1e-3 in it is not identifiable. A direction with
// s/S_i > relative_error_limit (ln p free by more than that) flags every
// parameter with a weight >= 0.1. The covariance of ln p is
// C = sum over the other directions of v_i v_i^T (s/S_i)^2: the pseudo-inverse
// of J^T J / s^2 (Golub & Van Loan, Matrix Computations, 4th ed., sec. 5.5),
// so no standard error is conditioned on a dropped partner. J is overwritten.
void identify(FitResult& res, gsl_matrix* jac, double s, const std::vector<Candidate>& candidates,
              const FitOptions& options, std::vector<double>& cov) {
  const std::size_t np = res.parameters.size();
  std::unique_ptr<gsl_matrix, GslFree> V(gsl_matrix_alloc(np, np)), X(gsl_matrix_alloc(np, np));
  std::unique_ptr<gsl_vector, GslFree> S(gsl_vector_alloc(np)), work(gsl_vector_alloc(np));
  for (std::size_t i = 0; i < jac->size1 * jac->tda; ++i)
    if (!std::isfinite(jac->data[i])) jac->data[i] = 0.0;
  gsl_linalg_SV_decomp_mod(jac, X.get(), V.get(), S.get(), work.get());
  double smax = 0.0;
  for (std::size_t i = 0; i < np; ++i) smax = std::max(smax, gsl_vector_get(S.get(), i));
  std::vector<char> null(np), weak(np);
  for (std::size_t i = 0; i < np; ++i) {
    const double si = gsl_vector_get(S.get(), i);
    null[i] = !(si > options.null_tolerance * smax);
    weak[i] = !null[i] && s > 0 && s / si > options.relative_error_limit;
    res.singular_values.push_back(s > 0 ? si / s : std::numeric_limits<double>::infinity());
  }
  cov.assign(np * np, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    if (null[i]) continue;
    const double w = s / gsl_vector_get(S.get(), i);
    for (std::size_t a = 0; a < np; ++a)
      for (std::size_t b = 0; b < np; ++b)
        cov[a * np + b] += gsl_matrix_get(V.get(), a, i) * gsl_matrix_get(V.get(), b, i) * w * w;
  }
  // Groups of flagged parameters: those sharing a direction the data do not fix.
  std::vector<int> group(np, -1);
  struct Group {
    std::vector<std::size_t> params;
    bool null = false;
    double worst = 0.0;  // largest s/S_i among its weak directions
  };
  std::vector<Group> groups;
  for (std::size_t i = 0; i < np; ++i) {
    if (!null[i] && !weak[i]) continue;
    std::vector<std::size_t> members;
    for (std::size_t k = 0; k < np; ++k)
      if (std::abs(gsl_matrix_get(V.get(), k, i)) >= (null[i] ? 1e-3 : 0.1)) members.push_back(k);
    int g = -1;
    for (std::size_t k : members)
      if (group[k] >= 0) g = group[k];
    if (g < 0) {
      g = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    for (std::size_t k : members) {
      if (group[k] >= 0 && group[k] != g) {  // merge the other group into g
        const int other = group[k];
        for (std::size_t m : groups[other].params) {
          group[m] = g;
          groups[g].params.push_back(m);
        }
        groups[g].null = groups[g].null || groups[other].null;
        groups[g].worst = std::max(groups[g].worst, groups[other].worst);
        groups[other].params.clear();
      } else if (group[k] < 0) {
        group[k] = g;
        groups[g].params.push_back(k);
      }
    }
    groups[g].null = groups[g].null || null[i];
    if (weak[i]) groups[g].worst = std::max(groups[g].worst, s / gsl_vector_get(S.get(), i));
  }
  for (std::size_t k = 0; k < np; ++k) {
    auto& e = res.parameters[k];
    e.identifiable = group[k] < 0;
    const double var = cov[k * np + k];
    e.std_error = e.identifiable ? e.value * std::sqrt(var) : 0.0;  // delta method: dp = p dln p
  }
  // Combinations the data fix: no component along a direction the curve does
  // not depend on, relative standard error within the limit, and a part that
  // is not identifiable on its own.
  for (const auto& c : candidates) {
    double norm = 0.0;
    for (double g : c.grad) norm += g * g;
    norm = std::sqrt(norm);
    if (!(norm > 0) || !(c.value > 0)) continue;
    bool involves = false;
    for (std::size_t k = 0; k < np; ++k)
      involves = involves || (group[k] >= 0 && std::abs(c.grad[k]) >= 0.01 * norm);
    if (!involves) continue;
    bool fixed = true;
    for (std::size_t i = 0; i < np && fixed; ++i) {
      if (!null[i]) continue;
      double along = 0.0;
      for (std::size_t k = 0; k < np; ++k) along += gsl_matrix_get(V.get(), k, i) * c.grad[k];
      fixed = std::abs(along) <= 1e-4 * norm;
    }
    double var = 0.0;
    for (std::size_t a = 0; a < np; ++a)
      for (std::size_t b = 0; b < np; ++b) var += c.grad[a] * cov[a * np + b] * c.grad[b];
    const double se = std::sqrt(std::max(var, 0.0));
    if (!fixed || !(se <= options.relative_error_limit * c.value)) continue;
    FixedCombination f;
    f.expression = c.expression;
    f.unit = c.unit;
    f.value = c.value;
    f.std_error = se;
    for (std::size_t k = 0; k < np; ++k)
      if (c.grad[k] != 0.0) f.parameters.push_back(res.parameters[k].name);
    res.combinations.push_back(std::move(f));
  }
  for (const auto& g : groups) {
    if (g.params.empty()) continue;
    std::vector<std::string> names;
    for (std::size_t k : g.params) names.push_back(res.parameters[k].name);
    const bool one = names.size() == 1;
    std::string reason;
    if (g.null && one)
      reason = "the curve does not depend on it at the fitted values (its element adds nothing "
               "measurable, or acts as part of another)";
    else if (g.null)
      reason = fmt::format("the curve depends on {} only through a combination of them", join_names(names));
    else
      reason = fmt::format("the data leave {} free by more than a factor e (standard error of the "
                           "log {:.3g} along a direction of the parameters)",
                           one ? "it" : "them together", g.worst);
    for (std::size_t k : g.params) res.parameters[k].reason = reason;
    std::string fixed;
    for (const auto& f : res.combinations) {
      bool shares = false;
      for (const auto& n : f.parameters)
        shares = shares || std::find(names.begin(), names.end(), n) != names.end();
      if (shares)
        fixed += fmt::format("{}{} = {:.4g} +- {:.2g}", fixed.empty() ? "; the data fix " : ", ",
                             f.expression, f.value, f.std_error);
    }
    res.warnings.push_back(fmt::format("{} {} not identifiable: {}{}; no standard error is given for {}",
                                       join_names(names), one ? "is" : "are", reason, fixed,
                                       one ? "it" : "them"));
  }
}

}  // namespace

FitResult fit_law(const laws::LawInfo& info, const CreepData& data, const FitOptions& options) {
  if (!info.fittable)
    throw FitError(info.name, fmt::format("law '{}' cannot be fitted yet: its creep is nonlinear in the "
                                          "stress (docs/laws.md, \"Nonlinear laws\"); compare it with the "
                                          "data through `rheodda law curve {}`",
                                          info.name, info.name));
  const ErrorHandlerOff handler_off;
  const std::size_t n = data.t.size(), np = info.parameters.size();
  for (const auto& spec : info.parameters)
    if (spec.min < 0.0)
      throw FitError(info.name, fmt::format("law '{}': parameter {} may be negative (range {}); fits "
                                            "work on positive parameters only",
                                            info.name, spec.name, spec.range_text()));
  if (n < np + 1)
    throw FitError(info.name,
                   fmt::format("{}: too few points for law '{}': {} parameters need at least {} "
                               "points, the data has {}",
                               data.source, info.name, np, np + 1, n));
  // CreepData built in code (not by parse_creep_csv) must hold the same invariants.
  std::size_t covered = 0;
  for (const auto& s : data.stages) {
    if (s.count == 0 || s.first != covered)
      throw FitError(info.name, fmt::format("{}: stage at t = {:g} has no data points", data.source, s.t));
    covered += s.count;
  }
  if (covered != n || data.displacement.size() != n || data.stages.empty())
    throw FitError(info.name, fmt::format("{}: the stages do not cover the {} data points", data.source, n));
  bool loaded = false;
  for (const auto& s : data.stages) loaded = loaded || s.stress != 0.0;
  if (!loaded)
    throw FitError(info.name, fmt::format("{}: the applied stress is zero in every stage; nothing "
                                          "to fit", data.source));
  double dmax = 0.0, mean = 0.0;
  for (double d : data.displacement) {
    dmax = std::max(dmax, std::abs(d));
    mean += d / static_cast<double>(n);
  }
  if (dmax == 0.0)
    throw FitError(info.name,
                   fmt::format("{}: the displacement is zero everywhere; nothing to fit", data.source));

  const std::optional<SeriesStructure> structure = probe_structure(info);
  Solver full(info, data, structure, 1.0 / dmax);
  Problem& pr = full.pr;

  const CurveFeatures features = analyse_curve(data);
  const std::vector<double> base = pr.structure ? series_start(*pr.structure, np, features)
                                                : generic_start(info, features);
  // The exact re-solve after the polish matters where GSL cannot settle: on a
  // kink of the curve in the threshold (a Bingham element). Elsewhere GSL's
  // minimum is the exact linear solution already (step tolerance 1e-10).
  bool has_bingham = false;
  if (pr.structure)
    for (const auto& el : pr.structure->elements) has_bingham = has_bingham || el.kind == Kind::bingham;
  const bool refine = options.structured_search && has_bingham;
  const bool structured_search = pr.structure && options.structured_search;

  // Sums of squares closer than `floor` are the same: a scaled residual of
  // 1e-10 rms (1e-10 of the largest displacement) is rounding, not fit.
  const double floor = static_cast<double>(n) * 1e-20;
  std::vector<double> best_x(np);
  double best_rss = std::numeric_limits<double>::infinity();
  double structured_rss = std::numeric_limits<double>::infinity();
  int best_iter = 0, best_status = GSL_FAILURE, structured = 0, starts_total = 0, agreeing_sample = 0;
  std::vector<double> rss_full;  // final RSS of the starts run on all points
  bool reference_lower = false;  // a classic start found a lower minimum than the structured search
  auto consider = [&](const Solver::Outcome& o, bool first) {
    // A later start must improve by more than rounding.
    if (std::isfinite(o.rss) && (first || o.rss < best_rss * (1.0 - 1e-9) - floor)) {
      best_rss = o.rss;
      best_iter = o.iterations;
      best_status = o.status;
      best_x = o.position;
      return true;
    }
    return false;
  };
  auto logs = [](const std::vector<double>& v) {
    std::vector<double> l(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) l[k] = std::log(v[k]);
    return l;
  };

  // 1. The starts of the variable-projection search (varpro.hpp), polished on all points.
  if (structured_search) {
    detail::VarProSettings vs;
    vs.per_decade = std::max(options.grid_per_decade, 1);
    for (auto& v : detail::varpro_starts(*pr.structure, np, data, pr.inv_scale, vs)) {
      const auto o = full.polish(logs(v.values), starts_total > 0 ? best_rss : -1.0, floor, options, refine);
      consider(o, starts_total == 0);
      ++starts_total;
      ++structured;
      rss_full.push_back(o.rss);
      if (std::isfinite(o.rss)) structured_rss = std::min(structured_rss, o.rss);
    }
  }
  // 2. The classic starts (the curve-derived one and `restarts` variations of
  // it): a reference. On more than kReferencePoints points they run on an even
  // subsample (every stride-th point of each stage, about kReferenceSample in
  // all), against the best minimum polished on that subsample; a start that
  // finds a lower one there is then polished on all points. (A 100-point
  // subsample of the 201-point staged Nishihara curves of docs/fitting.md missed
  // the reference's minimum in 10 of 300 draws; 200 points of 1 000 keep a
  // Burgers fit within 1 ms, bench/fit_bench.)
  const int classic = 1 + std::max(options.restarts, 0);
  std::vector<std::vector<double>> classic_starts;
  for (int r = 0; r < classic; ++r)
    classic_starts.push_back(logs(r == 0 ? base : restart_start(base, pr.structure, r, features.f_max)));
  constexpr std::size_t kReferencePoints = 500, kReferenceSample = 200;
  if (structured > 0 && std::isfinite(best_rss) && n > kReferencePoints) {
    const CreepData sub = subsample(data, kReferenceSample);
    Solver small(info, sub, structure, 1.0 / dmax);
    const double floor_sub = static_cast<double>(sub.t.size()) * 1e-20;
    const double level = small.polish(best_x, -1.0, floor_sub, options, refine).rss;
    for (const auto& start : classic_starts) {
      const auto o = small.polish(start, level, floor_sub, options, refine);
      ++starts_total;
      if (std::abs(o.rss - level) <= 1e-6 * level + floor_sub) ++agreeing_sample;
      else if (o.rss < level * (1.0 - 1e-6) - floor_sub) {
        const auto o2 = full.polish(o.position, -1.0, floor, options, refine);
        rss_full.push_back(o2.rss);
        reference_lower = consider(o2, false) || reference_lower;
      }
    }
  } else {
    for (const auto& start : classic_starts) {
      const auto o = full.polish(start, starts_total > 0 ? best_rss : -1.0, floor, options, refine);
      rss_full.push_back(o.rss);
      const bool lower = consider(o, starts_total == 0);
      reference_lower = reference_lower || (lower && structured > 0);
      ++starts_total;
    }
  }
  if (!std::isfinite(best_rss))
    throw FitError(info.name, fmt::format("law '{}': no start gave a finite fit", info.name));

  // Kelvin elements in series are interchangeable; report them ordered by
  // retardation time eta/E, shortest first (E2, eta2 the fast one), so the
  // labels do not depend on which start won.
  if (pr.structure) {
    std::vector<const Element*> kelvins;
    for (const auto& el : pr.structure->elements)
      if (el.kind == Kind::kelvin) kelvins.push_back(&el);
    std::vector<std::pair<double, double>> pairs;  // (ln E, ln eta)
    for (const auto* el : kelvins) pairs.emplace_back(best_x[el->E], best_x[el->eta]);
    std::stable_sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
      return a.second - a.first < b.second - b.first;
    });
    for (std::size_t i = 0; i < kelvins.size(); ++i) {
      best_x[kelvins[i]->E] = pairs[i].first;
      best_x[kelvins[i]->eta] = pairs[i].second;
    }
  }

  // The model saw exp(clamp(x, -700, 700)) (to_values): report that.
  for (double& v : best_x) v = std::clamp(v, -700.0, 700.0);
  // Residuals and Jacobian at the best point.
  gsl_multifit_nlinear_workspace* w = full.at(best_x);
  std::vector<double> fitted_scaled(gsl_multifit_nlinear_residual(w)->data,
                                    gsl_multifit_nlinear_residual(w)->data + n);

  FitResult res;
  res.law = info.name;
  res.points = n;
  res.starts = starts_total;
  res.structured_starts = structured;
  res.iterations = best_iter;
  res.converged = best_status == GSL_SUCCESS || best_status == GSL_ENOPROG;
  const double scale = dmax;
  res.rss = best_rss * scale * scale;
  double tss = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    res.fitted.push_back(data.displacement[j] + fitted_scaled[j] * scale);
    tss += (data.displacement[j] - mean) * (data.displacement[j] - mean);
  }
  // R^2 = 1 - RSS/TSS is undefined when the data have no spread: TSS at the
  // level of rounding (rms spread below 1e-10 of the largest displacement).
  const double nd = static_cast<double>(n), k = static_cast<double>(np);
  res.r2 = tss > nd * (1e-10 * dmax) * (1e-10 * dmax) ? 1.0 - res.rss / tss
                                                      : std::numeric_limits<double>::quiet_NaN();
  res.rmse = std::sqrt(res.rss / nd);
  const double log_mse = std::log(std::max(res.rss / nd, std::numeric_limits<double>::min()));
  res.aic = nd * log_mse + 2.0 * k;
  res.bic = nd * log_mse + k * std::log(nd);
  res.starts_agreeing = agreeing_sample;
  for (double rs : rss_full) res.starts_agreeing += std::abs(rs - best_rss) <= 1e-6 * best_rss + floor;

  // Is the minimum certain? (docs/fitting.md, "When the minimum is not certain")
  if (structured > 0 && (reference_lower || best_rss < structured_rss * (1.0 - 1e-6) - floor)) {
    res.minimum_certain = false;
    res.minimum_note = fmt::format(
        "the multi-start reference found a lower sum of squares than the variable-projection "
        "search (RSS {:.6g} < {:.6g}): other minima may exist",
        res.rss, structured_rss * scale * scale);
  } else if (res.starts_agreeing < 2) {
    res.minimum_certain = false;
    res.minimum_note = res.starts > 1 ? fmt::format("it was reached from one start only (of {})", res.starts)
                                      : std::string("only one start was tried");
  }

  auto& warn = res.warnings;
  if (!res.converged)
    warn.push_back(fmt::format("the fit stopped before converging ({}, {} iterations)",
                               gsl_strerror(best_status), best_iter));
  if (!res.minimum_certain)
    warn.push_back(fmt::format("the minimum is not certain: {}; try --restarts 20", res.minimum_note));

  for (std::size_t i = 0; i < np; ++i) {
    ParameterEstimate e;
    e.name = info.parameters[i].name;
    e.unit = info.parameters[i].unit;
    e.value = std::exp(best_x[i]);
    res.parameters.push_back(e);
  }
  // Identifiability and standard errors from the SVD of the Jacobian (identify()).
  std::vector<double> cov;
  {
    const gsl_matrix* J = gsl_multifit_nlinear_jac(w);
    std::unique_ptr<gsl_matrix, GslFree> jc(gsl_matrix_alloc(n, np));
    gsl_matrix_memcpy(jc.get(), J);
    const double s = std::sqrt(best_rss / (nd - k));  // residual standard deviation (scaled)
    const auto candidates = pr.structure ? combination_candidates(*pr.structure, res.parameters, data)
                                         : std::vector<Candidate>{};
    identify(res, jc.get(), s, candidates, options, cov);
  }
  res.correlation.assign(np * np, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t j = 0; j < np; ++j) {
      if (!res.parameters[i].identifiable || !res.parameters[j].identifiable) continue;
      const double d = cov[i * np + i] * cov[j * np + j];
      res.correlation[i * np + j] = i == j ? 1.0 : (d > 0 ? cov[i * np + j] / std::sqrt(d) : 0.0);
    }

  // ---- Warnings: what the data cannot tell ----
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t j = i + 1; j < np; ++j)
      if (res.parameters[i].identifiable && res.parameters[j].identifiable &&
          std::abs(res.correlation_at(i, j)) > options.correlation_limit)
        warn.push_back(fmt::format("{} and {} are strongly correlated (corr = {:.4f}): the data "
                                   "fix a combination of them, not each",
                                   res.parameters[i].name, res.parameters[j].name,
                                   res.correlation_at(i, j)));
  for (const auto& e : res.parameters)
    if (e.identifiable && e.std_error > options.relative_error_limit * e.value)
      warn.push_back(fmt::format("{} is poorly constrained: its standard error is {:.0f}% of its "
                                 "value",
                                 e.name, 100.0 * e.std_error / e.value));
  if (pr.structure) {
    const double duration = data.t.back() - data.stages.front().t;
    double first_step = duration;
    for (std::size_t j = 0; j < n; ++j)
      if (data.t[j] > data.stages.front().t) {
        first_step = data.t[j] - data.stages.front().t;
        break;
      }
    for (const auto& el : pr.structure->elements) {
      const auto& p = res.parameters;
      if (el.kind == Kind::kelvin) {
        const double tau = p[el.eta].value / p[el.E].value;
        if (duration < options.retardation_factor * tau)
          warn.push_back(fmt::format(
              "the test lasts {}, shorter than {} x {}/{} = {}: the Kelvin element has not "
              "settled, so {} and {} trade off with the other parameters",
              fmt_g(duration), fmt_g(options.retardation_factor), p[el.eta].name, p[el.E].name,
              fmt_g(options.retardation_factor * tau), p[el.E].name, p[el.eta].name));
        if (tau < first_step)
          warn.push_back(fmt::format(
              "{}/{} = {} is shorter than the first sampling interval {}: that Kelvin "
              "element acts as part of the instantaneous response",
              p[el.eta].name, p[el.E].name, fmt_g(tau), fmt_g(first_step)));
      } else if (el.kind == Kind::bingham) {
        if (p[el.threshold].value >= features.f_max)
          warn.push_back(fmt::format("the threshold {} = {} is above every applied stress (max {}): "
                                     "{} is not constrained by the data",
                                     p[el.threshold].name, fmt_g(p[el.threshold].value),
                                     fmt_g(features.f_max), p[el.eta].name));
      }
    }
  }
  return res;
}

std::vector<FitResult> fit_all(const laws::LawRegistry& registry, const CreepData& data,
                               Criterion criterion, std::vector<std::string>& skipped,
                               const FitOptions& options) {
  std::vector<FitResult> out;
  for (const auto& info : registry.laws()) {
    try {
      out.push_back(fit_law(info, data, options));
    } catch (const FitError& e) {
      skipped.push_back(fmt::format("{}: {}", info.name, e.what()));
    }
  }
  std::stable_sort(out.begin(), out.end(), [criterion](const FitResult& a, const FitResult& b) {
    return criterion == Criterion::aic ? a.aic < b.aic : a.bic < b.bic;
  });
  return out;
}

}  // namespace rheodda::fit
