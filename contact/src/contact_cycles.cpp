// Explicit cycles within a step (docs/reference/explicit-step.md): the contacts' forces at
// each cycle of core's explicit step, with every contact's state decided on its own at
// the cycle, and the records handed back to end_step at the step's end.
//
// A contact's springs are those of the implicit step (contact_springs.cpp): the normal
// spring p_n d_n and the shear spring k_s (d_t - s) to the locking point, both linearized
// on the step-start geometry (d_n = d_n0 + n_i.D_i + n_j.D_j, d_t = d_t0 + t_i.D_i +
// t_j.D_j; the seed's eqs. 17-18, 23-29), the creep seam folded into the shear spring as
// there (k_eff = k_s / (1 + k_s c/l), locking point shifted by -h; laws/contact_rheology.hpp).
// What differs is how the state is found: no open-close iteration, but at each cycle
//   - an open contact whose d_n > 0 closes, its shear spring unstretched where it touched;
//   - a closed contact whose normal force falls below -sigma_t l opens (and is no longer
//     intact);
//   - the shear spring's force k (d_t - s) beyond the Mohr-Coulomb strength
//     N tan(phi) + c l drags the locking point along (s grows) so that the force equals
//     the strength: the contact slides, and is no longer intact (residual friction and
//     cohesion at once); within the strength it is locked.
// This is the incremental elastic-plastic joint of explicit block codes (Cundall & Strack
// 1979; ../shared/reference/explicit-dda.md, "The block equations"): the slip is found by
// the spring's stretch, so a contact that stops sticks where it stopped, without the
// stick rule and anti-chattering of the iteration.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_geometry.hpp"
#include "rheodda/contact/strength.hpp"
#include "rheodda/contact/contact_system.hpp"

