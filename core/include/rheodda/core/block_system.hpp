// The global DDA system K D = F in its natural 6x6 block form.
//
// K is symmetric with one 6x6 block per block on the diagonal and one per
// interacting block pair off it (Shi 1988; the seed's eq. 30). Terms are
// collected as 6x6 blocks - never as a dense matrix and never as scalar
// triplets - and then handed to a solver (solver.hpp), which builds its own
// sparse storage straight from the blocks.
#pragma once

#include <Eigen/Dense>
#include <span>
#include <utility>
#include <vector>

#include "rheodda/contact/kinematics.hpp"

namespace rheodda::core {

using Mat6 = Eigen::Matrix<double, 6, 6>;

/// One off-diagonal block K_ij with i < j (K_ji = K_ij^T is implied).
struct OffDiagonalBlock {
  int i = 0;
  int j = 0;
  Mat6 k = Mat6::Zero();
};

class BlockSystem final : public contact::SystemSink {
 public:
  /// n blocks, all terms zero.
  void reset(int n);
  /// Starts from the given diagonal blocks and right-hand side, no off-diagonal blocks.
  void reset(const std::vector<Mat6>& diagonal, const Eigen::VectorXd& rhs);
  int block_count() const { return static_cast<int>(diagonal_.size()); }
  /// Records the centroids (x0, y0) the unknowns of each block refer to
  /// [length]; solvers that build coarse spaces from the geometry (amg) need
  /// them. Optional: without them the centroids are taken as all zero.
  void set_centroids(std::span<const contact::BlockView> blocks);
  /// Centroids given to set_centroids (empty if none) [length].
  const std::vector<contact::Vec2>& centroids() const { return centroids_; }

  /// K_ij += k (and K_ji += k^T for i != j). Call once per pair.
  void add_stiffness(int i, int j, const contact::Mat6& k) override;
  /// F_i += f.
  void add_load(int i, const contact::Vec6& f) override;

  Mat6& diagonal(int i) { return diagonal_[i]; }
  const Mat6& diagonal(int i) const { return diagonal_[i]; }
  const std::vector<Mat6>& diagonals() const { return diagonal_; }
  Eigen::VectorXd& rhs() { return rhs_; }
  const Eigen::VectorXd& rhs() const { return rhs_; }

  /// Merges repeated pairs and sorts the off-diagonal blocks by column j,
  /// then row i (the order of a column-major upper triangle). Idempotent.
  /// When the pairs come in the same sequence as at the last call (the
  /// iterates of one step), the merge reuses that call's slots: O(pairs), no sort.
  void finalize();
  /// Off-diagonal blocks (upper triangle); sorted after finalize().
  const std::vector<OffDiagonalBlock>& off_diagonal() const { return off_; }
  /// True if the two finalised systems have the same block sparsity pattern.
  bool same_pattern(const BlockSystem& other) const;

  /// y = K x (uses the upper blocks for both triangles).
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

 private:
  std::vector<Mat6> diagonal_;
  std::vector<OffDiagonalBlock> off_;  // merged and sorted (after finalize)
  std::vector<OffDiagonalBlock> raw_;  // as added since the last finalize
  // Merge map of the last finalize: the pair sequence it was built for, the
  // slot of each raw entry, the merged pairs.
  std::vector<std::pair<int, int>> merge_keys_;
  std::vector<int> merge_slot_;
  std::vector<std::pair<int, int>> merged_pattern_;
  Eigen::VectorXd rhs_;
  std::vector<contact::Vec2> centroids_;
  bool finalized_ = true;
};

}  // namespace rheodda::core
