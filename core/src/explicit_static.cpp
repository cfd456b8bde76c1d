// Static steps by explicit cycles (docs/reference/explicit-step.md, "Static steps by cycles";
// ../shared/reference/explicit-dda.md, "When only the state at rest matters"): with the
// explicit integrator and Settings::static_force_ratio, each static step of a static
// analysis (a creep step: the laws advanced over dt by the contacts' begin_step, as for the
// implicit step) is taken the way UDEC takes a creep step: cycles from rest back to
// equilibrium. The contacts are detected and linearized at the step start as in the
// explicit dynamic step (explicit_step.cpp); with D the displacements since the step start,
// the cycles seek
//     R(D) = F(t + dt) - K D - f_c(D) = 0                                            (1)
// (F the loads at the step's end, K the blocks' elastic and fixed-point stiffness, f_c the
// contacts' and bolts' forces, each contact's state decided at D; no dashpots, a static
// step has no rates). The masses are fictitious, only the state at rest counts: each block's
// mass matrix is scaled so that its stable cycle is the common fictitious cycle h = 1
// (Cundall 1982; UDEC's density scaling for static solutions),
//     M'_k = s_k M_k,  s_k = omega_k^2 h^2 / (2 safety)^2                             (2)
// omega_k^2 the largest eigenvalue of M_k^-1 K'_k (K'_k the block's stiffness and its
// contacts' and bolts' bound, (3) of explicit_step.cpp), so that h = safety 2 / omega'_k for
// every block; the kicks are locally damped at Settings::static_local_damping ((7) of
// explicit_step.cpp). The step has settled when the unbalanced-force ratio ((8) of
// explicit_step.cpp) is at most static_force_ratio, at the D it was found at, with every
// contact's creep seam linearized at the stress it carries there. The contacts are the
// step start's, linearized there, so a step moves no vertex further than the step limit
// (max_displacement_ratio w0, as every step): where the way to rest is longer (gravity
// switched on, a load applied at once) the step ends where a cycle would pass the limit,
// short of rest, and the next step goes on from there on contacts detected anew, as Shi's
// static steps approach rest over several steps                                      (3)
// (where the analysis has collapse stages, such a creep step counts as a mechanism). A step that
// does not settle within static_max_cycles is not taken: it is cut as an open-close
// iteration that does not settle is (and so located and taken as a collapse stage where
// the analysis has them). Unlike the implicit static step, the cycles keep no inertia term
// 2M/dt^2 (Shi's static step starts at rest but keeps the step's inertia): the state they
// find is the equilibrium itself, which the implicit step approaches as dt grows.
// The cycles look at the run's stop request as the dynamic step's do (explicit_step.cpp).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "block_terms.hpp"
#include "cycle_kernels.hpp"
#include "engine_impl.hpp"

