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

/// Fewer contacts than this are worked on one thread: a parallel region per cycle costs
/// more than their forces, and far more when the machine is loaded and a thread waits for a
/// core at every cycle. The results are the same bits either way.
constexpr std::ptrdiff_t kParallelContacts = 64;

/// Contacts worked between two looks for the blocks they complete (cycle_forces).
constexpr std::ptrdiff_t kGatherChunk = 256;

/// One contact at one cycle (the file's head): its state, and its forces on its blocks
/// into their slots of `force`.
inline void cycle_contact(const cycles::Spring& p, cycles::State& y, Vec6* force, const Eigen::VectorXd& D,
                          const Eigen::VectorXd& V, double kick, bool dashpots) {
  Vec6& fi = force[p.slot_i];
  Vec6& fj = force[p.slot_j];
  const auto Di = D.segment<6>(6 * p.i);
  const auto Dj = D.segment<6>(6 * p.j);
  const double dn = p.dn0 + p.ni.dot(Di) + p.nj.dot(Dj);
  const double slip = p.ti.dot(Di) + p.tj.dot(Dj);
  const double reach = p.reach0 + slip;  // stretch from the step's locking point
  const double N = p.pn * dn;
  // The normal and shear rates, for the dashpots' work and their forces alike.
  double vn = 0.0, vt = 0.0;
  bool rates = false;
  const auto find_rates = [&] {
    const auto Vi = V.segment<6>(6 * p.i);
    const auto Vj = V.segment<6>(6 * p.j);
    vn = p.ni.dot(Vi) + p.nj.dot(Vj);
    vt = p.ti.dot(Vi) + p.tj.dot(Vj);
    rates = true;
  };
  if (y.nd != 0.0 || y.ts != 0.0) {
    // The second half of the last cycle's dashpot work: its forces (kept times half its
    // kick) at the rates its kick led to. With the first half, booked where the forces were
    // found, each force F does F kick (v_before + v_after)/2: the kinetic energy a kick
    // changes is kick R.(v_before + v_after)/2, so this is the scheme's discrete work (the
    // power at either rate alone overstates it for the modes near the stable cycle, whose
    // rates change sign from cycle to cycle).
    find_rates();
    y.damped += y.nd * vn + y.ts * vt;
    y.nd = y.ts = 0.0;
  }
  if (y.state == ContactState::open) {
    if (!(N > 0.0)) {
      fi.setZero(), fj.setZero();
      return;
    }
    y.state = ContactState::locked;  // touches: the shear spring locks here, unstretched
    y.shift = reach;
    y.attached += 0.5 * N * dn;  // the overlap the normal spring finds on touching, gained without work
  } else if (N < -(y.intact ? p.tension : 0.0)) {
    // Opens: both springs detach with the energy they hold (the shear spring's stretch
    // reach - shift, locked or sliding).
    const double stretch = reach - y.shift;
    y.released += 0.5 * N * dn + 0.5 * p.ks * stretch * stretch;
    y.state = ContactState::open;
    y.intact = false;
    fi.setZero(), fj.setZero();
    return;
  }
  // Dashpots on the rates (JointSet::restitution, or explicit_damping), dynamic
  // steps only. The shear dashpot counts in the Mohr-Coulomb check with the spring: a joint
  // carries no more shear than its strength, whatever the rate (else a locked contact's
  // dashpot holds a block at the speed it slides with).
  double Nd = 0.0, Ts = 0.0;
  if (dashpots && (p.cn > 0.0 || p.cs > 0.0)) {
    if (!rates) find_rates();
    if (p.cn > 0.0) Nd = p.cn * vn;
    if (p.cs > 0.0) Ts = p.cs * vt;
  }
  double T = p.ks * (reach - y.shift) + Ts;
  const double limit = y.intact ? mohr_coulomb_strength(N, p.tan_phi, p.cohesion)
                                 : mohr_coulomb_strength(N, p.tan_phi_residual, p.cohesion_residual);
  if (std::abs(T) > limit) {
    // Slides: the spring, dragged along, carries the (residual) strength.
    y.intact = false;
    y.direction = T >= 0.0 ? 1 : -1;
    T = y.direction * mohr_coulomb_strength(N, p.tan_phi_residual, p.cohesion_residual);
    const double shift = reach - T / p.ks;
    y.slid += T * (shift - y.shift);  // the strength over the drag: friction's work (>= 0)
    y.shift = shift;
    y.state = ContactState::sliding;
    Ts = 0.0;  // the shear force is the strength: friction's, not a dashpot's
  } else {
    y.state = ContactState::locked;
  }
  if (Nd != 0.0 || Ts != 0.0) {
    // The dashpots' work, first half: at the rates their forces were found at.
    y.damped += 0.5 * kick * (Nd * vn + Ts * vt);
    y.nd = 0.5 * kick * Nd, y.ts = 0.5 * kick * Ts;
  }
  fi.noalias() = (N + Nd) * p.ni + T * p.ti;
  fj.noalias() = (N + Nd) * p.nj + T * p.tj;
}

