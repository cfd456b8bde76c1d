// The velocity a block keeps when fixed points begin or stop holding it
// (held_velocity.hpp, where the formulas are derived).
#include "held_velocity.hpp"

#include <cmath>

#include "block_terms.hpp"
#include "rheodda/contact/kinematics.hpp"

namespace rheodda::core {

void add_held_rows(HeldRows& J, const Vec2& c, const Vec2& x, const Eigen::Matrix2d& held) {
  const contact::Mat26 T = contact::displacement_matrix(c, x);
  for (int d = 0; d < 2; ++d) {
    if (held(d, d) == 0.0) continue;
    J.conservativeResize(J.rows() + 1, Eigen::NoChange);
    J.row(J.rows() - 1) = T.row(d);
  }
}

void add_fixed_point_rows(HeldRows& J, const Vec2& c, const Vec2& x, const PolygonIntegrals& g, const FixedPoint& fp) {
  add_held_rows(J, c, x, fp.held());
  if (!fp.hold_rotation) return;
  J.conservativeResize(J.rows() + 1, Eigen::NoChange);
  J.row(J.rows() - 1) = std::sqrt((g.Sxx + g.Syy) / g.S) * mean_rotation_row(g).transpose();
}

Vec6 held_velocity(const Eigen::Matrix<double, 6, 6>& M, const HeldRows& J, const Vec6& v, double size) {
  if (J.rows() == 0) return v;
  // Columns scaled to one unit (translations [-], rotation and strains x size
  // [length]) so that the rank does not depend on the units: J v = (J Sc)(Sc^-1 v).
  Vec6 scale;
  scale << 1.0, 1.0, 1.0 / size, 1.0 / size, 1.0 / size, 1.0 / size;
  const Eigen::MatrixXd Js = J * scale.asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeFullV);
  svd.setThreshold(1e-10);
  const Eigen::Index rank = svd.rank();
  if (rank >= 6) return Vec6::Zero();
  // N: a basis of the null space of J (the last 6 - rank right singular vectors).
  const Eigen::MatrixXd N = scale.asDiagonal() * svd.matrixV().rightCols(6 - rank);
  const Eigen::MatrixXd MN = M * N;
  return N * (N.transpose() * MN).ldlt().solve(MN.transpose() * v);
}

}  // namespace rheodda::core
