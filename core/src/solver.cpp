#include "rheodda/core/solver.hpp"

#include <cholmod.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rheodda::core {

// CHOLMOD state kept between solves: the matrix (its pattern stays valid while
// the block pattern is unchanged, so only values are refilled) and the factor
// (whose symbolic part is reused by cholmod_factorize).
struct LinearSolver::Cholmod {
  cholmod_common common{};
  cholmod_sparse* A = nullptr;
  cholmod_factor* L = nullptr;
  int blocks = -1;
  std::vector<std::pair<int, int>> pattern;  // off-diagonal (i, j), column-major order

  Cholmod() { cholmod_start(&common); }
  ~Cholmod() {
    if (L) cholmod_free_factor(&L, &common);
    if (A) cholmod_free_sparse(&A, &common);
    cholmod_finish(&common);
  }

  bool pattern_unchanged(const BlockSystem& s) const {
    if (s.block_count() != blocks || s.off_diagonal().size() != pattern.size()) return false;
    const auto& off = s.off_diagonal();
    for (std::size_t k = 0; k < off.size(); ++k)
      if (off[k].i != pattern[k].first || off[k].j != pattern[k].second) return false;
    return true;
  }

  // Builds the upper triangle of K in compressed-column form straight from the
  // 6x6 blocks: column 6J+r holds the off-diagonal blocks (I, J), I < J, in
  // increasing I, then rows 6J..6J+r of the diagonal block.
  void build_structure(const BlockSystem& s) {
    if (L) cholmod_free_factor(&L, &common);
    if (A) cholmod_free_sparse(&A, &common);
    blocks = s.block_count();
    pattern.clear();
    for (const auto& o : s.off_diagonal()) pattern.emplace_back(o.i, o.j);
    const std::size_t n = 6 * static_cast<std::size_t>(blocks);
    std::vector<int> per_column(static_cast<std::size_t>(blocks), 0);
    for (const auto& o : s.off_diagonal()) ++per_column[o.j];
    std::size_t nnz = 21 * static_cast<std::size_t>(blocks) + 36 * pattern.size();
    A = cholmod_allocate_sparse(n, n, nnz, /*sorted*/ 1, /*packed*/ 1, /*stype upper*/ 1, CHOLMOD_REAL,
                                &common);
    if (!A) throw std::runtime_error("cholmod: cannot allocate the system matrix");
    auto* p = static_cast<int*>(A->p);
    auto* rows = static_cast<int*>(A->i);
    std::size_t at = 0, next_off = 0;
    for (int J = 0; J < blocks; ++J) {
      const std::size_t first_off = next_off;
      next_off += static_cast<std::size_t>(per_column[J]);
      for (int r = 0; r < 6; ++r) {
        p[6 * J + r] = static_cast<int>(at);
        for (std::size_t k = first_off; k < next_off; ++k)
          for (int q = 0; q < 6; ++q) rows[at++] = 6 * pattern[k].first + q;
        for (int q = 0; q <= r; ++q) rows[at++] = 6 * J + q;
      }
    }
    p[n] = static_cast<int>(at);
  }

  void fill_values(const BlockSystem& s) {
    auto* x = static_cast<double*>(A->x);
    const auto& off = s.off_diagonal();
    std::size_t at = 0, next_off = 0;
    for (int J = 0; J < blocks; ++J) {
      const std::size_t first_off = next_off;
      while (next_off < off.size() && off[next_off].j == J) ++next_off;
      const Mat6& d = s.diagonal(J);
      for (int r = 0; r < 6; ++r) {
        for (std::size_t k = first_off; k < next_off; ++k)
          for (int q = 0; q < 6; ++q) x[at++] = off[k].k(q, r);
        for (int q = 0; q <= r; ++q) x[at++] = d(q, r);
      }
    }
  }
};

LinearSolver::LinearSolver(SolverKind kind, double tolerance, int max_iterations)
    : kind_(kind), tolerance_(tolerance), max_iterations_(max_iterations) {}

LinearSolver::~LinearSolver() = default;

namespace {

Eigen::VectorXd solve_pcg(const BlockSystem& s, double tolerance, int max_iterations,
                          SolverStats& stats) {
  const int n = s.block_count();
  // Block-Jacobi preconditioner: Cholesky of each 6x6 diagonal block.
  std::vector<Eigen::LLT<Mat6>> pre(static_cast<std::size_t>(n));
  for (int b = 0; b < n; ++b) {
    pre[b].compute(s.diagonal(b));
    if (pre[b].info() != Eigen::Success)
      throw std::runtime_error("pcg: diagonal block " + std::to_string(b) +
                               " is not positive definite");
  }
  auto precondition = [&](const Eigen::VectorXd& r) {
    Eigen::VectorXd z(r.size());
    for (int b = 0; b < n; ++b) z.segment<6>(6 * b) = pre[b].solve(r.segment<6>(6 * b));
    return z;
  };
  const Eigen::VectorXd& f = s.rhs();
  const double f_norm = f.norm();
  Eigen::VectorXd x = precondition(f);  // exact for a block-diagonal K
  if (f_norm == 0.0) return Eigen::VectorXd::Zero(f.size());
  Eigen::VectorXd r = f - s.multiply(x);
  Eigen::VectorXd z = precondition(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  for (int it = 0; it < max_iterations; ++it) {
    if (r.norm() <= tolerance * f_norm) return x;
    const Eigen::VectorXd q = s.multiply(p);
    const double alpha = rz / p.dot(q);
    x += alpha * p;
    r -= alpha * q;
    z = precondition(r);
    const double rz_new = r.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
    ++stats.pcg_iterations;
  }
  if (r.norm() <= tolerance * f_norm) return x;
  throw std::runtime_error("pcg: no convergence in " + std::to_string(max_iterations) +
                           " iterations (relative residual " +
                           std::to_string(r.norm() / f_norm) + ")");
}

}  // namespace

Eigen::VectorXd LinearSolver::solve(const BlockSystem& system) {
  ++stats_.solves;
  if (kind_ == SolverKind::pcg) return solve_pcg(system, tolerance_, max_iterations_, stats_);

  if (!cholmod_) cholmod_ = std::make_unique<Cholmod>();
  Cholmod& c = *cholmod_;
  if (!c.A || !c.pattern_unchanged(system)) {
    c.build_structure(system);
    c.fill_values(system);
    c.L = cholmod_analyze(c.A, &c.common);
    if (!c.L) throw std::runtime_error("cholmod: symbolic analysis failed");
    ++stats_.analyses;
  } else {
    c.fill_values(system);
  }
  cholmod_factorize(c.A, c.L, &c.common);
  ++stats_.factorizations;
  if (c.common.status == CHOLMOD_NOT_POSDEF || c.L->minor < c.L->n)
    throw std::runtime_error("cholmod: the system matrix is not positive definite (column " +
                             std::to_string(c.L->minor) + ")");
  if (c.common.status < CHOLMOD_OK)
    throw std::runtime_error("cholmod: factorisation failed (status " +
                             std::to_string(c.common.status) + ")");

  const Eigen::VectorXd& f = system.rhs();
  cholmod_dense b{};
  b.nrow = static_cast<std::size_t>(f.size());
  b.ncol = 1;
  b.nzmax = b.nrow;
  b.d = b.nrow;
  b.x = const_cast<double*>(f.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, c.L, &b, &c.common);
  if (!x) throw std::runtime_error("cholmod: solve failed");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(static_cast<double*>(x->x), f.size());
  cholmod_free_dense(&x, &c.common);
  return out;
}

}  // namespace rheodda::core