/// Block b's contact forces summed in the fixed order of its slots.
inline void gather_block(const int* first, const Vec6* force, std::ptrdiff_t b, Eigen::VectorXd& f) {
  Vec6 sum = Vec6::Zero();
  for (int e = first[b]; e < first[b + 1]; ++e) sum += force[e];
  f.segment<6>(6 * b) = sum;
}


}  // namespace

void ContactSystem::begin_cycles(std::span<const BlockView> blocks, int threads) {
  ExplicitCycles& a = cycles_;
  a.threads = threads;
  a.active = true;
  const std::size_t n = records_.work.contacts.size();
  a.springs.resize(n);
  a.states.resize(n);
  a.bounds.resize(2 * n);
  for (std::size_t c = 0; c < n; ++c) {
    const Contact& r = records_.work.contacts[c];
    const Hot& h = step_.hot[c];
    const JointSet& js = joint_sets_[r.joint_set];
    cycles::Spring& p = a.springs[c];
    p.ni = h.ni, p.nj = h.nj, p.ti = h.ti, p.tj = h.tj;
    p.dn0 = h.dn0;
    p.reach0 = h.dt0 + step_.seams[c].locking_shift;
    p.pn = h.pn;
    p.ks = shear_stiffness(c);
    p.tension = js.tensile_strength * r.length;
    p.tan_phi = tan_deg(js.friction_angle_of(true));
    p.tan_phi_residual = tan_deg(js.friction_angle_of(false));
    p.cohesion = js.cohesion_of(true) * r.length;
    p.cohesion_residual = js.cohesion_of(false) * r.length;
    p.cn = p.cs = 0.0;
    p.i = r.key.vblock, p.j = r.key.eblock;
    cycles::State& y = a.states[c];
    y.state = r.state;
    y.direction = static_cast<std::int8_t>(r.slide_direction);
    y.intact = r.intact;
    y.shift = 0.0;
    y.damped = y.nd = y.ts = y.slid = y.released = y.attached = 0.0;
    a.bounds[2 * c] = std::isfinite(blocks[r.key.eblock].mass) ? 2.0 : 1.0;
    a.bounds[2 * c + 1] = std::isfinite(blocks[r.key.vblock].mass) ? 2.0 : 1.0;
    if (r.state == ContactState::sliding) {
      // A contact sliding at the step start carries its friction from the first cycle:
      // its spring starts stretched by the friction force over k (the elastic part of
      // an elastic-plastic joint's shear displacement).
      const double f = mohr_coulomb_strength(h.normal_force, h.tan_phi, h.cohesion, r.length);
      y.shift = p.reach0 - r.slide_direction * f / p.ks;
      y.attached = 0.5 * f * f / p.ks;  // a sliding contact's book stores no shear spring
    }
  }
  a.order_by_block(records_.work.contacts, static_cast<int>(blocks.size()));
}

void ExplicitCycles::order_by_block(std::span<const Contact> work, int block_count) {
  const std::size_t n = work.size();
  force.assign(2 * n, Vec6::Zero());
  // The contacts of each block in the order of the records (vertex side before edge side
  // where a contact has a block on both): the gather's fixed order.
  block_first.assign(static_cast<std::size_t>(block_count) + 1, 0);
  for (const Contact& r : work) ++block_first[r.key.vblock + 1], ++block_first[r.key.eblock + 1];
  for (int b = 0; b < block_count; ++b) block_first[b + 1] += block_first[b];
  next.assign(block_first.begin(), block_first.end() - 1);
  for (std::size_t c = 0; c < n; ++c) {
    springs[c].slot_i = next[work[c].key.vblock]++;
    springs[c].slot_j = next[work[c].key.eblock]++;
  }
  // The first and last contact on each block, and the blocks by their last contact: the
  // order in which the cycles can gather them.
  block_first_contact.assign(static_cast<std::size_t>(block_count), static_cast<int>(n));
  block_last_contact.assign(static_cast<std::size_t>(block_count), -1);
  for (std::size_t c = n; c-- > 0;)
    for (const int b : {work[c].key.vblock, work[c].key.eblock}) block_first_contact[b] = static_cast<int>(c);
  for (std::size_t c = 0; c < n; ++c)
    for (const int b : {work[c].key.vblock, work[c].key.eblock}) block_last_contact[b] = static_cast<int>(c);
  completion.resize(static_cast<std::size_t>(block_count));
  for (int b = 0; b < block_count; ++b) completion[b] = b;
  std::stable_sort(completion.begin(), completion.end(),
                   [&](int x, int y) { return block_last_contact[x] < block_last_contact[y]; });
}

