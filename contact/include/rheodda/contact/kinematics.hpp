// What the contact layer needs to know of blocks, and how it hands its terms
// back to the global system. The DDA host (core/) provides both; keeping them
// here lets contact/ be written and tested without the host (layering:
// laws <- contact <- core <- apps).
#pragma once

#include <Eigen/Dense>
#include <span>

namespace rheodda::contact {

using Vec2 = Eigen::Vector2d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat26 = Eigen::Matrix<double, 2, 6>;

/// DDA first-order displacement function of a block (Shi 1988; the seed's
/// T(i) in eq. 27; ../shared/reference/dda.md): the displacement of point p is
/// T(p) D with D = (u0, v0, r0, ex, ey, gxy) taken at the block centroid c.
///   T = | 1 0 -(y-y0)  (x-x0)   0      (y-y0)/2 |
///       | 0 1  (x-x0)    0    (y-y0)   (x-x0)/2 |
inline Mat26 displacement_matrix(const Vec2& c, const Vec2& p) {
  const double dx = p.x() - c.x(), dy = p.y() - c.y();
  Mat26 t;
  t << 1.0, 0.0, -dy, dx, 0.0, 0.5 * dy,
       0.0, 1.0, dx, 0.0, dy, 0.5 * dx;
  return t;
}

/// Read-only view of one block at the start of the current step.
struct BlockView {
  std::span<const Vec2> vertices;      ///< counter-clockwise, first vertex not repeated [length]
  Vec2 centroid = Vec2::Zero();        ///< [length]
  std::span<const int> edge_joint_set; ///< joint set index of edge k (vertex k -> k+1)
  /// Mass per unit thickness rho S [mass/length]; the contact dashpots of a
  /// joint set with a restitution use it (JointSet::restitution). 0: unknown;
  /// infinity: a block that does not move (held at fixed points).
  double mass = 0.0;
};

/// Receiver of contact terms of the global equilibrium system K D = F
/// (6x6 sub-matrices per block pair; the seed's eqs. 28-30).
class SystemSink {
 public:
  virtual ~SystemSink() = default;
  /// K_ij += k; for i != j the host also adds k^T to K_ji (call once per pair).
  virtual void add_stiffness(int i, int j, const Mat6& k) = 0;
  /// F_i += f.
  virtual void add_load(int i, const Vec6& f) = 0;
};

}  // namespace rheodda::contact
