// The bolts in the explicit step's cycles (bolts.hpp; docs/reference/bolts.md, "In the
// explicit step"; docs/reference/explicit-step.md): the same bolt as in the implicit step,
// its force found at each cycle instead of by Newton's method within the open-close
// iteration.
//
// At a cycle with D the displacements since the step start, the ends are where (1) of
// bolts.hpp moves them, and the bolt's elastic force is (2) on that length,
//     N_e = k_eff (s0 - Delta e_p + L(D) - L0)                                     (C1)
// with Delta e_p the plastic elongation the step's cycles took so far. Beyond the yield
// force the bolt stretches plastically (elastic-perfectly plastic, bolt.hpp): the plastic
// elongation takes up the excess,
//     |N_e| > N_y:  Delta e_p += (N_e - s N_y) / k_eff,  N = s N_y  (s = sign N_e)   (C2)
// its plastic work N_y |increment| booked (the incremental elastic-plastic element of
// explicit codes: Cundall & Strack 1979, as the joints' shear in
// contact/src/contact_cycles.cpp). Within the yield force a dashpot beside the spring,
//     N = clamp(N_e + c n . (G_b V_b - G_a V_a), -N_y, N_y),  c = tau k_eff          (C3)
// (the stiffness-proportional damping of (5) of explicit_step.cpp; tau = 0 without
// explicit_damping). The generalized forces are (3) of bolts.hpp along the cycle's axis
// n(D): the bolt turns with the blocks exactly, as Newton's iterate does in the implicit
// step. The dashpot's force N_d = N - N_e of a cycle makes, with the bolt's other forces, a
// kick of length kick (h, h/2 at the step's first and last cycle; (2) of explicit_step.cpp),
// and its work is booked as the contacts' dashpots' (contact_cycles.cpp):
//     W_d += N_d kick (Ldot(V_before) + Ldot(V_after)) / 2,
//     Ldot(V) = g_b . V_b - g_a . V_a,  g = G^T n at the cycle's D                  (C4)
// V_before the rates the force was found at, V_after those its kick led to: the kinetic
// energy a kick changes is kick R . (V_before + V_after)/2, so (C4) is the scheme's own
// discrete work (docs/reference/explicit-step.md, "Energy balance"). The first half is
// booked at the cycle, the second at the next cycle (or end_cycles) once V_after is known.
// The rupture is checked at the step's end (commit), as in the implicit step.
//
// Each bolt is worked on its own (OpenMP); each block gathers its bolts' forces in the
// bolts' order, so that the sums are the same bits whatever the number of threads.
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "bolts.hpp"

namespace rheodda::core {

namespace {

/// Bound factor of an end's stiffness for the stable cycle: 2 when the other end is on a
/// block too (the two blocks' modes together, as the contacts' bound), 1 at a fixed anchor.
double bound_factor(const Bolt& bolt) { return bolt.block_b >= 0 ? 2.0 : 1.0; }

/// Ldot of (C4): the rate of the bolt's length at the rates V, g_b . V_b - g_a . V_a (g = G^T n;
/// a fixed anchor has no rate) [length/time].
double length_rate(const Bolt& bolt, const contact::Vec6& g_a, const contact::Vec6& g_b, const Eigen::VectorXd& V) {
  double r = -g_a.dot(V.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_a)));
  if (bolt.block_b >= 0) r += g_b.dot(V.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_b)));
  return r;
}

/// Fewer bolts than this are worked on one thread: a parallel region per cycle costs more
/// than a few bolts' forces (the results are the same bits either way).
constexpr std::ptrdiff_t kParallelBolts = 16;

}  // namespace

void BoltSet::cycle_stiffness(std::vector<contact::Mat6>& K) const {
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    const Trial& t = trials_[k];
    if (!t.active) continue;
    const Bolt& bolt = model_->bolts[k];
    const double f = bound_factor(bolt);
    // (4) at the step start, with the axial stiffness of the elastic branch whatever the mode:
    // a yielding bolt unloads elastically within the step.
    Eigen::Matrix2d K2 = t.at.K2 + (t.sign != 0 ? t.k_eff : 0.0) * t.at.n * t.at.n.transpose();
    K[bolt.block_a].noalias() += f * end_hessian(t.at.a, K2, t.at.curv_a);
    if (bolt.block_b >= 0) K[bolt.block_b].noalias() += f * end_hessian(t.at.b, K2, t.at.curv_b);
  }
}

void BoltSet::cycle_damping(double tau, std::vector<contact::Mat6>& C) const {
  if (!(tau > 0.0)) return;
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    const Trial& t = trials_[k];
    if (!t.active) continue;
    const Bolt& bolt = model_->bolts[k];
    const double f = bound_factor(bolt) * tau * t.k_eff;
    const contact::Vec6 g_a = t.at.a.G.transpose() * t.at.n;
    C[bolt.block_a].noalias() += f * g_a * g_a.transpose();
    if (bolt.block_b >= 0) {
      const contact::Vec6 g_b = t.at.b.G.transpose() * t.at.n;
      C[bolt.block_b].noalias() += f * g_b * g_b.transpose();
    }
  }
}