namespace rheodda::contact {

namespace {

int thread_count(int requested) { return requested > 0 ? requested : omp_get_max_threads(); }

/// Fewer contacts (blocks) than this are worked on one thread: a parallel region per cycle
/// costs more than their forces, and far more when the machine is loaded and a thread
/// waits for a core at every cycle. The results are the same bits either way.
constexpr std::ptrdiff_t kParallelContacts = 64;
constexpr std::ptrdiff_t kParallelBlocks = 16;

}  // namespace

void ContactSystem::begin_cycles(std::span<const BlockView> blocks, int threads) {
  const int block_count = static_cast<int>(blocks.size());
  cycle_threads_ = threads;
  cycled_ = true;
  const std::size_t n = work_.size();
  cycles_.resize(n);
  cycle_force_.assign(2 * n, Vec6::Zero());
  for (std::size_t c = 0; c < n; ++c) {
    const Contact& r = work_[c];
    const Hot& h = hot_[c];
    const JointSet& js = joint_sets_[r.joint_set];
    Cycle& y = cycles_[c];
    y.state = r.state;
    y.direction = r.slide_direction;
    y.intact = r.intact;
    y.tan_phi = tan_deg(js.friction_angle_of(true));
    y.tan_phi_residual = tan_deg(js.friction_angle_of(false));
    y.cohesion = js.cohesion_of(true);
    y.cohesion_residual = js.cohesion_of(false);
    y.shift = 0.0;
    y.cn = y.cs = 0.0;
    y.damped = y.nd = y.ts = 0.0;
    y.bound_i = std::isfinite(blocks[r.key.eblock].mass) ? 2.0 : 1.0;
    y.bound_j = std::isfinite(blocks[r.key.vblock].mass) ? 2.0 : 1.0;
    if (r.state == ContactState::sliding) {
      // A contact sliding at the step start carries its friction from the first cycle:
      // its spring starts stretched by the friction force over k (the elastic part of
      // an elastic-plastic joint's shear displacement).
      const double f = mohr_coulomb_strength(h.normal_force, h.tan_phi, h.cohesion, r.length);
      y.shift = h.dt0 + seams_[c].locking_shift - r.slide_direction * f / shear_stiffness(c);
    }
  }
  // The contacts of each block in the order of the records: the gather's fixed order.
  block_first_.assign(static_cast<std::size_t>(block_count) + 1, 0);
  for (const Contact& r : work_) ++block_first_[r.key.vblock + 1], ++block_first_[r.key.eblock + 1];
  for (int b = 0; b < block_count; ++b) block_first_[b + 1] += block_first_[b];
  block_entries_.resize(2 * n);
  std::vector<int> next(block_first_.begin(), block_first_.end() - 1);
  for (std::size_t c = 0; c < n; ++c) {
    block_entries_[next[work_[c].key.vblock]++] = static_cast<int>(2 * c);
    block_entries_[next[work_[c].key.eblock]++] = static_cast<int>(2 * c + 1);
  }
}

void ContactSystem::cycle_stiffness(std::vector<Mat6>& K) const {
  for (std::size_t c = 0; c < work_.size(); ++c) {
    const Contact& r = work_[c];
    const Hot& h = hot_[c];
    const Cycle& y = cycles_[c];
    const double ps = shear_stiffness(c);
    K[r.key.vblock].noalias() += y.bound_i * (h.pn * h.ni * h.ni.transpose() + ps * h.ti * h.ti.transpose());
    K[r.key.eblock].noalias() += y.bound_j * (h.pn * h.nj * h.nj.transpose() + ps * h.tj * h.tj.transpose());
  }
}

void ContactSystem::cycle_damping(double tau, std::vector<Mat6>& C) {
  for (std::size_t c = 0; c < work_.size(); ++c) {
    const Contact& r = work_[c];
    const Hot& h = hot_[c];
    Cycle& y = cycles_[c];
    if (joint_sets_[r.joint_set].restitution) {
      y.cn = h.cn, y.cs = h.cs;
    } else {
      y.cn = tau * h.pn;
      y.cs = tau * shear_stiffness(c);
    }
    if (!step_dynamic_ || (y.cn == 0.0 && y.cs == 0.0)) continue;
    C[r.key.vblock].noalias() += y.bound_i * (y.cn * h.ni * h.ni.transpose() + y.cs * h.ti * h.ti.transpose());
    C[r.key.eblock].noalias() += y.bound_j * (y.cn * h.nj * h.nj.transpose() + y.cs * h.tj * h.tj.transpose());
  }
}

void ContactSystem::cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double h_work,
                                 Eigen::VectorXd& f) {
  const auto n = static_cast<std::ptrdiff_t>(work_.size());
  const bool dashpots = step_dynamic_;
  const int threads = thread_count(cycle_threads_);
#pragma omp parallel for schedule(static) num_threads(threads) if (n >= kParallelContacts)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const auto c = static_cast<std::size_t>(k);
    const Contact& r = work_[c];
    const Hot& h = hot_[c];
    Cycle& y = cycles_[c];
    Vec6& fi = cycle_force_[2 * c];
    Vec6& fj = cycle_force_[2 * c + 1];
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    const double slip = h.ti.dot(Di) + h.tj.dot(Dj);
    const double reach = h.dt0 + seams_[c].locking_shift + slip;  // stretch from the step's locking point
    const double N = h.pn * dn;
    if (y.nd != 0.0 || y.ts != 0.0) {
      // The dashpot forces of the last cycle did work over the drift just made, h V (the
      // scheme's discrete work; their power at the lagged rate would overstate it for the
      // modes near the stable cycle, whose rates change sign from cycle to cycle).
      const auto Vi = V.segment<6>(6 * r.key.vblock);
      const auto Vj = V.segment<6>(6 * r.key.eblock);
      y.damped += h_work * (y.nd * (h.ni.dot(Vi) + h.nj.dot(Vj)) + y.ts * (h.ti.dot(Vi) + h.tj.dot(Vj)));
      y.nd = y.ts = 0.0;
    }
    if (y.state == ContactState::open) {
      if (!(N > 0.0)) {
        fi.setZero(), fj.setZero();
        continue;
      }
      y.state = ContactState::locked;  // touches: the shear spring locks here, unstretched
      y.shift = reach;
    } else if (N < -(y.intact ? joint_sets_[r.joint_set].tensile_strength * r.length : 0.0)) {
      y.state = ContactState::open;
      y.intact = false;
      fi.setZero(), fj.setZero();
      continue;
    }
    // Dashpots on the rates (JointSet::restitution, or explicit_damping), dynamic
    // steps only. The shear dashpot counts in the Mohr-Coulomb check with the spring: a joint
    // carries no more shear than its strength, whatever the rate (else a locked contact's
    // dashpot holds a block at the speed it slides with).
    double Nd = 0.0, Ts = 0.0;
    if (dashpots) {
      const auto Vi = V.segment<6>(6 * r.key.vblock);
      const auto Vj = V.segment<6>(6 * r.key.eblock);
      if (y.cn > 0.0) Nd = y.cn * (h.ni.dot(Vi) + h.nj.dot(Vj));
      if (y.cs > 0.0) Ts = y.cs * (h.ti.dot(Vi) + h.tj.dot(Vj));
    }
    const double ks = shear_stiffness(c);
    double T = ks * (reach - y.shift) + Ts;
    const double limit = mohr_coulomb_strength(N, y.intact ? y.tan_phi : y.tan_phi_residual,
                                  y.intact ? y.cohesion : y.cohesion_residual, r.length);
    if (std::abs(T) > limit) {
      // Slides: the spring, dragged along, carries the (residual) strength.
      y.intact = false;
      y.direction = T >= 0.0 ? 1 : -1;
      T = y.direction * mohr_coulomb_strength(N, y.tan_phi_residual, y.cohesion_residual, r.length);
      y.shift = reach - T / ks;
      y.state = ContactState::sliding;
      y.nd = Nd;  // the shear force is the strength: friction's, not a dashpot's
    } else {
      y.state = ContactState::locked;
      y.nd = Nd, y.ts = Ts;
    }
    fi.noalias() = (N + Nd) * h.ni + T * h.ti;
    fj.noalias() = (N + Nd) * h.nj + T * h.tj;
  }
  const auto nb = static_cast<std::ptrdiff_t>(block_first_.size()) - 1;
  f.resize(6 * nb);
