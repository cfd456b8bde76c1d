// Helpers shared by the core tests.
#pragma once

#include <vector>

#include "rheodda/core/model.hpp"

namespace rheodda::core::test {

/// A block of the default material with the given vertices [m] and, optionally, edge joint sets.
inline BlockDef block(std::vector<Vec2> vertices, std::vector<int> edge_joint_set = {}) {
  BlockDef b;
  b.vertices = std::move(vertices);
  b.edge_joint_set = std::move(edge_joint_set);
  return b;
}

}  // namespace rheodda::core::test