void ContactSystem::cycle_stiffness(std::vector<Mat6>& K) const { cycles_.add_stiffness(K); }

void ExplicitCycles::add_stiffness(std::vector<Mat6>& K) const {
  for (std::size_t c = 0; c < springs.size(); ++c) {
    const cycles::Spring& p = springs[c];
    const double bi = bounds[2 * c], bj = bounds[2 * c + 1];
    K[p.i].noalias() += bi * (p.pn * p.ni * p.ni.transpose() + p.ks * p.ti * p.ti.transpose());
    K[p.j].noalias() += bj * (p.pn * p.nj * p.nj.transpose() + p.ks * p.tj * p.tj.transpose());
  }
}

void ContactSystem::cycle_damping(double tau, std::vector<Mat6>& C) {
  for (std::size_t c = 0; c < cycles_.springs.size(); ++c) {
    cycles::Spring& p = cycles_.springs[c];
    if (joint_sets_[records_.work.contacts[c].joint_set].restitution) {
      p.cn = step_.hot[c].cn, p.cs = step_.hot[c].cs;
    } else {
      p.cn = tau * p.pn;
      p.cs = tau * p.ks;
    }
    if (!step_.dynamic || (p.cn == 0.0 && p.cs == 0.0)) continue;
    const double bi = cycles_.bounds[2 * c], bj = cycles_.bounds[2 * c + 1];
    C[p.i].noalias() += bi * (p.cn * p.ni * p.ni.transpose() + p.cs * p.ti * p.ti.transpose());
    C[p.j].noalias() += bj * (p.cn * p.nj * p.nj.transpose() + p.cs * p.tj * p.tj.transpose());
  }
}

void ContactSystem::cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick,
                                 Eigen::VectorXd& f) {
  cycles_.forces(D, V, kick, step_.dynamic, f);
}

void ExplicitCycles::forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, bool dashpots,
                            Eigen::VectorXd& f) {
  const auto n = static_cast<std::ptrdiff_t>(springs.size());
  const auto nb = static_cast<std::ptrdiff_t>(block_first.size()) - 1;
  const int thread_total = thread_count(threads);
  const cycles::Spring* spring = springs.data();
  cycles::State* state = states.data();
  Vec6* slot = force.data();
  const int* first = block_first.data();
  const int* first_contact = block_first_contact.data();
  const int* last_contact = block_last_contact.data();
  const int* done = completion.data();
  f.resize(6 * nb);
  // Each thread works a contiguous range of the contacts, in chunks, and gathers a block as
  // soon as the last contact on it is done, while its slots are still in the cache; a
  // block whose contacts lie in the ranges of two threads is gathered after them all. Each
  // block's sum is over its slots in their fixed order whoever makes it: the same bits
  // whatever the threads.
  // A team of one still wakes a futex at its barriers (a system call per cycle): one thread
  // works without a parallel region.
  const auto work_range = [&](int nt, int t) {
    const std::ptrdiff_t lo = n * t / nt, hi = n * (t + 1) / nt;
    // The blocks whose last contact is in [lo, hi), by their last contact.
    std::ptrdiff_t up_to = std::lower_bound(done, done + nb, lo, [&](int b, std::ptrdiff_t c) {
                             return last_contact[b] < c;
                           }) - done;
    for (std::ptrdiff_t c0 = lo; c0 < hi; c0 += kGatherChunk) {
      const std::ptrdiff_t c1 = std::min(hi, c0 + kGatherChunk);
      for (std::ptrdiff_t k = c0; k < c1; ++k) cycle_contact(spring[k], state[k], slot, D, V, kick, dashpots);
      for (; up_to < nb && last_contact[done[up_to]] < c1; ++up_to)
        if (first_contact[done[up_to]] >= lo) gather_block(first, slot, done[up_to], f);
    }
  };
  const auto gather_left = [&](std::ptrdiff_t b, int nt) {
    // A block with no contact, or one whose contacts span two threads' ranges.
    bool spans = last_contact[b] < 0;
    for (int u = 1; u < nt && !spans; ++u) {
      const std::ptrdiff_t split = n * u / nt;
      spans = first_contact[b] < split && last_contact[b] >= split;
    }
    if (spans) gather_block(first, slot, b, f);
  };
  if (thread_total > 1 && n >= kParallelContacts) {
#pragma omp parallel num_threads(thread_total)
    {
      const int nt = omp_get_num_threads();
      work_range(nt, omp_get_thread_num());
#pragma omp barrier
#pragma omp for schedule(static)
      for (std::ptrdiff_t b = 0; b < nb; ++b) gather_left(b, nt);
    }
  } else {
    work_range(1, 0);
    for (std::ptrdiff_t b = 0; b < nb; ++b) gather_left(b, 1);
  }
}

