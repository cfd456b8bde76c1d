// The nonlinear polish of a fit: GSL's trust-region solver on one data set (gsl_solver.hpp).
#include "gsl_solver.hpp"

#include <gsl/gsl_blas.h>

#include <algorithm>
#include <cmath>

#include "bounded_polish.hpp"
#include "varpro.hpp"

namespace rheodda::fit::detail {

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
  s.sigma_column = d.sigma_column;
  for (const auto& st : d.stages) {
    StageInfo si{st.t, st.stress, s.t.size(), 0};
    for (std::size_t j = st.first; j < st.first + st.count; ++j)
      if ((j - st.first) % stride == 0 || j + 1 == st.first + st.count) {
        s.t.push_back(d.t[j]);
        s.displacement.push_back(d.displacement[j]);
        s.line.push_back(j < d.line.size() ? d.line[j] : 0);
        if (!d.sigma.empty()) s.sigma.push_back(d.sigma[j]);
      }
    si.count = s.t.size() - si.first;
    s.stages.push_back(si);
  }
  return s;
}

// ---- Mapping (gsl_solver.hpp): MINUIT's bound transforms --------------------------
std::vector<double> Mapping::to_full(const double* z) const {
  std::vector<double> out = x;
  for (std::size_t a = 0; a < free.size(); ++a) {
    const double l = lo[a], h = hi[a], za = z[a];
    double v = za;
    if (std::isfinite(l) && std::isfinite(h)) v = l + (std::sin(za) + 1.0) * 0.5 * (h - l);
    else if (std::isfinite(l)) v = l - 1.0 + std::sqrt(za * za + 1.0);
    else if (std::isfinite(h)) v = h + 1.0 - std::sqrt(za * za + 1.0);
    out[free[a]] = v;
  }
  apply_derived(out);
  return out;
}

void Mapping::apply_derived(std::vector<double>& xs) const {
  if (derived.empty()) return;
  std::vector<double> p(xs.size());
  for (const auto& d : derived) {
    for (std::size_t k = 0; k < xs.size(); ++k) p[k] = std::exp(std::clamp(xs[k], -700.0, 700.0));
    const double v = d.e.evaluate(p);
    xs[d.k] = v > 0.0 ? std::log(v) : -700.0;
  }
}

std::vector<double> Mapping::chain(const std::vector<double>& xs) const {
  const std::size_t np = xs.size();
  std::vector<double> D(np * np, 0.0), p(np), g;
  for (std::size_t k = 0; k < np; ++k) {
    D[k * np + k] = 1.0;
    p[k] = std::exp(std::clamp(xs[k], -700.0, 700.0));
  }
  for (const auto& d : derived) {
    const double v = d.e.evaluate(p, &g);
    for (std::size_t j = 0; j < np; ++j) {
      double s = 0.0;
      if (v > 0.0)
        for (std::size_t m = 0; m < np; ++m)
          if (g[m] != 0.0) s += p[m] * g[m] / v * D[m * np + j];
      D[d.k * np + j] = s;
    }
  }
  return D;
}

bool Mapping::bounded() const {
  for (std::size_t a = 0; a < free.size(); ++a)
    if (std::isfinite(lo[a]) || std::isfinite(hi[a])) return true;
  return false;
}

std::vector<double> Mapping::to_free(const std::vector<double>& xs, bool inside) const {
  std::vector<double> z(free.size());
  for (std::size_t a = 0; a < free.size(); ++a) {
    const double l = lo[a], h = hi[a];
    const double margin =
        !inside ? 0.0 : std::isfinite(l) && std::isfinite(h) ? std::min(1e-3 * (h - l), 1e-3) : 1e-3;
    double v = xs[free[a]];
    if (std::isfinite(l)) v = std::max(v, l + margin);
    if (std::isfinite(h)) v = std::min(v, h - margin);
    if (std::isfinite(l) && std::isfinite(h)) z[a] = std::asin(std::clamp(2.0 * (v - l) / (h - l) - 1.0, -1.0, 1.0));
    else if (std::isfinite(l)) z[a] = std::sqrt((v - l + 1.0) * (v - l + 1.0) - 1.0);
    else if (std::isfinite(h)) z[a] = std::sqrt((h - v + 1.0) * (h - v + 1.0) - 1.0);
    else z[a] = v;
  }
  return z;
}

double Mapping::derivative(std::size_t a, double z) const {
  const double l = lo[a], h = hi[a];
  if (std::isfinite(l) && std::isfinite(h)) return std::cos(z) * 0.5 * (h - l);
  if (std::isfinite(l)) return z / std::sqrt(z * z + 1.0);
  if (std::isfinite(h)) return -z / std::sqrt(z * z + 1.0);
  return 1.0;
}

