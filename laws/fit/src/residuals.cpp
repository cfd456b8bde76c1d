// Residuals of a fit and their Jacobian (residuals.hpp; docs/guide/fitting.md, "What is fitted").
#include "residuals.hpp"

#include <gsl/gsl_errno.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>

namespace rheodda::fit::detail {

namespace {

void to_values(const gsl_vector* x, Problem& pr) {
  for (std::size_t k = 0; k < pr.np; ++k)
    pr.values[k] = std::exp(std::clamp(gsl_vector_get(x, k), -700.0, 700.0));
}

// Exact staged response of a series law and its derivatives with respect to
// the log parameters (docs/guide/fitting.md, "What is fitted"):
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

}  // namespace

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
  if (!pr.weight.empty())
    for (std::size_t j = 0; j < pr.n; ++j) out[j] *= pr.weight[j];
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
    const double w = pr.weight.empty() ? 1.0 : pr.weight[j];
    for (std::size_t k = 0; k < pr.np; ++k) dst[k] = std::isfinite(src[k]) ? src[k] * w : 0.0;
  }
  return GSL_SUCCESS;
}

}  // namespace rheodda::fit::detail