#pragma omp parallel for schedule(static) num_threads(threads) if (nb >= kParallelBlocks)
  for (std::ptrdiff_t b = 0; b < nb; ++b) {
    Vec6 sum = Vec6::Zero();
    for (int e = block_first_[b]; e < block_first_[b + 1]; ++e) sum += cycle_force_[block_entries_[e]];
    f.segment<6>(6 * b) = sum;
  }
}

CheckResult ContactSystem::end_cycles(std::span<const BlockView> blocks, const Eigen::VectorXd& D) {
  CheckResult res;
  double scale = 0.0;
  for (std::size_t c = 0; c < work_.size(); ++c) {
    Contact& r = work_[c];
    Hot& h = hot_[c];
    const Cycle& y = cycles_[c];
    const ContactState before = h.start_state;
    r.state = y.state;
    if (y.state == ContactState::sliding) r.slide_direction = y.direction;
    if (!y.intact && r.intact) {
      // No longer intact: end_step's friction and the next step take the residual values.
      r.intact = false;
      h.tan_phi = y.tan_phi_residual;
      h.cohesion = y.cohesion_residual;
      h.tensile_strength = 0.0;
    }
    if (y.state == ContactState::locked && y.shift != 0.0) {
      // The locking point where the cycles left it: end_step's stretch d_t0 + slip counts from there.
      const BlockView& eb = blocks[r.key.eblock];
      r.locking_ratio += y.shift / (edge_end(eb, r.key.edge) - edge_start(eb, r.key.edge)).norm();
      h.dt0 -= y.shift;
    }
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    h.normal_force = h.assembled_normal_force = y.state == ContactState::open ? 0.0 : h.pn * dn;
    r.penetration = dn;
    if (y.state != ContactState::open) {
      res.max_penetration = std::max(res.max_penetration, dn);
      scale = std::max(scale, std::abs(h.normal_force));
    }
    if (y.state == before) continue;
    ++res.state_changes;
    if (before == ContactState::open) ++res.changes.closed;
    else if (y.state == ContactState::open) ++res.changes.opened;
    else if (y.state == ContactState::sliding) ++res.changes.slipped;
    else ++res.changes.stuck;
  }
  force_scale_ = scale;
  step_max_penetration_ = res.max_penetration;
  cycle_damping_ = 0.0;  // in the records' order: the same sum whatever the threads
  for (const Cycle& y : cycles_) cycle_damping_ += y.damped;
  return res;
}

}  // namespace rheodda::contact