int ContactSystem::cycle_relinearize(const Eigen::VectorXd& D) {
  // As check does for an iterate of the implicit step: each locked contact of a law that
  // is not linear takes the seam of the stress its spring carries at D (relinearize_seam);
  // the cycles' springs follow.
  const double f_res = settings_.force_resolution * step_.force_scale;
  int changed = 0;
  for (std::size_t c = 0; c < records_.work.contacts.size(); ++c) {
    const Contact& r = records_.work.contacts[c];
    const cycles::State& y = cycles_.states[c];
    if (y.state != ContactState::locked || r.rheology < 0 || !(r.tributary_length > 0.0) ||
        !step_.laws[r.joint_set].active || r.creep_failed || joint_sets_[r.joint_set].law->is_linear())
      continue;
    cycles::Spring& p = cycles_.springs[c];
    const double slip = p.ti.dot(D.segment<6>(6 * p.i)) + p.tj.dot(D.segment<6>(6 * p.j));
    const double tau = p.ks * (p.reach0 + slip - y.shift) / r.tributary_length;
    if (!relinearize_seam(c, tau, f_res)) continue;
    p.ks = shear_stiffness(c);
    p.reach0 = step_.hot[c].dt0 + step_.seams[c].locking_shift;
    ++changed;
  }
  return changed;
}

CheckResult ContactSystem::end_cycles(std::span<const BlockView> blocks, const Eigen::VectorXd& D,
                                      const Eigen::VectorXd& V) {
  CheckResult res;
  double scale = 0.0;
  cycles_.work = {};
  for (std::size_t c = 0; c < records_.work.contacts.size(); ++c) {
    Contact& r = records_.work.contacts[c];
    Hot& h = step_.hot[c];
    const cycles::State& y = cycles_.states[c];
    const cycles::Spring& p = cycles_.springs[c];
    const ContactState before = h.start_state;
    r.state = y.state;
    if (y.state == ContactState::sliding) r.slide_direction = y.direction;
    if (!y.intact && r.intact) {
      // No longer intact: end_step's friction and the next step take the residual values.
      r.intact = false;
      const JointSet& js = joint_sets_[r.joint_set];
      h.tan_phi = p.tan_phi_residual;
      h.cohesion = js.cohesion_of(false);
      h.tensile_strength = 0.0;
    }
    if (y.state == ContactState::locked && y.shift != 0.0) {
      // The locking point where the cycles left it: end_step's stretch d_t0 + slip counts from there.
      const BlockView& eb = blocks[r.key.eblock];
      r.locking_ratio += y.shift / edge_length(eb, r.key.edge);
      h.dt0 -= y.shift;
    }
    if (y.nd != 0.0 || y.ts != 0.0) {
      // The second half of the last cycle's dashpot work (cycle_contact): its forces at the
      // step's end rates, which its kick led to.
      const auto Vi = V.segment<6>(6 * p.i);
      const auto Vj = V.segment<6>(6 * p.j);
      cycles_.work.damping += y.nd * (p.ni.dot(Vi) + p.nj.dot(Vj)) + y.ts * (p.ti.dot(Vi) + p.tj.dot(Vj));
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
    if (y.state == ContactState::sliding) {
      // Committed sliding, it stores no shear spring: the stretch the cycles left is released.
      const double stretch = p.reach0 + p.ti.dot(Di) + p.tj.dot(Dj) - y.shift;
      cycles_.work.release += 0.5 * p.ks * stretch * stretch;
    }
    if (y.state == before) continue;
    ++res.state_changes;
    if (before == ContactState::open) ++res.changes.closed;
    else if (y.state == ContactState::open) ++res.changes.opened;
    else if (y.state == ContactState::sliding) ++res.changes.slipped;
    else ++res.changes.stuck;
  }
  step_.force_scale = scale;
  step_.max_penetration = res.max_penetration;
  // What the cycles did to the springs, with what end_cycles added above (the stretch of
  // the springs committed sliding, the last cycle's dashpot halves).
  const CycleWork summed = cycles_.summed();
  cycles_.work.damping += summed.damping;
  cycles_.work.friction += summed.friction;
  cycles_.work.release += summed.release;
  cycles_.work.attach += summed.attach;
  return res;
}

CycleWork ExplicitCycles::summed() const {
  CycleWork sum;  // in the records' order: the same sums whatever the threads
  for (const cycles::State& y : states) {
    sum.damping += y.damped;
    sum.friction += y.slid;
    sum.release += y.released;
    sum.attach += y.attached;
  }
  return sum;
}

}  // namespace rheodda::contact
