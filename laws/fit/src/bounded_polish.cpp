// A bounded fit taken to its constrained minimum; the optimality conditions (bounded_polish.hpp).
#include "bounded_polish.hpp"

#include <gsl/gsl_multifit_nlinear.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheodda::fit::detail {

Optimality optimality(const gsl_matrix* J, const gsl_vector* f, const std::vector<int>& side, double tolerance,
                      double floor) {
  Optimality o;
  const std::size_t n = J->size1, p = J->size2;
  double ff = 0.0;
  for (std::size_t j = 0; j < n; ++j) ff += gsl_vector_get(f, j) * gsl_vector_get(f, j);
  if (ff <= floor) return o;
  for (std::size_t a = 0; a < p; ++a) {
    double g = 0.0, jj = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double v = gsl_matrix_get(J, j, a);
      g += v * gsl_vector_get(f, j);
      jj += v * v;
    }
    if (jj == 0.0) continue;  // the curve does not depend on it: nothing to satisfy
    const double c = g / std::sqrt(ff * jj);
    // inside: |c|; at the lower bound only c < 0 violates (chi^2 falls inward), at the upper only c > 0
    const double violation = side[a] < 0 ? -c : side[a] > 0 ? c : std::abs(c);
    if (violation > o.worst) o.worst = violation, o.worst_col = a;
  }
  o.holds = o.worst <= tolerance;
  return o;
}

namespace {

// Solves the small dense system M d = r (M symmetric positive definite, m <= a
// dozen) by Gaussian elimination with partial pivoting; false if singular.
bool solve_small(std::vector<double> M, std::vector<double> r, std::size_t m, std::vector<double>& d) {
  for (std::size_t c = 0; c < m; ++c) {
    std::size_t piv = c;
    for (std::size_t i = c + 1; i < m; ++i)
      if (std::abs(M[i * m + c]) > std::abs(M[piv * m + c])) piv = i;
    if (!(std::abs(M[piv * m + c]) > 0.0)) return false;
    if (piv != c) {
      for (std::size_t k = 0; k < m; ++k) std::swap(M[c * m + k], M[piv * m + k]);
      std::swap(r[c], r[piv]);
    }
    for (std::size_t i = c + 1; i < m; ++i) {
      const double q = M[i * m + c] / M[c * m + c];
      for (std::size_t k = c; k < m; ++k) M[i * m + k] -= q * M[c * m + k];
      r[i] -= q * r[c];
    }
  }
  d.assign(m, 0.0);
  for (std::size_t c = m; c-- > 0;) {
    double s = r[c];
    for (std::size_t k = c + 1; k < m; ++k) s -= M[c * m + k] * d[k];
    d[c] = s / M[c * m + c];
  }
  return std::all_of(d.begin(), d.end(), [](double v) { return std::isfinite(v); });
}

double sum_of_squares(const gsl_vector* f) {
  double s = 0.0;
  for (std::size_t j = 0; j < f->size; ++j) s += gsl_vector_get(f, j) * gsl_vector_get(f, j);
  return s;
}

}  // namespace