void BoltSet::begin_cycles(double tau, int block_count, int threads) {
  cycle_threads_ = threads;
  const std::size_t n = trials_.size();
  cycle_force_.assign(2 * n, contact::Vec6::Zero());
  for (Trial& t : trials_) {
    t.cycled = true;
    t.cycle_plastic = t.cycle_work = t.damper_half = 0.0;
    t.damper = tau * t.k_eff;
  }
  // The bolts of each block in the bolts' order: the gather's fixed order (CSR).
  block_first_.assign(static_cast<std::size_t>(block_count) + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (!trials_[k].active) continue;
    const Bolt& bolt = model_->bolts[k];
    ++block_first_[bolt.block_a + 1];
    if (bolt.block_b >= 0) ++block_first_[bolt.block_b + 1];
  }
  for (int b = 0; b < block_count; ++b) block_first_[b + 1] += block_first_[b];
  block_entries_.resize(static_cast<std::size_t>(block_first_.back()));
  std::vector<int> next(block_first_.begin(), block_first_.end() - 1);
  for (std::size_t k = 0; k < n; ++k) {
    if (!trials_[k].active) continue;
    const Bolt& bolt = model_->bolts[k];
    block_entries_[next[bolt.block_a]++] = static_cast<int>(2 * k);
    if (bolt.block_b >= 0) block_entries_[next[bolt.block_b]++] = static_cast<int>(2 * k + 1);
  }
}

void BoltSet::book_damper(std::size_t k, const Eigen::VectorXd& V) {
  Trial& t = trials_[k];
  if (t.damper_half == 0.0) return;
  t.cycle_work += t.damper_half * length_rate(model_->bolts[k], t.damper_g_a, t.damper_g_b, V);  // (C4)
  t.damper_half = 0.0;
}

void BoltSet::cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, Eigen::VectorXd& f) {
  const auto n = static_cast<std::ptrdiff_t>(trials_.size());
  const int threads = cycle_threads_ > 0 ? cycle_threads_ : omp_get_max_threads();
  // One thread works without a parallel region: a team of one still wakes a futex at the
  // region's barrier, a system call per cycle (cycle_kernels.hpp, kParallelBlocks).
  const bool parallel = threads > 1 && n >= kParallelBolts;
  const auto bolt_force = [&](std::ptrdiff_t i) {
    const auto k = static_cast<std::size_t>(i);
    Trial& t = trials_[k];
    if (!t.active) return;
    const Bolt& bolt = model_->bolts[k];
    const Point p = point(k, D);  // the ends and the axis at D
    const contact::Vec6 g_a = p.a.G.transpose() * p.n;  // d L / d D_a = -g_a, d L / d D_b = g_b
    const contact::Vec6 g_b = p.b.G.transpose() * p.n;
    // (C4), second half: the last cycle's dashpot force at the rates V its kick led to.
    book_damper(k, V);
    const double ny = bolt.yield_force;
    const double elastic = t.elastic_force(p.L);  // (C1)
    double N = 0.0;
    if (std::abs(elastic) > ny) {
      // (C2): yields; the plastic elongation takes up the excess, its work N_y |increment|.
      t.sign = elastic > 0.0 ? 1 : -1;
      const double plastic = (elastic - t.sign * ny) / t.k_eff;
      t.cycle_plastic += plastic;
      t.cycle_work += ny * std::abs(plastic);
      N = t.sign * ny;
    } else {
      // (C3): elastic, with its dashpot, within the yield force whatever the rate.
      t.sign = 0;
      N = elastic;
      if (t.damper > 0.0) {
        const double rate = length_rate(bolt, g_a, g_b, V);
        N = std::clamp(elastic + t.damper * rate, -ny, ny);
        const double damper = N - elastic;  // N_d [force]
        if (damper != 0.0) {
          // (C4), first half: at the rates the force was found at; the second at the next
          // cycle's (book_damper), along this cycle's axis.
          t.cycle_work += 0.5 * kick * damper * rate;
          t.damper_half = 0.5 * kick * damper;
          t.damper_g_a = g_a, t.damper_g_b = g_b;
        }
      }
    }
    // (3): -N g_a on block a, N g_b on block b.
    cycle_force_[2 * k].noalias() = -N * g_a;
    cycle_force_[2 * k + 1].noalias() = N * g_b;
  };
  const auto nb = static_cast<std::ptrdiff_t>(block_first_.size()) - 1;
  const auto gather = [&](std::ptrdiff_t b) {
    if (block_first_[b] == block_first_[b + 1]) return;
    contact::Vec6 sum = contact::Vec6::Zero();
    for (int e = block_first_[b]; e < block_first_[b + 1]; ++e) sum += cycle_force_[block_entries_[e]];
    f.segment<6>(6 * b) += sum;
  };
  if (parallel) {
#pragma omp parallel num_threads(threads)
    {
#pragma omp for schedule(static)
      for (std::ptrdiff_t i = 0; i < n; ++i) bolt_force(i);
#pragma omp for schedule(static)
      for (std::ptrdiff_t b = 0; b < nb; ++b) gather(b);
    }
  } else {
    for (std::ptrdiff_t i = 0; i < n; ++i) bolt_force(i);
    for (std::ptrdiff_t b = 0; b < nb; ++b) gather(b);
  }
}

void BoltSet::end_cycles(const Eigen::VectorXd& D, const Eigen::VectorXd& V) {
  // The mode of the last cycle stands (Trial::sign); the iterate at the end D, for the
  // creep error estimate (bolt_creep_error.cpp) and commit; the last cycle's dashpot work
  // completed at the step's end rates V (C4).
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    if (!trials_[k].active) continue;
    book_damper(k, V);
    trials_[k].at = point(k, D);
  }
}

}  // namespace rheodda::core
