#include "rheodda/contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rheodda::contact {

Box bounding_box(const BlockView& block, double margin) {
  Box b;
  b.lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  b.hi = -b.lo;
  for (const Vec2& v : block.vertices) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  b.lo.array() -= margin;
  b.hi.array() += margin;
  return b;
}

const std::vector<std::pair<int, int>>& BroadPhase::find_pairs(std::span<const Box> boxes) {
  pairs_.clear();
  const int n = static_cast<int>(boxes.size());
  if (n < 2) return pairs_;

  // Domain and cell size: the median of the larger box side.
  Box dom = boxes[0];
  sizes_.resize(n);
  for (int i = 0; i < n; ++i) {
    dom.lo = dom.lo.cwiseMin(boxes[i].lo);
    dom.hi = dom.hi.cwiseMax(boxes[i].hi);
    sizes_[i] = (boxes[i].hi - boxes[i].lo).maxCoeff();
  }
  std::nth_element(sizes_.begin(), sizes_.begin() + n / 2, sizes_.end());
  const Vec2 ext = dom.hi - dom.lo;
  double h = std::max(sizes_[n / 2], 1e-12 * std::max(1.0, ext.maxCoeff()));
  // Cap the cell count at about 4N (a few huge blocks must not blow the grid up).
  const double max_cells = 4.0 * n + 16.0;
  while ((std::floor(ext.x() / h) + 1.0) * (std::floor(ext.y() / h) + 1.0) > max_cells) h *= 1.5;
  const int nx = static_cast<int>(std::floor(ext.x() / h)) + 1;
  const int ny = static_cast<int>(std::floor(ext.y() / h)) + 1;
  const double inv = 1.0 / h;
  auto cx = [&](double x) { return std::clamp(static_cast<int>((x - dom.lo.x()) * inv), 0, nx - 1); };
  auto cy = [&](double y) { return std::clamp(static_cast<int>((y - dom.lo.y()) * inv), 0, ny - 1); };

  // Counting sort of (cell, block) entries.
  cell_start_.assign(static_cast<size_t>(nx) * ny + 1, 0);
  for (int i = 0; i < n; ++i)
    for (int y = cy(boxes[i].lo.y()); y <= cy(boxes[i].hi.y()); ++y)
      for (int x = cx(boxes[i].lo.x()); x <= cx(boxes[i].hi.x()); ++x)
        ++cell_start_[static_cast<size_t>(y) * nx + x + 1];
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_items_.resize(cell_start_.back());
  {
    std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (int i = 0; i < n; ++i)
      for (int y = cy(boxes[i].lo.y()); y <= cy(boxes[i].hi.y()); ++y)
        for (int x = cx(boxes[i].lo.x()); x <= cx(boxes[i].hi.x()); ++x)
          cell_items_[fill[static_cast<size_t>(y) * nx + x]++] = i;
  }

  // A pair belongs to the cell holding the lower-left corner of the boxes' overlap.
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const size_t c = static_cast<size_t>(y) * nx + x;
      for (int a = cell_start_[c]; a < cell_start_[c + 1]; ++a)
        for (int b = a + 1; b < cell_start_[c + 1]; ++b) {
          const int i = cell_items_[a], j = cell_items_[b];
          const Box& bi = boxes[i];
          const Box& bj = boxes[j];
          if (!bi.overlaps(bj)) continue;
          if (cx(std::max(bi.lo.x(), bj.lo.x())) != x || cy(std::max(bi.lo.y(), bj.lo.y())) != y)
            continue;
          pairs_.emplace_back(std::min(i, j), std::max(i, j));
        }
    }
  std::sort(pairs_.begin(), pairs_.end());
  return pairs_;
}

std::vector<std::pair<int, int>> brute_force_pairs(std::span<const Box> boxes) {
  std::vector<std::pair<int, int>> out;
  const int n = static_cast<int>(boxes.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (boxes[i].overlaps(boxes[j])) out.emplace_back(i, j);
  return out;
}

}  // namespace rheodda::contact
