#include "rheodda/core/block_system.hpp"

#include <algorithm>

namespace rheodda::core {

void BlockSystem::reset(int n) {
  diagonal_.assign(static_cast<std::size_t>(n), Mat6::Zero());
  off_.clear();
  raw_.clear();
  rhs_.setZero(6 * static_cast<Eigen::Index>(n));
  finalized_ = true;
}

void BlockSystem::reset(const std::vector<Mat6>& diagonal, const Eigen::VectorXd& rhs) {
  diagonal_ = diagonal;  // reuses the storage when the size is unchanged
  off_.clear();
  raw_.clear();
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
    raw_.push_back({i, j, k});
    finalized_ = false;
  } else {
    raw_.push_back({j, i, k.transpose()});
    finalized_ = false;
  }
}

void BlockSystem::add_load(int i, const contact::Vec6& f) { rhs_.segment<6>(6 * i) += f; }

void BlockSystem::finalize() {
  if (finalized_) return;
  finalized_ = true;
  // Blocks added after an earlier finalize (without reset) join the merged ones.
  if (!off_.empty()) raw_.insert(raw_.begin(), off_.begin(), off_.end());
  // The same sequence of pairs as last time (the iterates of one step: every
  // contact adds its pair, open or not): merge through the cached slots, no sort.
  bool same = raw_.size() == merge_keys_.size();
  for (std::size_t k = 0; same && k < raw_.size(); ++k)
    same = raw_[k].i == merge_keys_[k].first && raw_[k].j == merge_keys_[k].second;
  if (!same) {
    // Sort an index (not the 6x6 blocks) by column j, then row i, and give each
    // distinct pair a slot.
    std::vector<int> order(raw_.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return raw_[a].j != raw_[b].j ? raw_[a].j < raw_[b].j : raw_[a].i < raw_[b].i;
    });
    merge_keys_.resize(raw_.size());
    merge_slot_.resize(raw_.size());
    merged_pattern_.clear();
    for (int k : order) {
      if (merged_pattern_.empty() || merged_pattern_.back().first != raw_[k].i ||
          merged_pattern_.back().second != raw_[k].j)
        merged_pattern_.emplace_back(raw_[k].i, raw_[k].j);
      merge_slot_[k] = static_cast<int>(merged_pattern_.size()) - 1;
      merge_keys_[k] = {raw_[k].i, raw_[k].j};
    }
  }
  off_.resize(merged_pattern_.size());
  for (std::size_t s = 0; s < off_.size(); ++s) {
    off_[s].i = merged_pattern_[s].first;
    off_[s].j = merged_pattern_[s].second;
    off_[s].k.setZero();
  }
  for (std::size_t k = 0; k < raw_.size(); ++k) off_[merge_slot_[k]].k += raw_[k].k;
  raw_.clear();
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
