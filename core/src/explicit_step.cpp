// The explicit step (docs/reference/explicit-step.md; ../shared/reference/explicit-dda.md):
// a dynamic step of dt taken in n cycles of central difference instead of one implicit
// solve. The contacts are detected once, on the step-start geometry (begin_step, with the
// search reaching the step's motion as for the implicit step: the contact list stays valid
// over the cycles the way a Verlet list does while nothing moves beyond its margin), and
// linearized there as in the implicit step; the blocks' geometry and the creep laws move
// once, at the step's end (end_step, accept). Within the step, with D the displacements
// since its start (6 per block, the seed's eq. 27 unknowns) and V their rates:
//     R(D, V, t) = F(t) - K D - C V - f_c(D, V)                                     (1)
// F the block loads (gravity, initial stress, point loads, water, fixed points) linear in
// t between the step's ends, K the blocks' elastic and fixed-point stiffness (a held
// rotation's spring k_r g g^T with it, block_terms.hpp: in the omega bound of (3) at its
// frequency sqrt(k_r / (rho J)) = sqrt(p/m), a fixed point's; assemble_blocks), C the block
// damping on the strain terms (Material::damping_ratio's tau S E_e, else (4)), f_c the contacts'
// forces with each contact's state decided at D (contact_cycles.cpp). Central difference
// (Newmark beta = 0, gamma = 1/2) with the block mass M = rho int T^T T dA (Shi 1988):
//     V_(1/2) = V_0 + h/2 M^-1 R_0,  D_(k+1) = D_k + h V_(k+1/2),
//     V_(k+3/2) = V_(k+1/2) + h M^-1 R_(k+1),  V_n = V_(n-1/2) + h/2 M^-1 R_n         (2)
// with the cycle h = dt / n a share (Settings::explicit_safety) of the stable one. Central
// difference with a dashpot is stable for h <= 2/omega (sqrt(1 + zeta^2) - zeta); with
// zeta = c / (2 omega), c bounding M^-1 C, that is h <= 2 / (sqrt(omega^2 + c^2/4) + c/2)
// (3), smallest at the largest omega: omega_max^2 and c are bounded per block by the
// largest eigenvalues of M^-1 K' and M^-1 C' (K', C' the block's own terms plus the
// contacts' and the bolts' bounds, ContactModel::cycle_stiffness, BoltSet::cycle_stiffness).
// The bolts (bolt_cycles.cpp) add their forces f_b(D, V) beside f_c in (1): each bolt's
// elastic-plastic force along its axis at D, with a dashpot as the contacts' (5).
// Damping (Settings::explicit_damping, zeta): the implicit step's scheme damps the contacts'
// and the blocks' elastic vibrations within a step; the cycles resolve them, so what has no
// damping of its own takes some. A block's strain modes, modal damping at zeta
//     C_e = M_e Phi diag(2 zeta omega_i) Phi^T M_e,  K_e Phi = M_e Phi diag(omega_i^2)   (4)
// (K_e = S E_e, M_e the strain rows of M; Phi M_e-orthonormal). The contacts, dashpots
// c = tau k beside each spring with tau = 2 zeta / omega_max                          (5)
// (stiffness-proportional: the scene's highest mode at zeta, the lower ones less), so that
// the cycle shortens by no more than sqrt(1 + zeta^2) - zeta. Per-contact dashpots at zeta
// on the reduced mass would overdamp a block held by many contacts (zeta sqrt(n/2) on its
// n springs) and shorten the cycle by as much.
// Density scaling (Settings::stage_cycles), in the dynamic stages of a static analysis only,
// where the state at rest is what counts: a block's mass matrix scaled by s >= 1 (its loads
// kept) so that no step needs more than stage_cycles cycles                             (6)
// (UDEC's and PFC's density scaling for static solutions; Cundall 1982).
// Local damping (Settings::stage_local_damping, alpha), in the same stages: Cundall's on each
// of the block's mass-normalised unknowns q = L^T v (M = L L^T): |q_i| loses alpha |r_i| h  (7)
// at each kick, r = L^-1 R, never more than it has
// The unbalanced-force ratio (SettleStage::force_ratio; UDEC's "ratio", Itasca): at the
// step's end, over the blocks that move, max_k |R_k| / mean_k |F_k|, R_k the translation rows
// of (1) at the last cycle and F_k those of the loads                                  (8)
// Blocks held at two or more fixed points (or at one and in rotation; count_held) and
// removed blocks do not move. Every block and
// every contact is updated on its own: the cycles run in parallel (OpenMP) and give the
// same bits whatever the number of threads (contacts gathered per block in a fixed order).
// Every Engine::kStopPollCycles cycles they look at the run's stop request
// (Engine::set_stop_request): a stop asked abandons the step as a cut step is.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "block_terms.hpp"
#include "cycle_kernels.hpp"
#include "engine_impl.hpp"

