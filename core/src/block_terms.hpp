// Block sub-matrix formulas shared by the engine (engine.cpp) and its energy
// balance (energy.cpp): the elastic matrix, the unit mass matrix and the value
// of a point-load history (Shi 1988; docs/reference/engine.md, "Sub-matrices").
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "rheodda/core/block_system.hpp"
#include "rheodda/core/defaults.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/core/polygon.hpp"

namespace rheodda::core {

/// Elastic matrix E_e relating (sigma_x, sigma_y, tau_xy) to (ex, ey, gxy) [stress]
/// (Shi 1988, elastic stress submatrix):
///   plane stress: E/(1-nu^2)        | 1   nu  0         |
///                                   | nu  1   0         |
///                                   | 0   0   (1-nu)/2  |
///   plane strain: E/((1+nu)(1-2nu)) | 1-nu nu   0        |
///                                   | nu   1-nu 0        |
///                                   | 0    0    (1-2nu)/2|
inline Eigen::Matrix3d elastic_matrix(const Material& m) {
  const double E = m.young_modulus, nu = m.poisson_ratio;
  Eigen::Matrix3d e;
  if (m.plane == PlaneMode::plane_stress) {
    e << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
    e *= E / (1.0 - nu * nu);
  } else {
    e << 1.0 - nu, nu, 0.0, nu, 1.0 - nu, 0.0, 0.0, 0.0, 0.5 * (1.0 - 2.0 * nu);
    e *= E / ((1.0 + nu) * (1.0 - 2.0 * nu));
  }
  return e;
}

/// int T^T T dA over a block with central moments (S, a = int dx^2,
/// b = int dy^2, c = int dx dy), dx = x - x0, dy = y - y0 (the first moments
/// vanish about the centroid). Shi 1988, mass (inertia) submatrix / rho.
inline Mat6 unit_mass_matrix(const PolygonIntegrals& m) {
  const double S = m.S, a = m.Sxx, b = m.Syy, c = m.Sxy;
  Mat6 M = Mat6::Zero();
  M(0, 0) = S;
  M(1, 1) = S;
  M(2, 2) = a + b;
  M(2, 3) = -c;
  M(2, 4) = c;
  M(2, 5) = 0.5 * (a - b);
  M(3, 3) = a;
  M(3, 5) = 0.5 * c;
  M(4, 4) = b;
  M(4, 5) = 0.5 * c;
  M(5, 5) = 0.25 * (a + b);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < i; ++j) M(i, j) = M(j, i);
  return M;
}

/// Retardation time tau [time] of a block's Kelvin-Voigt strain damping
/// (Material::damping_ratio zeta; docs/reference/engine.md, "Block damping"): the viscous
/// stress E_e tau eps_dot is stiffness proportional, so a strain mode of angular
/// frequency omega has the damping ratio tau omega / 2; tau = 2 zeta / omega_1
/// gives the block's lowest strain mode the ratio zeta (its higher modes more).
/// omega_1^2 is the smallest eigenvalue of K_e v = omega^2 M_e v with K_e = S E_e
/// and M_e = rho x the strain rows of int T^T T dA (Shi 1988; the rigid-body rows
/// couple only through rotation, left out: the strain modes of a block at rest).
inline double strain_damping_time(const PolygonIntegrals& g, const Material& m,
                                  const Eigen::Matrix3d& elastic) {
  if (!(m.damping_ratio > 0.0)) return 0.0;
  const Eigen::Matrix3d K = g.S * elastic;
  const Eigen::Matrix3d M = m.density * unit_mass_matrix(g).block<3, 3>(3, 3);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(K, M, Eigen::EigenvaluesOnly);
  const double w2 = es.eigenvalues().minCoeff();
  return w2 > 0.0 ? 2.0 * m.damping_ratio / std::sqrt(w2) : 0.0;
}

/// Piecewise-linear value of a load history at time t (held beyond the ends).
inline Vec2 load_at(const std::vector<LoadSample>& h, double t) {
  if (t <= h.front().time) return h.front().force;
  if (t >= h.back().time) return h.back().force;
  const auto it = std::upper_bound(h.begin(), h.end(), t,
                                   [](double v, const LoadSample& s) { return v < s.time; });
  const LoadSample& b = *it;
  const LoadSample& a = *(it - 1);
  const double w = (t - a.time) / (b.time - a.time);
  return (1.0 - w) * a.force + w * b.force;
}

