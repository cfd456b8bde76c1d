// Aggregation multigrid for the DDA block system, used as the preconditioner
// of a conjugate gradient (the `amg` solver, solver.hpp; docs/reference/engine.md,
// "Solvers").
//
// Why: the global system of a large DDA model is a 2-D graph of 6x6 blocks.
// A sparse Cholesky factor of it grows like N^1.5 in flops (nested
// dissection on a planar graph) and is refactorised at every open-close
// iterate; block-Jacobi CG needs hundreds of iterations because the contact
// penalties are 10^3-10^4 times the blocks' own inertia. A multigrid V-cycle
// costs a few matrix-vector products and its convergence rate does not
// depend on the model size, so each solve is O(N).
//
// Coarse spaces come from the geometry of DDA itself. A group of adjacent
// blocks (an aggregate) is given the six unknowns of one DDA block at the
// group's centre x_a: the affine displacement field
//   u(x) = T(x - x_a) D_a    (Shi 1988; contact/kinematics.hpp)
// Restricted to a member block i with centroid x_i, this field is exactly
// the block displacement D_i = P_i D_a with
//   P_i = | 1 0 -dy dx  0  dy/2 |      dx = x_i - x_a, dy = y_i - y_a
//         | 0 1  dx  0 dy  dx/2 |
//         | 0 0  1   0  0  0    |      (rotation and strains are the same
//         | 0 0  0   1  0  0    |       at every point of an affine field)
//         | 0 0  0   0  1  0    |
//         | 0 0  0   0  0  1    |
// so the coarse space holds every rigid-body motion and every uniform strain
// of each aggregate (the near-null space of the penalty couplings). The
// coarse matrix is the Galerkin product A_c = P^T A P, block by block; it is
// again a DDA-like block system and is coarsened the same way.
//
// Aggregates (Vanek, Mandel & Brezina 1996, smoothed aggregation): blocks are
// grouped with their strongly coupled neighbours, |A_ij|_F > theta
// sqrt(|A_ii|_F |A_jj|_F), so open contacts (zero blocks) never join two
// blocks. The tentative transfer P0 (the P_i above) jumps at aggregate
// borders, where it stretches the stiff contact springs; one damped
// block-Jacobi step smooths it, P = (I - omega D^-1 A) P0 with
// omega = 4 / (3 lambda_max(D^-1 A)), which is what keeps the iteration count
// flat when the contacts are 10^3-10^4 times stiffer than the blocks. Smoother: symmetric block Gauss-Seidel (a forward sweep before the
// coarse correction, a backward sweep after it), which needs no eigenvalue
// estimate and keeps the V-cycle symmetric positive definite, as CG needs.
// The coarsest level (at most kCoarsest blocks) is solved by a dense Cholesky.
//
// Reuse: the aggregates and the coarse patterns depend only on the block
// pattern of A; while it is unchanged (the iterates of one step, and steps
// whose contacts join the same block pairs), refresh() recomputes only the
// values and the transfers from the blocks' current centroids. The aggregates
// and the smoothing weights so depend on the systems of earlier steps: a
// resumed run takes them up from its saved state (save(), restore()) to solve
// as the uninterrupted run does, bit for bit.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "rheodda/core/block_system.hpp"
#include "rheodda/core/solver_state.hpp"

namespace rheodda::core {

class BlockAmg {
 public:
  /// Builds the hierarchy (aggregates, patterns and values) for s.
  void setup(const BlockSystem& s);
  /// Recomputes the values for s, whose block pattern must be the one given to
  /// setup() (the caller checks; see same_pattern()).
  void refresh(const BlockSystem& s);
  /// True if s has the block pattern the hierarchy was built for.
  bool same_pattern(const BlockSystem& s) const;
  /// z = M^-1 r: one V-cycle from z = 0 (symmetric positive definite in r).
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  /// Number of levels, the finest included (1 = the coarsest solve alone).
  int levels() const { return static_cast<int>(levels_.size()); }
  /// Blocks on level l.
  int blocks(int l) const { return levels_[l].n; }
  /// Coarse block of each block of level l (empty on the coarsest level).
  const std::vector<int>& aggregates(int l) const { return levels_[l].agg; }

