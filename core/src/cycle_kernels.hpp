// What the explicit cycles do per block, shared by the dynamic step's cycles
// (explicit_step.cpp) and the static steps by cycles (explicit_static.cpp): the bound of a
// block's highest frequency, Cundall's local damping on a kick, the unbalanced-force ratio,
// and the test of the step limit. The equations cited are those of explicit_step.cpp's header.
#pragma once

#include <omp.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/block_system.hpp"
#include "rheodda/core/contact_model.hpp"
#include "rheodda/core/model.hpp"
#include "engine_impl.hpp"

namespace rheodda::core::cycles {

/// Fewer blocks than this are kicked and drifted on one thread: a parallel region per cycle
/// costs more than their update (the same bits either way; contact_cycles.cpp likewise). One
/// thread works without a parallel region at all: a team of one still wakes a futex at the
/// region's barrier, a system call per cycle.
constexpr std::ptrdiff_t kParallelBlocks = 16;

/// The contacts take their cycles' arrays (ContactModel::begin_cycles) for cycles on `threads`
/// (Settings::threads); returns the threads the blocks' loops run on (0: OpenMP's default).
inline int begin(ContactModel& contacts, std::span<const contact::BlockView> views, int threads) {
  if (!contacts.begin_cycles(views, threads)) throw std::logic_error("the contact model cannot take explicit cycles");
  return threads > 0 ? threads : omp_get_max_threads();
}

/// After the last cycle, at D with the rates V its kick led to: the contacts (and the bolts,
/// `with_bolts`) take the cycles' states, their changes counted into rep; the trial
/// converged there.
inline StepTrial end(ContactModel& contacts, BoltSet& bolts, bool with_bolts, std::span<const contact::BlockView> views,
                     const Eigen::VectorXd& D, const Eigen::VectorXd& V, StepReport& rep) {
  StepTrial trial;
  trial.converged = true;
  trial.check = contacts.end_cycles(views, D, V);
  if (with_bolts) bolts.end_cycles(D, V);
  rep.changes += trial.check.changes;
  return trial;
}

/// Largest eigenvalue of M^-1 A for the block mass M (its Cholesky factor L), A symmetric:
/// omega_max^2 of (3) when A is the block's stiffness bound [1/time^2].
inline double largest_eigenvalue(const Eigen::LLT<Mat6>& L, const Mat6& A) {
  Mat6 B = L.matrixL().solve(A);
  B = L.matrixL().solve(B.transpose()).eval();  // L^-1 A L^-T, symmetric
  Eigen::SelfAdjointEigenSolver<Mat6> es(0.5 * (B + B.transpose()), Eigen::EigenvaluesOnly);
  return std::max(es.eigenvalues().maxCoeff(), 0.0);
}

/// (7): a kick of `kick` [time] of the velocity v of a block under its unbalanced force R,
/// with local damping alpha, in the block's mass-normalised unknowns q = L^T v (M = L L^T,
/// kinetic energy |q|^2 / 2), where it is Cundall's on decoupled unit masses: each component
/// of the kicked q loses alpha |r_i| kick in magnitude (r = L^-1 R), never more than it has.
/// Applied to the kicked velocity, it cannot reverse a motion or pump energy in (a force
/// -alpha |R_i| sign(v_i) on DDA's coupled rotation and strain unknowns, or beside a force
/// that already reverses the motion, can). Returns the kinetic energy it took, booked exactly
/// [force x length].
template <class V>
double damped_kick(const Mat6& L_lower, const Vec6& R, double kick, double alpha, V&& v) {
  const auto L = L_lower.triangularView<Eigen::Lower>();
  const Vec6 r = L.solve(R);
  const Vec6 u = L_lower.transpose() * v + kick * r;
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    const double m = std::abs(u(i)) - kick * alpha * std::abs(r(i));
    q(i) = m > 0.0 ? std::copysign(m, u(i)) : 0.0;
  }
  v = L.transpose().solve(q);
  return 0.5 * (u.squaredNorm() - q.squaredNorm());
}

/// The distance of each block's farthest vertex from its centroid [length].
inline std::vector<double> vertex_radii(const std::vector<BlockState>& blocks) {
  std::vector<double> radius(blocks.size(), 0.0);
  for (std::size_t k = 0; k < blocks.size(); ++k)
    for (const Vec2& v : blocks[k].vertices) radius[k] = std::max(radius[k], (v - blocks[k].centroid).norm());
  return radius;
}

/// A bound of the largest displacement of a block's vertices under its unknowns D [length]:
/// a vertex at r = p - c from the centroid moves by T(p) D = (D0 - r_y D2 + r_x D3 + r_y D5 / 2,
/// D1 + r_x D2 + r_y D4 + r_x D5 / 2) (contact/kinematics.hpp, displacement_matrix), so with
/// |r| <= radius, |T D| <= |(D0, D1)| + radius (|D2| + |D3| + |D4| + |D5| / 2).
inline double vertex_displacement_bound(const Vec6& D, double radius) {
  return std::hypot(D(0), D(1)) +
         radius * (std::abs(D(2)) + std::abs(D(3)) + std::abs(D(4)) + 0.5 * std::abs(D(5)));
}

/// Whether a vertex of `blocks` moves further than `allowed` [length] under d, the step
/// limit's test of the static steps by cycles ((3) of explicit_static.cpp): the answer of
/// Engine::Impl::max_vertex_displacement(d) > allowed, each block's vertices looked at only
/// where its bound (vertex_displacement_bound, `radius` from vertex_radii) does not rule it
/// out. The bound holds with a margin far above round-off (1e-12 of the limit), so the
/// answer is the same bits as the vertex-by-vertex test at a fraction of its cost.
inline bool moves_beyond(const std::vector<BlockState>& blocks, const std::vector<double>& radius,
                         const Eigen::VectorXd& d, double allowed) {
  const double sure = allowed * (1.0 - 1e-12);
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Vec6 Dk = d.segment<6>(6 * static_cast<Eigen::Index>(k));
    if (vertex_displacement_bound(Dk, radius[k]) <= sure) continue;
    if (std::sqrt(largest_vertex_displacement_sq(blocks[k], Dk)) > allowed) return true;
  }
  return false;
}

/// The unbalanced-force ratio (8): the largest unbalanced force of a moving block over the
/// mean applied force of the moving blocks [-]; 0 when no moving block carries a load.
/// `unbalanced`: |R| of each block's translation rows [force]; F: the loads [force].
inline double unbalanced_force_ratio(const std::vector<double>& unbalanced, const Eigen::VectorXd& F,
                                     const std::vector<char>& frozen) {
  double largest = 0.0, applied = 0.0;
  int counted = 0;
  for (std::size_t k = 0; k < unbalanced.size(); ++k) {
    if (frozen[k]) continue;
    largest = std::max(largest, unbalanced[k]);
    applied += F.segment<2>(6 * static_cast<Eigen::Index>(k)).norm();
    ++counted;
  }
  return applied > 0.0 ? largest / (applied / counted) : 0.0;
}

}  // namespace rheodda::core::cycles