namespace rheodda::core {

namespace {

/// More cycles than this in one step is a scene the explicit step cannot take.
constexpr double kMaxCycles = 1.0e8;

/// Density scaling (6): passes after the first that raise the scales of the blocks still
/// below the wanted cycle.
constexpr int kScalingPasses = 3;

/// (4): each strain mode of a block damped at the ratio zeta.
Eigen::Matrix3d modal_strain_damping(const Eigen::Matrix3d& K, const Eigen::Matrix3d& M, double zeta) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(K, M);
  const Eigen::Matrix3d& phi = es.eigenvectors();  // M-orthonormal
  const Eigen::Vector3d w = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix3d Mphi = M * phi;
  return Mphi * (2.0 * zeta * w).asDiagonal() * Mphi.transpose();
}

}  // namespace

Engine::Impl::CycleBlocks Engine::Impl::cycle_blocks(double dt, bool unscaled) const {
  const Settings& s = model.settings;
  const std::size_t nb = st.blocks.size();
  CycleBlocks out;
  std::vector<Mat6> K_end;
  assemble_blocks(dt, st.time, out.K, out.F0, false);  // (1): the loads at the step's start and end, K
  assemble_blocks(dt, st.time + dt, K_end, out.dF, false);
  out.dF -= out.F0;
  out.loads_change = out.dF.lpNorm<Eigen::Infinity>() > 0.0;
  out.frozen = frozen_blocks();
  std::vector<Mat6> bound = out.K;  // K' of (3): the block's own stiffness and its contacts' bound
  contacts->cycle_stiffness(bound);
  if (!model.bolts.empty()) bolt_set.cycle_stiffness(bound);  // (4) of bolts.hpp (bolt_cycles.cpp)
  // (6) Density scaling (Settings::stage_cycles): in a dynamic stage of a static analysis a
  // block whose stable cycle is below h_wanted has its mass matrix scaled by s >= 1, which
  // divides omega^2 by s and its damping rate by at least sqrt(s): s = (h_wanted / h)^2
  // brings its cycle to h_wanted. The contacts' dashpots follow the new omega_max (5), which
  // may shorten another block's cycle: a few passes settle it. A block's scale only rises
  // within a stage (from BlockState::mass_scale), so that its velocity is rescaled once, with
  // its kinetic energy kept (cycle_trial).
  out.scale.assign(nb, 1.0);
  const bool scaled = !unscaled && density_scaling_now();
  const double h_wanted = scaled ? dt / (s.stage_cycles * s.explicit_safety) : 0.0;
  if (scaled)
    for (std::size_t k = 0; k < nb; ++k) out.scale[k] = st.blocks[k].mass_scale;
  std::vector<double> h(nb, std::numeric_limits<double>::infinity());
  for (int pass = 0;; ++pass) {
    cycle_block_pass(bound, out, h);
    if (!scaled || out.h_stable >= h_wanted || pass == kScalingPasses) break;
    for (std::size_t k = 0; k < nb; ++k)
      if (h[k] < h_wanted) out.scale[k] *= (h_wanted / h[k]) * (h_wanted / h[k]);
  }
  return out;
}

