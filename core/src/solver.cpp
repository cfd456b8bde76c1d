#include "rheodda/core/solver.hpp"

#include <cholmod.h>
#include <omp.h>

#include "block_amg.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rheodda::core {

namespace {

// Debian's CHOLMOD is built with OpenMP and opens its supernodal parallel
// regions with a compiled-in num_threads(4) (CHOLMOD_OMP_NUM_THREADS in
// cholmod_core.h), which neither OMP_NUM_THREADS nor omp_set_num_threads
// overrides. On a machine with fewer free cores than that the threads wait on
// each other (docs/design/linear-solvers.md, "CHOLMOD runs serially"). rheodda solves one model per
// core (studies run their cases in parallel, `-j`), so CHOLMOD runs serially:
// no parallel region is active while this guard lives (OpenMP's
// max-active-levels 0), and the caller's setting comes back after.
class SerialOpenMp {
 public:
  SerialOpenMp() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMp() { omp_set_max_active_levels(levels_); }
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  int levels_;
};

}  // namespace

// CHOLMOD state kept between solves: the matrix (its pattern stays valid while
// the block pattern is unchanged, so only values are refilled) and the factor
// (whose symbolic part is reused by cholmod_factorize).
struct LinearSolver::Cholmod {
  cholmod_common common{};
  cholmod_sparse* A = nullptr;
  cholmod_factor* L = nullptr;
  int blocks = -1;
  std::vector<std::pair<int, int>> pattern;  // off-diagonal (i, j), column-major order

  Cholmod() {
    cholmod_start(&common);
    common.print = 0;  // CHOLMOD's own messages went to stdout; the errors below say it all
  }
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

/// Conjugate gradient on K x = F from the start x (warm start), preconditioned
/// by z = M^-1 r. Stops when ||F - K x|| <= tolerance ||F||.
template <class Precondition>
void pcg(const BlockSystem& s, double tolerance, int max_iterations, SolverStats& stats,
         Precondition&& precondition, Eigen::VectorXd& x) {
  const Eigen::VectorXd& f = s.rhs();
  const double f_norm = f.norm();
  if (f_norm == 0.0) {
    x.setZero(f.size());
    return;
  }
  Eigen::VectorXd r = f - s.multiply(x);
  if (r.norm() > f_norm) {  // a start worse than zero: start from zero
    x.setZero(f.size());
    r = f;
  }
  Eigen::VectorXd z(f.size());
  precondition(r, z);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  int replacements = 0;
  for (int it = 0; it < max_iterations; ++it) {
    if (r.norm() <= tolerance * f_norm) {
      // The recurrence's residual drifts from F - K x by round-off; check the
      // true one and carry on from it (at most 3 times: then the drift is the
      // attainable accuracy).
      r = f - s.multiply(x);
      if (r.norm() <= tolerance * f_norm || ++replacements > 3) return;
      precondition(r, z);
      p = z;
      rz = r.dot(z);
    }
    const Eigen::VectorXd q = s.multiply(p);
    const double alpha = rz / p.dot(q);
    x += alpha * p;
    r -= alpha * q;
    precondition(r, z);
    const double rz_new = r.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
    ++stats.pcg_iterations;
  }
  if (r.norm() <= tolerance * f_norm) return;
  throw std::runtime_error("pcg: no convergence in " + std::to_string(max_iterations) +
                           " iterations (relative residual " +
                           std::to_string(r.norm() / f_norm) + ")");
}

Eigen::VectorXd solve_block_jacobi(const BlockSystem& s, double tolerance, int max_iterations,
                                   SolverStats& stats) {
  const int n = s.block_count();
  // Block-Jacobi preconditioner: Cholesky of each 6x6 diagonal block.
  std::vector<Eigen::LLT<Mat6>> pre(static_cast<std::size_t>(n));
  for (int b = 0; b < n; ++b) {
    pre[b].compute(s.diagonal(b));
    if (pre[b].info() != Eigen::Success)
      throw SingularSystemError("pcg: diagonal block " + std::to_string(b) + " is not positive definite", b, -1);
  }
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    for (int b = 0; b < n; ++b) z.segment<6>(6 * b) = pre[b].solve(r.segment<6>(6 * b));
  };
  Eigen::VectorXd x(s.rhs().size());
  precondition(s.rhs(), x);  // exact for a block-diagonal K
  pcg(s, tolerance, max_iterations, stats, precondition, x);
  return x;
}

}  // namespace