  /// The part of the hierarchy that depends on the systems seen so far (the
  /// aggregates, the smoothing weights and the points they were computed at;
  /// block_amg_state.cpp), into `out`'s amg fields.
  void save(SolverState& out) const;
  /// Takes up a saved hierarchy: same_pattern() compares with its pattern and
  /// the next refresh() rebuilds its levels from it before refreshing, so the
  /// solves go on as they would have in the hierarchy it was saved from.
  void restore(const SolverState& saved);

  /// Coarsening stops at this many blocks; below it a dense Cholesky solves.
  static constexpr int kCoarsest = 24;
  /// Strength of connection threshold theta (see above).
  static constexpr double kStrength = 0.02;

 private:
  struct Level {
    int n = 0;
    // The matrix: level 0 points at the BlockSystem's storage, coarser levels own theirs.
    const std::vector<Mat6>* diag = nullptr;
    const std::vector<OffDiagonalBlock>* off = nullptr;  // upper blocks, sorted by (j, i)
    std::vector<Mat6> own_diag;
    std::vector<OffDiagonalBlock> own_off;
    std::vector<int> col_start;  // off entries of column j: [col_start[j], col_start[j+1])
    std::vector<Mat6> diag_inv;  // A_jj^-1 for the Gauss-Seidel sweeps
    std::vector<contact::Vec2> pos;       // the points the unknowns refer to [length]
    // Rows of A without the diagonal, both triangles: neighbour, off block, transposed?
    std::vector<int> row_start, row_nbr, row_off;
    std::vector<char> row_t;
    // Transfer to the next coarser level (absent on the coarsest).
    std::vector<int> agg;             // block -> coarse block (aggregate)
    std::vector<Mat6> P0;             // tentative transfer block P_i (see above)
    double omega = 0.0;               // prolongator smoothing weight 4 / (3 lambda_max(D^-1 A))
    std::vector<int> p_start, p_col;  // smoothed P by fine row: coarse column, 6x6 value
    std::vector<Mat6> p_val;
    std::vector<int> g_slot;          // Galerkin product i, a, b -> coarse slot (-1 - a: diagonal)
    // Work vectors.
    Eigen::VectorXd b, x, r, t;
  };

  void build_columns(Level& L) const;
  void invert_diagonal(Level& L) const;
  /// Aggregates of L and the pattern of the next level; returns false when
  /// coarsening does not reduce the size enough.
  bool aggregate(Level& L, Level& C) const;
  /// Centres of the aggregates (mean of their blocks' points) and P0.
  void place_aggregates(Level& L, Level& C) const;
  void build_rows(Level& L) const;
  double lambda_max(const Level& L) const;
  void smooth_prolongator(Level& L) const;
  /// A_c = P^T A P into C; with build = true also the pattern of C.
  void galerkin(Level& L, Level& C, bool build) const;
  void factor_coarsest();
  /// Builds the levels for s from the saved aggregates (restore()).
  void rebuild(const BlockSystem& s);
  void vcycle(std::size_t l);
  void forward_sweep(Level& L) const;   // x <- forward Gauss-Seidel on A x = b, from x = 0
  void backward_sweep(Level& L) const;  // x <- backward Gauss-Seidel on A x = b
  void residual(Level& L) const;        // r = b - A x, right after forward_sweep

  std::vector<Level> levels_;
  std::vector<std::pair<int, int>> pattern_;  // level-0 off pattern the hierarchy was built for
  Eigen::LLT<Eigen::MatrixXd> coarse_llt_;
  Eigen::LDLT<Eigen::MatrixXd> coarse_ldlt_;
  bool coarse_definite_ = true;
  /// Saved by restore(), built into levels_ by the next refresh() (then reset).
  std::unique_ptr<SolverState> pending_;
};

}  // namespace rheodda::core