/// A fixed point's hold on its block's rotation (FixedPoint::hold_rotation; docs/reference/
/// engine.md, "Holding a block's rotation"). The block's mean rotation theta [rad] is the
/// angle of the rotation R that carries its initial shape best onto its current one in the
/// least-squares sense of its area (of its mass), R = argmax tr(R^T F Sigma0), F the
/// block's affine map (BlockState::map_A) and Sigma0 = int X X^T dA0 the central second
/// moments of its initial polygon:
///   tan(theta) = ((F Sigma0)21 - (F Sigma0)12) / ((F Sigma0)11 + (F Sigma0)22)
/// (a rigid motion F = R(phi) gives theta = phi; for a square, Sigma0 isotropic, theta is the
/// polar angle of F, Block.rotation). To first order in a step's unknowns D (u0, v0, r0, ex,
/// ey, gxy; the seed's eq. 27) at the step-start geometry, with the central moments a =
/// int dx^2, b = int dy^2, c = int dx dy and J = a + b [length^4]:
///   dtheta = g . D,  g = m / J,  m = (0, 0, J, -c, c, (a - b)/2)
/// m the rotation row of int T^T T dA (unit_mass_matrix): rho m . v is the block's angular
/// momentum about its centroid. The spring's energy k_r (theta + g . D - theta_held)^2 / 2
/// adds, as Shi's fixed point adds p T^T S T and p T^T S (x0 - x) (Shi 1988; dda.md),
///   K += k_r g g^T,  F += -k_r (theta - theta_held) g
/// to the block's terms. Since M^-1 m = e_r0 / rho, the spring's force turns the block and
/// strains it not, and a rotation held at once takes the angular velocity only
/// (held_velocity.hpp). A square or a regular polygon (a = b, c = 0) has g = e_r0: the
/// spring acts on r0 alone. k_r = p J0/S0 (rotation_hold_stiffness, defaults.hpp).
struct RotationHold {
  double stiffness = 0.0;   ///< k_r [force x length/rad]
  double deflection = 0.0;  ///< theta - theta_held, within (-pi, pi] [rad]
  Vec6 row = Vec6::Zero();  ///< g: the change of theta per unit D [-] (zero on u0, v0)
};

/// theta of RotationHold: the mean rotation of a block of affine map F [-] whose initial
/// polygon has the central integrals g0 [rad], within (-pi, pi].
inline double mean_rotation(const PolygonIntegrals& g0, const Eigen::Matrix2d& F) {
  Eigen::Matrix2d sigma0;  // Sigma0 / S0: positive definite whichever the polygon's orientation [length^2]
  sigma0 << g0.Sxx, g0.Sxy, g0.Sxy, g0.Syy;
  sigma0 /= g0.S;
  const Eigen::Matrix2d A = F * sigma0;
  return std::atan2(A(1, 0) - A(0, 1), A(0, 0) + A(1, 1));
}

/// g = m / J of RotationHold: the first-order change of a block's mean rotation per unit
/// D at the geometry of central integrals g [-].
inline Vec6 mean_rotation_row(const PolygonIntegrals& g) {
  const double J = g.Sxx + g.Syy;
  Vec6 row;
  row << 0.0, 0.0, 1.0, -g.Sxy / J, g.Sxy / J, 0.5 * (g.Sxx - g.Syy) / J;
  return row;
}

/// The hold of `fp` (hold_rotation) on its block: p the fixed-point spring [force/length],
/// `initial` the block's initial polygon [length], F its affine map [-], g the central
/// integrals of its step-start geometry.
inline RotationHold rotation_hold(double p, const FixedPoint& fp, std::span<const Vec2> initial,
                                  const Eigen::Matrix2d& F, const PolygonIntegrals& g) {
  const PolygonIntegrals g0 = central_integrals(initial);
  RotationHold h;
  h.stiffness = rotation_hold_stiffness(p, g0);
  h.deflection = std::remainder(mean_rotation(g0, F) - fp.held_rotation.value_or(0.0), 2.0 * std::numbers::pi);
  h.row = mean_rotation_row(g);
  return h;
}

}  // namespace rheodda::core
