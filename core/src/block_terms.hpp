// Block sub-matrix formulas shared by the engine (engine.cpp) and its energy
// balance (energy.cpp): the elastic matrix, the unit mass matrix and the value
// of a point-load history (Shi 1988; docs/reference/engine.md, "Sub-matrices").
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "rheodda/core/block_system.hpp"
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

}  // namespace rheodda::core