namespace rheodda::core {

namespace {

/// The common fictitious cycle of (2) [time]: any value gives the same states (the scales
/// go with h^2), only the velocities' units depend on it.
constexpr double kCycle = 1.0;

}  // namespace

Engine::Impl::Trial Engine::Impl::relax_trial(double dt, StepReport& rep) {
  const Settings& s = model.settings;
  const std::size_t nb = st.blocks.size();
  const auto nbi = static_cast<std::ptrdiff_t>(nb);
  const int threads = cycles::begin(*contacts, views, s.threads);
  auto t0 = Clock::now();
  std::vector<Mat6> K;
  Eigen::VectorXd F;
  assemble_blocks(dt, st.time + dt, K, F, false);  // (1): the loads at the step's end, K
  const std::vector<char> frozen = frozen_blocks();
  std::vector<Mat6> bound = K;
  contacts->cycle_stiffness(bound);
  const bool bolts = !model.bolts.empty();
  if (bolts) {
    bolt_set.cycle_stiffness(bound);
    bolt_set.begin_cycles(0.0, static_cast<int>(nb), s.threads);  // no dashpots: no rates
  }
  // (2): each block's mass scaled to the common cycle, held as its Cholesky factor.
  std::vector<Mat6> L(nb, Mat6::Zero());
  std::vector<double> w2(nb, 0.0);
  double w2_max = 0.0;
  for (std::size_t k = 0; k < nb; ++k) {
    if (frozen[k]) continue;
    const Eigen::LLT<Mat6> M(model.materials[st.blocks[k].material].density * unit_mass_matrix(moments[k]));
    L[k] = M.matrixL();
    w2[k] = cycles::largest_eigenvalue(M, bound[k]);
    w2_max = std::max(w2_max, w2[k]);
  }
  if (!(w2_max > 0.0)) w2_max = 1.0;  // nothing stiff anywhere: free bodies, no equilibrium to find
  for (std::size_t k = 0; k < nb; ++k) {
    if (frozen[k]) continue;
    // A block with nothing stiff on it (a free body) takes the scene's stiffest scale: it
    // moves least per cycle, and the step does not settle anyway.
    const double w = w2[k] > 0.0 ? w2[k] : w2_max;
    L[k] *= kCycle * std::sqrt(w) / (2.0 * s.explicit_safety);
  }
  std::vector<double> unbalanced(nb, 0.0);  // |R| of each block's translation, for (8) of explicit_step.cpp
  rep.assembly_seconds += seconds_since(t0);
  t0 = Clock::now();

  const double alpha = s.static_local_damping;
  Eigen::VectorXd V = Eigen::VectorXd::Zero(6 * nbi), Dn = Eigen::VectorXd::Zero(6 * nbi), f, R(6 * nbi);
  int n = 0;
  double ratio = 0.0;
  bool settled = false, partial = false;
  const double allowed = max_displacement_ratio_now() * w0;  // (3): the step's displacement limit
  const std::vector<double> radius = cycles::vertex_radii(st.blocks);  // for its test at each cycle
  Eigen::VectorXd D_before;
  const bool parallel_blocks = threads > 1 && nbi >= cycles::kParallelBlocks;  // (cycle_kernels.hpp)
  for (;; ++n) {
    poll_stop(n);  // a stop asked within the step: abandoned by the caller (solve_trial)
    contacts->cycle_forces(Dn, V, kCycle, f);
    if (bolts) bolt_set.cycle_forces(Dn, V, kCycle, f);
    const auto residual = [&](std::ptrdiff_t k) {
      if (frozen[k]) return;
      R.segment<6>(6 * k) = F.segment<6>(6 * k) - K[k] * Dn.segment<6>(6 * k) - f.segment<6>(6 * k);
      unbalanced[k] = R.segment<2>(6 * k).norm();
    };
    if (parallel_blocks) {
#pragma omp parallel for schedule(static) num_threads(threads)
      for (std::ptrdiff_t k = 0; k < nbi; ++k) residual(k);
    } else {
      for (std::ptrdiff_t k = 0; k < nbi; ++k) residual(k);
    }
    ratio = cycles::unbalanced_force_ratio(unbalanced, F, frozen);
    // At rest, each contact whose creep law is not linear takes the seam of the stress it
    // carries there (as an iterate of the implicit step does), and the cycles go on from
    // there while any changed (bounded by the contacts' refinement limits).
    if (ratio <= s.static_force_ratio && contacts->cycle_relinearize(Dn) == 0) {
      settled = true;
      break;
    }
    if (n == s.static_max_cycles) break;
    if (ratio <= s.static_force_ratio) continue;  // the forces again, at the new seams
    D_before = Dn;
    const auto kick_block = [&](std::ptrdiff_t k) {
      if (frozen[k]) return;
      auto Vk = V.segment<6>(6 * k);
      // Leapfrog from rest: the first kick is half a cycle, as (2) of explicit_step.cpp.
      cycles::damped_kick(L[k], R.segment<6>(6 * k), n == 0 ? 0.5 * kCycle : kCycle, alpha, Vk);
      Dn.segment<6>(6 * k) += kCycle * Vk;
    };
    if (parallel_blocks) {
#pragma omp parallel for schedule(static) num_threads(threads)
      for (std::ptrdiff_t k = 0; k < nbi; ++k) kick_block(k);
    } else {
      for (std::ptrdiff_t k = 0; k < nbi; ++k) kick_block(k);
    }
    if (cycles::moves_beyond(st.blocks, radius, Dn, allowed)) {
      // The way to rest is longer than a step may move on its step-start contacts: the step
      // ends short of rest, where the limit is reached, and the next goes on (3).
      Dn = D_before;
      partial = true;
      break;
    }
  }
  rep.solve_seconds += seconds_since(t0);
  cycle_force_ratio = ratio;
  rep.cycles = n;
  rep.cycle_dt = 0.0;  // fictitious: the cycles of a static step span no time
  Trial trial;
  trial.iterations = n;
  if (partial && n == 0) {
    // Its first cycle would already pass the limit: nothing holds a block (a free body).
    trial.unsettled = "the static step's first cycle moves a vertex beyond the step limit (a block that nothing holds)";
    return trial;
  }
  if (!settled && !partial) {
    std::ostringstream why;
    why << "the static step's cycles did not settle: unbalanced-force ratio " << ratio << " after " << n
        << " cycles, static_force_ratio " << s.static_force_ratio << " (settings.static_max_cycles)";
    trial.unsettled = why.str();
    return trial;  // the caller abandons the step
  }
  D = Dn;
  Trial taken = cycles::end(*contacts, bolt_set, bolts, views, D, V, rep);
  taken.iterations = n;
  taken.short_of_rest = partial;
  return taken;
}

}  // namespace rheodda::core