void Engine::Impl::cycle_block_pass(const std::vector<Mat6>& bound, CycleBlocks& out, std::vector<double>& h) const {
  const Settings& s = model.settings;
  const std::size_t nb = st.blocks.size();
  // Mass, block damping and the stable cycle (3) per block.
  out.M_inv.assign(nb, Mat6::Zero());
  out.L.assign(nb, Mat6::Zero());
  out.C.assign(nb, Eigen::Matrix3d::Zero());
  out.h_stable = std::numeric_limits<double>::infinity();
  out.stable_block = -1;
  std::vector<Mat6> damping(nb, Mat6::Zero());
  std::vector<Eigen::LLT<Mat6>> mass(nb);
  std::vector<double> w2(nb, 0.0);
  double w2_max = 0.0;
  for (std::size_t k = 0; k < nb; ++k) {
    h[k] = std::numeric_limits<double>::infinity();
    if (out.frozen[k]) continue;
    const BlockState& b = st.blocks[k];
    const Material& mat = model.materials[b.material];
    const Mat6 M = out.scale[k] * mat.density * unit_mass_matrix(moments[k]);
    mass[k].compute(M);
    out.M_inv[k] = mass[k].solve(Mat6::Identity());
    out.L[k] = mass[k].matrixL();
    const Eigen::Matrix3d Ke = moments[k].S * elastic[b.material];
    if (const double tau = strain_damping_time(moments[k], mat, elastic[b.material]); tau > 0.0)
      out.C[k] = tau * Ke;  // the material's Kelvin-Voigt damping (block_terms.hpp)
    else if (s.explicit_damping > 0.0)
      out.C[k] = modal_strain_damping(Ke, M.block<3, 3>(3, 3), s.explicit_damping);  // (4)
    damping[k].block<3, 3>(3, 3) += out.C[k];
    w2[k] = cycles::largest_eigenvalue(mass[k], bound[k]);
    w2_max = std::max(w2_max, w2[k]);
  }
  // (5): the contacts' dashpots, stiffness-proportional at tau = 2 zeta / omega_max.
  const double tau = s.explicit_damping > 0.0 && w2_max > 0.0 ? 2.0 * s.explicit_damping / std::sqrt(w2_max) : 0.0;
  contacts->cycle_damping(tau, damping);
  if (!model.bolts.empty()) bolt_set.cycle_damping(tau, damping);  // the bolts' dashpots, as (5)
  out.tau = tau;
  for (std::size_t k = 0; k < nb; ++k) {
    if (out.frozen[k] || !(w2[k] > 0.0)) continue;  // nothing stiff on it: free flight sets no limit
    const double c = cycles::largest_eigenvalue(mass[k], damping[k]);
    h[k] = 2.0 / (std::sqrt(w2[k] + 0.25 * c * c) + 0.5 * c);  // (3)
    if (h[k] < out.h_stable) out.h_stable = h[k], out.stable_block = static_cast<int>(k);
  }
}

Engine::StableCycle Engine::Impl::stable_cycle() {
  contacts->begin_step(views, step_context(model.settings.dt));
  if (!model.bolts.empty()) bolt_set.begin_step(model, st.blocks, st.bolts, model.settings.dt);
  StableCycle out;
  try {
    if (contacts->begin_cycles(views, model.settings.threads)) {
      const CycleBlocks b = cycle_blocks(model.settings.dt, true);
      out.cycle = model.settings.explicit_safety * b.h_stable;
      out.block = b.stable_block;
    }
  } catch (...) {
    contacts->abandon_step();
    throw;
  }
  contacts->abandon_step();
  return out;
}

std::vector<double> Engine::Impl::block_cycles() {
  // cycle_blocks keeps each block's cycle (3) to itself; a second pass over its blocks, on
  // the same bound and masses, gives them.
  std::vector<double> h(st.blocks.size(), std::numeric_limits<double>::infinity());
  contacts->begin_step(views, step_context(model.settings.dt));
  if (!model.bolts.empty()) bolt_set.begin_step(model, st.blocks, st.bolts, model.settings.dt);
  try {
    if (contacts->begin_cycles(views, model.settings.threads)) {
      CycleBlocks b = cycle_blocks(model.settings.dt, true);
      std::vector<Mat6> bound = b.K;
      contacts->cycle_stiffness(bound);
      if (!model.bolts.empty()) bolt_set.cycle_stiffness(bound);
      cycle_block_pass(bound, b, h);
      for (double& x : h) x *= model.settings.explicit_safety;
    }
  } catch (...) {
    contacts->abandon_step();
    throw;
  }
  contacts->abandon_step();
  return h;
}

