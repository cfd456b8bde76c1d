// The run-time state of one block: where it stands, its stress and motion,
// and the affine map from its initial to its current position. Apart from
// engine.hpp so that what works on blocks (the bolts, the energy balance)
// takes it without the engine.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "rheodda/core/model.hpp"

namespace rheodda::core {

using Mat2 = Eigen::Matrix2d;

/// Run-time state of one block.
struct BlockState {
  std::vector<Vec2> vertices;       ///< current vertices, counter-clockwise [length]
  std::vector<int> edge_joint_set;  ///< joint set of edge k (vertex k -> k+1)
  int material = 0;                 ///< index into Model::materials
  Vec2 centroid = Vec2::Zero();     ///< current centroid [length]
  Vec3 stress = Vec3::Zero();       ///< (sigma_x, sigma_y, tau_xy) [stress]
  Vec6 velocity = Vec6::Zero();     ///< (u0, v0, r0, ex, ey, gxy) rates [length/time, 1/time];
                                    ///< stays zero in a static analysis
  Vec6 acceleration = Vec6::Zero(); ///< at the end of the last step [length/time^2, 1/time^2];
                                    ///< kept by the trapezoidal rule only (zero otherwise)
  /// The factor on the block's mass matrix in a density-scaled dynamic stage
  /// (Settings::stage_cycles; docs/reference/explicit-step.md, "Density scaling") [-]; 1 otherwise.
  /// The velocity is that of the scaled block and the kinetic energy v^T (s M) v / 2.
  double mass_scale = 1.0;
  /// Affine map from initial to current position of a material point:
  /// x = map_A x0 + map_b (composed from every accepted step).
  Mat2 map_A = Mat2::Identity();    ///< [-]
  Vec2 map_b = Vec2::Zero();        ///< [length]
};

}  // namespace rheodda::core