const char* unknown_name(int k) {
  static const char* names[] = {"u0 (translation x)", "v0 (translation y)", "r0 (rotation)",
                                "ex (strain x)",      "ey (strain y)",      "gxy (shear strain)"};
  return k >= 0 && k < 6 ? names[k] : "?";
}

Eigen::VectorXd LinearSolver::solve(const BlockSystem& system) { return solve(system, tolerance_); }

Eigen::VectorXd LinearSolver::solve(const BlockSystem& system, double tolerance) {
  tolerance = std::max(tolerance, tolerance_);
  ++stats_.solves;
  const SolverKind kind = resolve(kind_, system.block_count());
  if (kind == SolverKind::pcg) return solve_block_jacobi(system, tolerance, max_iterations_, stats_);
  if (kind == SolverKind::amg && kind_ == SolverKind::amg) return solve_amg(system, tolerance);
  if (kind == SolverKind::amg && !amg_failed_) {
    // automatic: the V-cycle has been seen to lose definiteness on irregular
    // block sizes (a generated rock mass of 734 blocks, docs/reference/engine.md
    // "Solvers"); CHOLMOD, exact, takes over rather than the run failing.
    try {
      return solve_amg(system, tolerance);
    } catch (const SingularSystemError&) {
      throw;
    } catch (const std::runtime_error&) {
      amg_failed_ = true;
      stats_.amg_fallback_solve = stats_.solves;
    }
  }
  return solve_cholmod(system);
}

Eigen::VectorXd LinearSolver::solve_cholmod(const BlockSystem& system) {
  if (!cholmod_) cholmod_ = std::make_unique<Cholmod>();
  Cholmod& c = *cholmod_;
  const SerialOpenMp serial;
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
  if (c.common.status == CHOLMOD_NOT_POSDEF || c.L->minor < c.L->n) {
    // L->minor counts in the fill-reducing order: map it back to the unknown.
    const std::size_t k = c.L->minor;
    const int column = c.L->Perm ? static_cast<const int*>(c.L->Perm)[k] : static_cast<int>(k);
    throw SingularSystemError("cholmod: the system matrix is not positive definite at block " +
                                  std::to_string(column / 6) + ", unknown " + unknown_name(column % 6),
                              column / 6, column % 6);
  }
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

namespace {

constexpr std::array<LinearSolverEntry, 4> kLinearSolvers{{
    {SolverKind::automatic, "automatic"},
    {SolverKind::cholmod, "cholmod"},
    {SolverKind::pcg, "pcg"},
    {SolverKind::amg, "amg"},
}};

}  // namespace

std::span<const LinearSolverEntry> linear_solvers() { return kLinearSolvers; }

const LinearSolverEntry& linear_solver_entry(SolverKind method) {
  for (const LinearSolverEntry& e : kLinearSolvers)
    if (e.method == method) return e;
  throw std::logic_error("a linear solver without a row in linear_solvers()");
}

SolverKind LinearSolver::resolve(SolverKind kind, int blocks) {
  if (kind != SolverKind::automatic) return kind;
  return blocks >= kAmgBlocks ? SolverKind::amg : SolverKind::cholmod;
}

Eigen::VectorXd LinearSolver::solve_amg(const BlockSystem& system, double tolerance) {
  if (!amg_) amg_ = std::make_unique<BlockAmg>();
  if (amg_->same_pattern(system)) {
    amg_->refresh(system);
  } else {
    amg_->setup(system);
    ++stats_.analyses;
  }
  ++stats_.factorizations;
  // Warm start from the last solution: the previous iterate of the open-close
  // iteration, or the last step's displacements.
  if (last_.size() != system.rhs().size()) last_.setZero(system.rhs().size());
  pcg(system, tolerance, max_iterations_, stats_,
      [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { amg_->apply(r, z); }, last_);
  return last_;
}

}  // namespace rheodda::core