Engine::Impl::Trial Engine::Impl::cycle_trial(double dt, StepReport& rep) {
  const Settings& s = model.settings;
  const std::size_t nb = st.blocks.size();
  const auto nbi = static_cast<std::ptrdiff_t>(nb);
  const int threads = cycles::begin(*contacts, views, s.threads);
  auto t0 = Clock::now();
  const CycleBlocks blocks = cycle_blocks(dt);
  const bool bolts = !model.bolts.empty();
  if (bolts) bolt_set.begin_cycles(blocks.tau, static_cast<int>(nb), s.threads);  // bolt_cycles.cpp
  const std::vector<Mat6>& K = blocks.K;
  const std::vector<Mat6>& M_inv = blocks.M_inv;
  const std::vector<Eigen::Matrix3d>& C = blocks.C;
  const std::vector<char>& frozen = blocks.frozen;
  const Eigen::VectorXd& F0 = blocks.F0;
  const Eigen::VectorXd& dF = blocks.dF;
  const bool loads_change = blocks.loads_change;
  const double h_stable = blocks.h_stable;
  const int stable_block = blocks.stable_block;
  const double h_allowed = s.explicit_safety * h_stable;
  const double wanted = std::isfinite(h_allowed) ? std::ceil(dt / h_allowed) : 1.0;
  if (!(wanted <= kMaxCycles))
    throw std::runtime_error("step " + std::to_string(st.step) + " at time " + std::to_string(st.time) +
                             ": the explicit step needs " + std::to_string(wanted) + " cycles of " +
                             std::to_string(h_allowed) + " for a step of " + std::to_string(dt) +
                             " (its stable cycle is set by block " + std::to_string(stable_block) +
                             "); give the implicit integrator or a shorter step");
  const int n = std::max(1, static_cast<int>(wanted));
  const double h = dt / n;
  rep.assembly_seconds += seconds_since(t0);
  t0 = Clock::now();

  // (2): the cycles.
  const double ratio = ratio_now();
  const double alpha = local_damping_now();
  Eigen::VectorXd V = Eigen::VectorXd::Zero(6 * nbi), Dn = Eigen::VectorXd::Zero(6 * nbi), f;
  // (6): a block whose scale rose keeps its kinetic energy: v sqrt(s_old / s_new).
  for (std::size_t k = 0; k < nb; ++k)
    if (!frozen[k])
      V.segment<6>(6 * static_cast<Eigen::Index>(k)) =
          ratio * std::sqrt(st.blocks[k].mass_scale / blocks.scale[k]) * st.blocks[k].velocity;
  // The work the blocks' damping takes (strain damping, local damping), per block, summed
  // over the blocks in order.
  std::vector<double> damped(nb, 0.0);
  // |R| of each block's translation at the step's end, where a stage's rest test asks for it (8).
  const bool force_ratio_wanted = s.settle.force_ratio > 0.0 && settling();
  std::vector<double> unbalanced(force_ratio_wanted ? nb : 0, 0.0);
  // One thread works without a parallel region (cycle_kernels.hpp, kParallelBlocks).
  const bool parallel_blocks = threads > 1 && nbi >= cycles::kParallelBlocks;
  for (int c = 0; c <= n; ++c) {
    poll_stop(c);  // a stop asked within the step: abandoned by the caller (solve_trial)
    const double w = static_cast<double>(c) / n;
    const double kick = (c == 0 || c == n) ? 0.5 * h : h;
    const bool drift = c < n;
    contacts->cycle_forces(Dn, V, kick, f);
    if (bolts) bolt_set.cycle_forces(Dn, V, kick, f);  // added per block after the contacts' sum
    const auto kick_block = [&](std::ptrdiff_t k) {
      if (frozen[k]) return;
      auto Dk = Dn.segment<6>(6 * k);
      auto Vk = V.segment<6>(6 * k);
      Vec6 R = F0.segment<6>(6 * k) - K[k] * Dk - f.segment<6>(6 * k);
      if (loads_change) R += w * dF.segment<6>(6 * k);
      const Vec3 strain_force = C[k] * Vk.tail<3>();
      R.tail<3>() -= strain_force;
      if (force_ratio_wanted && c == n) unbalanced[k] = R.head<2>().norm();
      // The strain damping's work in this kick: its force times kick (v_before + u)/2, u the
      // kicked velocity before local damping. Summed over the kicks, these are the scheme's
      // exact discrete work (the kinetic energy a kick changes is kick R.(v_before + u)/2).
      const Vec3 v_before = Vk.tail<3>();
      const Vec6 dv = kick * (M_inv[k] * R);
      damped[k] += 0.5 * kick * strain_force.dot(2.0 * v_before + dv.tail<3>());
      if (alpha > 0.0) {
        damped[k] += cycles::damped_kick(blocks.L[k], R, kick, alpha, Vk);  // (7): the kinetic energy it took
      } else {
        Vk += dv;
      }
      if (drift) Dk += h * Vk;
    };
    if (parallel_blocks) {
#pragma omp parallel for schedule(static) num_threads(threads)
      for (std::ptrdiff_t k = 0; k < nbi; ++k) kick_block(k);
    } else {
      for (std::ptrdiff_t k = 0; k < nbi; ++k) kick_block(k);
    }
  }
  cycle_block_damping = 0.0;
  for (const double x : damped) cycle_block_damping += x;
  cycle_force_ratio = force_ratio_wanted ? cycles::unbalanced_force_ratio(unbalanced, F0 + dF, frozen) : 0.0;
  rep.solve_seconds += seconds_since(t0);
  D = Dn;
  cycle_velocity.resize(nb);
  for (std::size_t k = 0; k < nb; ++k) cycle_velocity[k] = V.segment<6>(6 * static_cast<Eigen::Index>(k));
  cycle_scale = blocks.scale;
  rep.mass_scale = blocks.scale.empty() ? 1.0 : *std::max_element(blocks.scale.begin(), blocks.scale.end());
  rep.cycles = n;
  rep.cycle_dt = h;
  rep.stable_block = stable_block;
  return cycles::end(*contacts, bolt_set, bolts, views, D, V, rep);
}

}  // namespace rheodda::core
