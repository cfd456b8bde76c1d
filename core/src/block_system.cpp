#include "rheodda/core/block_system.hpp"

#include <algorithm>

namespace rheodda::core {

void BlockSystem::reset(int n) {
  diagonal_.assign(static_cast<std::size_t>(n), Mat6::Zero());
  off_.clear();
  rhs_.setZero(6 * static_cast<Eigen::Index>(n));
  finalized_ = true;
}

void BlockSystem::reset(const std::vector<Mat6>& diagonal, const Eigen::VectorXd& rhs) {
  diagonal_ = diagonal;  // reuses the storage when the size is unchanged
  off_.clear();
  rhs_ = rhs;
  finalized_ = true;
}

void BlockSystem::set_centroids(std::span<const contact::BlockView> blocks) {
  centroids_.resize(blocks.size());
  for (std::size_t k = 0; k < blocks.size(); ++k) centroids_[k] = blocks[k].centroid;
}

void BlockSystem::add_stiffness(int i, int j, const contact::Mat6& k) {
  if (i == j) {
    diagonal_[i] += k;
  } else if (i < j) {
    off_.push_back({i, j, k});
    finalized_ = false;
  } else {
    off_.push_back({j, i, k.transpose()});
    finalized_ = false;
  }
}

void BlockSystem::add_load(int i, const contact::Vec6& f) { rhs_.segment<6>(6 * i) += f; }

void BlockSystem::finalize() {
  if (finalized_) return;
  std::sort(off_.begin(), off_.end(), [](const OffDiagonalBlock& a, const OffDiagonalBlock& b) {
    return a.j != b.j ? a.j < b.j : a.i < b.i;
  });
  std::size_t out = 0;
  for (std::size_t k = 0; k < off_.size(); ++k) {
    if (out > 0 && off_[out - 1].i == off_[k].i && off_[out - 1].j == off_[k].j) {
      off_[out - 1].k += off_[k].k;
    } else {
      if (out != k) off_[out] = off_[k];
      ++out;
    }
  }
  off_.resize(out);
  finalized_ = true;
}

bool BlockSystem::same_pattern(const BlockSystem& other) const {
  if (diagonal_.size() != other.diagonal_.size() || off_.size() != other.off_.size()) return false;
  for (std::size_t k = 0; k < off_.size(); ++k)
    if (off_[k].i != other.off_[k].i || off_[k].j != other.off_[k].j) return false;
  return true;
}

Eigen::VectorXd BlockSystem::multiply(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y(x.size());
  const int n = block_count();
  for (int b = 0; b < n; ++b) y.segment<6>(6 * b).noalias() = diagonal_[b] * x.segment<6>(6 * b);
  for (const auto& o : off_) {
    y.segment<6>(6 * o.i).noalias() += o.k * x.segment<6>(6 * o.j);
    y.segment<6>(6 * o.j).noalias() += o.k.transpose() * x.segment<6>(6 * o.i);
  }
  return y;
}

}  // namespace rheodda::core
