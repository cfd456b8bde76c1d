// Broad phase: which block pairs may touch.
//
// Why a grid. Testing all N(N-1)/2 block pairs (the classic DDA code) costs
// O(N^2). Here each block's bounding box, enlarged by the contact search
// distance, is binned into a uniform grid whose cell size is the median box
// size; a pair is reported by the one cell that holds the lower-left corner of
// the overlap of the two boxes, so no pair is reported twice and no set is
// needed. Large blocks (a base block under a wall) cover many cells: the cost
// stays O(N + cells covered), with the cell count capped at a few times N.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "rheodda/contact/kinematics.hpp"

namespace rheodda::contact {

/// Axis-aligned bounding box [length].
struct Box {
  Vec2 lo = Vec2::Zero();
  Vec2 hi = Vec2::Zero();
  bool overlaps(const Box& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
  }
};

/// Bounding box of a block's vertices enlarged by `margin` [length] on every side.
Box bounding_box(const BlockView& block, double margin);

/// Reusable uniform-grid broad phase (keeps its buffers between steps).
class BroadPhase {
 public:
  /// All pairs (i, j), i < j, whose boxes overlap, sorted. O(N) for blocks of
  /// similar size.
  const std::vector<std::pair<int, int>>& find_pairs(std::span<const Box> boxes);

 private:
  std::vector<std::pair<int, int>> pairs_;
  std::vector<int> cell_start_, cell_items_;
  std::vector<double> sizes_;
};

/// Reference for tests: every pair tested, O(N^2).
std::vector<std::pair<int, int>> brute_force_pairs(std::span<const Box> boxes);

}  // namespace rheodda::contact