BoundedOutcome bounded_polish(Solver& solver, std::vector<double> x, int max_iterations) {
  const Mapping& m = *solver.mapping();
  const std::size_t nf = m.free.size(), n = solver.pr.n;
  // The same problem over the free log parameters themselves (z = x, no transform).
  Mapping plain = m;
  plain.lo.assign(nf, -std::numeric_limits<double>::infinity());
  plain.hi.assign(nf, std::numeric_limits<double>::infinity());
  Solver js(*solver.pr.info, *solver.pr.data, solver.pr.structure, solver.pr.inv_scale, solver.pr.weight,
            std::move(plain));
  const double floor = static_cast<double>(n) * 1e-20;
  auto project = [&](std::vector<double>& xs) {
    for (std::size_t a = 0; a < nf; ++a) xs[m.free[a]] = std::clamp(xs[m.free[a]], m.lo[a], m.hi[a]);
    m.apply_derived(xs);
  };
  auto sides = [&](const std::vector<double>& xs) {
    std::vector<int> s(nf, 0);
    for (std::size_t a = 0; a < nf; ++a)
      s[a] = xs[m.free[a]] <= m.lo[a] ? -1 : xs[m.free[a]] >= m.hi[a] ? 1 : 0;
    return s;
  };
  project(x);
  gsl_multifit_nlinear_workspace* w = js.at(x);
  double rss = sum_of_squares(gsl_multifit_nlinear_residual(w));
  double lambda = 1e-3;
  BoundedOutcome out;
  std::vector<double> J(n * nf), f(n), d;
  for (; out.iterations < max_iterations; ++out.iterations) {
    const gsl_matrix* Jg = gsl_multifit_nlinear_jac(w);
    const gsl_vector* fg = gsl_multifit_nlinear_residual(w);
    const auto side = sides(x);
    // Converged well inside the reporting tolerance: nothing left to gain.
    if (optimality(Jg, fg, side, 1e-3 * kOptimalityTolerance, floor).holds) break;
    for (std::size_t j = 0; j < n; ++j) {
      f[j] = gsl_vector_get(fg, j);
      for (std::size_t a = 0; a < nf; ++a) J[j * nf + a] = gsl_matrix_get(Jg, j, a);
    }
    std::vector<double> g(nf, 0.0);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t a = 0; a < nf; ++a) g[a] += J[j * nf + a] * f[j];
    // The active set: on a bound with the descent direction -g pointing out of the box.
    std::vector<std::size_t> inactive;
    for (std::size_t a = 0; a < nf; ++a)
      if (!((side[a] < 0 && g[a] > 0.0) || (side[a] > 0 && g[a] < 0.0))) inactive.push_back(a);
    const std::size_t mi = inactive.size();
    if (mi == 0) break;
    std::vector<double> A(mi * mi, 0.0), r(mi);
    for (std::size_t u = 0; u < mi; ++u) {
      r[u] = -g[inactive[u]];
      for (std::size_t v = 0; v < mi; ++v)
        for (std::size_t j = 0; j < n; ++j) A[u * mi + v] += J[j * nf + inactive[u]] * J[j * nf + inactive[v]];
    }
    bool accepted = false;
    std::vector<double> xn;
    while (lambda < 1e16) {
      std::vector<double> M = A;
      for (std::size_t u = 0; u < mi; ++u) M[u * mi + u] += lambda * std::max(A[u * mi + u], 1e-300);
      if (solve_small(M, r, mi, d)) {
        xn = x;
        for (std::size_t u = 0; u < mi; ++u) xn[m.free[inactive[u]]] += d[u];
        project(xn);
        w = js.at(xn);
        const double rn = sum_of_squares(gsl_multifit_nlinear_residual(w));
        if (rn < rss) {
          accepted = true;
          lambda = std::max(lambda * 0.1, 1e-12);
          const double gain = rss - rn;
          rss = rn;
          double moved = 0.0;
          for (std::size_t a = 0; a < nf; ++a) moved = std::max(moved, std::abs(xn[m.free[a]] - x[m.free[a]]));
          x = std::move(xn);
          if (gain <= 1e-15 * rss + floor && moved <= 1e-13) lambda = 1e16;  // no more progress to make
          break;
        }
      }
      lambda *= 10.0;
    }
    if (!accepted || lambda >= 1e16) {
      ++out.iterations;
      break;
    }
  }
  w = js.at(x);
  out.x = x;
  out.rss = sum_of_squares(gsl_multifit_nlinear_residual(w));
  out.optimal = optimality(gsl_multifit_nlinear_jac(w), gsl_multifit_nlinear_residual(w), sides(x),
                           kOptimalityTolerance, floor)
                    .holds;
  return out;
}

}  // namespace rheodda::fit::detail