void Solver::set_full(const gsl_vector* z) {
  std::vector<double> zz(z->size);
  for (std::size_t a = 0; a < z->size; ++a) zz[a] = gsl_vector_get(z, a);
  const auto xs = mapping_->to_full(zz.data());
  for (std::size_t k = 0; k < xs.size(); ++k) gsl_vector_set(x_full_.get(), k, xs[k]);
}

int Solver::mapped_residual_cb(const gsl_vector* z, void* params, gsl_vector* f) {
  auto& s = *static_cast<Solver*>(params);
  s.set_full(z);
  return residual_cb(s.x_full_.get(), &s.pr, f);
}

// Chain rule: dr/dz_a = dr/dx_k dx_k/dz_a for free parameter a = parameter k,
// plus sum over the derived parameters m of dr/dx_m dx_m/dx_k dx_k/dz_a.
int Solver::mapped_jacobian_cb(const gsl_vector* z, void* params, gsl_matrix* jac) {
  auto& s = *static_cast<Solver*>(params);
  s.set_full(z);
  jacobian_cb(s.x_full_.get(), &s.pr, s.jac_full_.get());
  const auto& m = *s.mapping_;
  const std::size_t np = s.pr.np;
  std::vector<double> D;
  if (!m.derived.empty()) {
    std::vector<double> xs(np);
    for (std::size_t k = 0; k < np; ++k) xs[k] = gsl_vector_get(s.x_full_.get(), k);
    D = m.chain(xs);
  }
  for (std::size_t a = 0; a < m.free.size(); ++a) {
    const double d = m.derivative(a, gsl_vector_get(z, a));
    const std::size_t k = m.free[a];
    for (std::size_t j = 0; j < s.pr.n; ++j) {
      double v = gsl_matrix_get(s.jac_full_.get(), j, k);
      for (const auto& dv : m.derived) v += gsl_matrix_get(s.jac_full_.get(), j, dv.k) * D[dv.k * np + k];
      gsl_matrix_set(jac, j, a, v * d);
    }
  }
  return GSL_SUCCESS;
}

// ---- Solver (gsl_solver.hpp) ----------------------------------------------------
Solver::Solver(const laws::LawInfo& info, const CreepData& data, const std::optional<SeriesStructure>& structure,
               double inv_scale, std::vector<double> weight, std::optional<Mapping> mapping)
    : mapping_(std::move(mapping)) {
  const std::size_t n = data.t.size(), np = info.parameters.size();
  pr.weight = std::move(weight);
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
  if (mapping_) {
    fdf_.f = mapped_residual_cb;
    fdf_.df = pr.structure ? mapped_jacobian_cb : nullptr;
    fdf_.p = mapping_->free.size();
    fdf_.params = this;
    x_full_.reset(gsl_vector_alloc(np));
    jac_full_.reset(gsl_matrix_alloc(n, np));
  }
  const std::size_t p = fdf_.p;
  gsl_multifit_nlinear_parameters params = gsl_multifit_nlinear_default_parameters();
  params.trs = gsl_multifit_nlinear_trs_lm;
  // Modified Cholesky on the normal equations: a quarter faster than QR here,
  // and robust when a parameter is unidentifiable (J^T J near singular). The
  // covariance comes from an SVD of J (identify()).
  params.solver = gsl_multifit_nlinear_solver_mcholesky;
  w_.reset(gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, p));
  x_.reset(gsl_vector_alloc(p));
  fv_.reset(gsl_vector_alloc(n));
}

// The loop of gsl_multifit_nlinear_driver with an early stop, then varpro_refine (gsl_solver.hpp).
Solver::Outcome Solver::polish(const std::vector<double>& start, double stop_at, double floor,
                               const FitOptions& options, bool refine) {
  const std::size_t np = fdf_.p;  // GSL's parameters: z with a mapping, else the log parameters
  const std::vector<double> z = mapping_ ? mapping_->to_free(start) : start;
  for (std::size_t k = 0; k < np; ++k) gsl_vector_set(x_.get(), k, z[k]);
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
  if (mapping_) {  // no refine: it ignores the mapping
    o.position = mapping_->to_full(o.position.data());
    if (mapping_->bounded()) {  // to the constrained minimum (bounded_polish.hpp)
      const auto b = bounded_polish(*this, o.position, options.max_iterations);
      if (b.rss <= o.rss) o.position = b.x, o.rss = b.rss;
      o.iterations += b.iterations;
      o.status = b.optimal ? GSL_SUCCESS : GSL_EMAXITER;
    }
    return o;
  }
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

gsl_multifit_nlinear_workspace* Solver::at(const std::vector<double>& position) {
  const std::vector<double> z = mapping_ ? mapping_->to_free(position, false) : position;
  for (std::size_t k = 0; k < fdf_.p; ++k) gsl_vector_set(x_.get(), k, z[k]);
  gsl_multifit_nlinear_init(x_.get(), &fdf_, w_.get());
  return w_.get();
}

}  // namespace rheodda::fit::detail
