// Linear solvers for the block system (block_system.hpp).
//
// cholmod: sparse Cholesky LL' by SuiteSparse CHOLMOD. The symbolic analysis
//   (fill-reducing ordering, elimination tree, supernodes) depends only on the
//   sparsity pattern; it is redone only when the block pattern changes, which
//   is detected by comparing the sorted list of off-diagonal block pairs
//   (O(pairs), no scalar work). Otherwise only the numeric factorisation runs.
// pcg: conjugate gradient preconditioned by the inverses of the 6x6 diagonal
//   blocks (block Jacobi); memory O(blocks + pairs). Hundreds of iterations on
//   contact-dominated systems: kept as a reference.
// amg: conjugate gradient preconditioned by one aggregation-multigrid V-cycle
//   (block_amg.hpp), warm-started from the last solution; O(blocks) work per
//   iteration and an iteration count that does not grow with the model.
// automatic (the default): cholmod for small models, amg for large ones.
#pragma once

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rheodda/core/block_system.hpp"
#include "rheodda/core/solver_state.hpp"
#include "rheodda/core/model.hpp"

namespace rheodda::core {

class BlockAmg;

/// A registered linear solver: its Settings value and its scene word.
struct LinearSolverEntry {
  SolverKind method;
  std::string_view word;  ///< the scene's `solver` word
};

/// Every linear solver, one row each (solver.cpp).
std::span<const LinearSolverEntry> linear_solvers();

/// The row of `method` (Settings::solver).
const LinearSolverEntry& linear_solver_entry(SolverKind method);

/// The system matrix is not positive definite: the first unknown at which the
/// factorisation broke down, as a block and one of its six DDA unknowns
/// (0 u0, 1 v0, 2 r0, 3 εx, 4 εy, 5 γxy; Shi 1988), when the solver can tell.
struct SingularSystemError : std::runtime_error {
  SingularSystemError(const std::string& what, int block_, int unknown_)
      : std::runtime_error(what), block(block_), unknown(unknown_) {}
  int block = -1;    ///< block index, -1 if unknown
  int unknown = -1;  ///< 0..5, -1 if unknown
};

/// "rotation r0" etc.: the name of DDA unknown `k` (0..5) of a block.
const char* unknown_name(int k);

class LinearSolver {
 public:
  /// tolerance and max_iterations apply to pcg only.
  explicit LinearSolver(SolverKind kind, double tolerance = 1.0e-10, int max_iterations = 10000);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Solves K D = F for a finalised system. Throws std::runtime_error if K is
  /// not positive definite (cholmod) or PCG does not converge. Under `automatic`
  /// a solve whose amg conjugate gradient does not converge is redone by CHOLMOD,
  /// which then solves the rest of the run (SolverStats::amg_fallback_solve).
  Eigen::VectorXd solve(const BlockSystem& system);
  /// The same with the iterative solvers' stop loosened to `tolerance` when it
  /// is above the solver's own (an open-close iterate whose states are still
  /// changing; cholmod is exact either way).
  Eigen::VectorXd solve(const BlockSystem& system, double tolerance);
  /// The solve of `blocks` blocks is iterative (pcg or amg), so a looser
  /// tolerance makes it cheaper.
  bool iterative(int blocks) const { return used(blocks) != SolverKind::cholmod; }
  double tolerance() const { return tolerance_; }
  SolverKind kind() const { return kind_; }
  /// The solver `kind` stands for in a model of `blocks` blocks (automatic ->
  /// cholmod or amg; the others are themselves).
  static SolverKind resolve(SolverKind kind, int blocks);
  /// The solver this one uses now: resolve(kind(), blocks), or cholmod after an
  /// automatic fallback.
  SolverKind used(int blocks) const {
    return amg_failed_ ? SolverKind::cholmod : resolve(kind_, blocks);
  }
  /// automatic picks amg from this many blocks on. Below it CHOLMOD (run
  /// serially) is exact (no tolerance to choose) and faster; above it the
  /// Cholesky factor's N^1.5 flops take over. The crossover on the brick-wall
  /// benchmark: docs/notes/performance.md, "Which solver, from how many blocks"
  /// (scripts/solver-switch.sh).
  static constexpr int kAmgBlocks = 2000;
  const SolverStats& stats() const { return stats_; }
  /// What the next solves depend on beside their systems (solver_state.cpp):
  /// restore() it into a solver of the same kind to solve on bit for bit.
  SolverState state() const;
  void restore(const SolverState& state);

 private:
  struct Cholmod;
  Eigen::VectorXd solve_amg(const BlockSystem& system, double tolerance);
  Eigen::VectorXd solve_cholmod(const BlockSystem& system);
  SolverKind kind_;
  bool amg_failed_ = false;  ///< automatic: amg did not converge once, CHOLMOD from then on
  double tolerance_;
  int max_iterations_;
  SolverStats stats_;
  std::unique_ptr<Cholmod> cholmod_;
  std::unique_ptr<BlockAmg> amg_;
  Eigen::VectorXd last_;  ///< last solution (amg: the start of the next solve)
};

}  // namespace rheodda::core
