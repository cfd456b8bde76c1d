// The bolts in a step (bolts.hpp; docs/reference/bolts.md, "Equations"): their terms in
// the block equations, the check of their yield state, and their state update
// when the step is accepted.
#include <algorithm>
#include <cmath>
#include <string>

#include "bolts.hpp"
#include "rheodda/laws/automatic_scheme.hpp"
#include "rheodda/laws/series_law.hpp"

namespace rheodda::core {

namespace {

/// Current position of the material point whose initial position was p0 [length].
Vec2 position(const BlockState& b, const Vec2& p0) { return b.map_A * p0 + b.map_b; }

/// The two ends of a bolt now [length].
std::pair<Vec2, Vec2> ends(const Bolt& bolt, const std::vector<BlockState>& blocks) {
  const Vec2 a = position(blocks[bolt.block_a], bolt.point_a);
  const Vec2 b = bolt.block_b >= 0 ? position(blocks[bolt.block_b], bolt.point_b) : bolt.point_b;
  return {a, b};
}

/// Length when installed, L0 (Bolt::installed_length) [length].
double installed_length(const Bolt& bolt) {
  return bolt.installed_length > 0.0 ? bolt.installed_length : (bolt.point_b - bolt.point_a).norm();
}

/// Unstressed length L_rest = L0 - pretension / k (bolt.hpp) [length].
double rest_length(const Bolt& bolt) { return installed_length(bolt) - bolt.pretension / bolt.axial_stiffness; }

/// Relative margin of the yield checks, so that a force at N_y to round-off
/// does not flip between the modes from one iterate to the next [-].
constexpr double kYieldMargin = 1e-9;

}  // namespace

const char* bolt_mode_name(BoltMode m) {
  switch (m) {
    case BoltMode::elastic: return "elastic";
    case BoltMode::yielding: return "yielding";
    case BoltMode::ruptured: return "ruptured";
  }
  return "?";
}

BoltState BoltSet::installed_state(const Bolt& bolt) {
  BoltState s;
  s.length = installed_length(bolt);
  s.elongation = s.length - rest_length(bolt);  // = pretension / k
  s.force = bolt.pretension;
  s.state = std::abs(s.force) >= bolt.yield_force ? BoltMode::yielding : BoltMode::elastic;
  return s;
}

std::vector<BoltState> BoltSet::initial_states(const Model& m) {
  std::vector<BoltState> out;
  for (const Bolt& bolt : m.bolts) out.push_back(installed_state(bolt));
  return out;
}

double BoltSet::stored_energy(const Model& m, const std::vector<BoltState>& states) {
  double e = 0.0;
  for (std::size_t k = 0; k < states.size(); ++k)
    if (states[k].state != BoltMode::ruptured) e += 0.5 * states[k].force * states[k].force / m.bolts[k].axial_stiffness;
  return e;
}

void BoltSet::linearize(std::size_t k, double guess) {
  // (2) of bolts.hpp: Delta e_c = h + c N (laws/contact_rheology.hpp, eq. 1),
  // so N = k_eff (s0 + Delta) with k_eff = k/(1 + k c), s0 = e0 - e_p - e_c - h.
  const Bolt& bolt = model_->bolts[k];
  const BoltState& s = start_[k];
  Trial& t = trials_[k];
  const double kb = bolt.axial_stiffness;
  t.guess = guess;
  if (bolt.law) t.lin = bolt.law->linearize(t.constants, s.rheology, t.force_start, guess);
  t.k_eff = kb / (1.0 + kb * t.lin.c);
  t.s0 = s.elongation - s.plastic_elongation - s.creep_elongation() - t.lin.h;
}

void BoltSet::begin_step(const Model& m, const std::vector<BlockState>& blocks,
                         const std::vector<BoltState>& committed, double dt) {
  model_ = &m;
  start_ = committed;
  trials_.assign(m.bolts.size(), Trial{});
  for (std::size_t k = 0; k < m.bolts.size(); ++k) {
    const Bolt& bolt = m.bolts[k];
    const BoltState& s = committed[k];
    Trial& t = trials_[k];
    if (s.state == BoltMode::ruptured) continue;
    const auto [xa, xb] = ends(bolt, blocks);
    const double L = (xb - xa).norm();
    if (!(L > 0.0)) continue;  // ends met: no axis this step (docs/reference/bolts.md, "Limits")
    const Vec2 n = (xb - xa) / L;
    // (1): g = T^T n at the step-start position of each end.
    t.g_a = contact::displacement_matrix(blocks[bolt.block_a].centroid, xa).transpose() * n;
    if (bolt.block_b >= 0) t.g_b = contact::displacement_matrix(blocks[bolt.block_b].centroid, xb).transpose() * n;
    t.active = true;
    t.force_start = s.force;
    if (bolt.law) t.constants = bolt.law->step_constants(dt, laws::automatic_scheme(*bolt.law, bolt.axial_stiffness, dt));
    linearize(k, s.force);
    t.sign = s.state == BoltMode::yielding ? (s.force >= 0.0 ? 1 : -1) : 0;
  }
}

double BoltSet::elongation_increment(std::size_t k, const Eigen::VectorXd& D) const {
  const Bolt& bolt = model_->bolts[k];
  const Trial& t = trials_[k];
  double d = -t.g_a.dot(D.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_a)));
  if (bolt.block_b >= 0) d += t.g_b.dot(D.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_b)));
  return d;  // (1) [length]
}

void BoltSet::assemble(contact::SystemSink& sink) const {
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    const Trial& t = trials_[k];
    if (!t.active) continue;
    const Bolt& bolt = model_->bolts[k];
    const int a = bolt.block_a, b = bolt.block_b;
    if (t.sign != 0) {  // (4): the yield force, no stiffness
      const double f = t.sign * bolt.yield_force;
      sink.add_load(a, f * t.g_a);
      if (b >= 0) sink.add_load(b, -f * t.g_b);
      continue;
    }
    // (3): the spring k_eff along the axis, its force N0 at Delta = 0.
    const double n0 = t.k_eff * t.s0;
    sink.add_stiffness(a, a, t.k_eff * t.g_a * t.g_a.transpose());
    sink.add_load(a, n0 * t.g_a);
    if (b >= 0) {
      sink.add_stiffness(b, b, t.k_eff * t.g_b * t.g_b.transpose());
      sink.add_stiffness(a, b, -t.k_eff * t.g_a * t.g_b.transpose());
      sink.add_load(b, -n0 * t.g_b);
    }
  }
}

int BoltSet::check(const Eigen::VectorXd& D) {
  int changes = 0;
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    Trial& t = trials_[k];
    if (!t.active) continue;
    const Bolt& bolt = model_->bolts[k];
    // The elastic trial force with the plastic elongation of the step start (2).
    const double trial = t.k_eff * (t.s0 + elongation_increment(k, D));
    const double ny = bolt.yield_force;
    if (t.sign == 0 && std::abs(trial) > ny * (1.0 + kYieldMargin)) {
      t.sign = trial > 0.0 ? 1 : -1;  // beyond the yield force: it yields
      ++changes;
    } else if (t.sign != 0 && t.sign * trial < ny * (1.0 - kYieldMargin)) {
      t.sign = 0;  // a yielding bolt whose elongation turned back: elastic again
      ++changes;
    }
    // A law that is not affine: its linearization holds at the force it was made at
    // only (laws/contact_rheology.hpp, eq. 1'); make it again at this iterate's.
    if (bolt.law && bolt.law->linearity() != laws::Linearity::affine) {
      const double force = t.sign != 0 ? t.sign * ny : trial;
      const laws::Linearization before = t.lin;
      linearize(k, force);
      const double moved = std::abs(t.lin.h - before.h) + std::abs((t.lin.c - before.c) * force);
      if (moved > kYieldMargin * (std::abs(t.s0) + std::abs(t.lin.h) + std::abs(force) / bolt.axial_stiffness))
        ++changes;
    }
  }
  return changes;
}

BoltEnergy BoltSet::commit(const Model& m, const std::vector<BlockState>& blocks, double t_end,
                           std::vector<BoltState>& states) {
  BoltEnergy energy;
  for (std::size_t k = 0; k < m.bolts.size(); ++k) {
    const Bolt& bolt = m.bolts[k];
    BoltState& s = states[k];
    const auto [xa, xb] = ends(bolt, blocks);
    s.length = (xb - xa).norm();
    s.elongation = s.length - rest_length(bolt);  // exact, on the moved geometry
    if (s.state == BoltMode::ruptured || k >= trials_.size() || !trials_[k].active) continue;
    const Trial& t = trials_[k];
    const double kb = bolt.axial_stiffness;
    const double n_start = s.force, plastic_start = s.plastic_elongation, creep_start = s.creep_elongation();
    // The end force: the yield force, or (2) on the exact elongation; an elastic
    // trial that ends beyond N_y on the exact geometry yields as well.
    double force = t.sign != 0 ? t.sign * bolt.yield_force
                               : t.k_eff * (s.elongation - plastic_start - creep_start - t.lin.h);
    const bool yielding = t.sign != 0 || std::abs(force) > bolt.yield_force;
    if (yielding) force = std::copysign(bolt.yield_force, force);
    // Creep over the step under the law's force (laws/contact_rheology.hpp, advance).
    if (bolt.law) {
      laws::RheologyState next;
      bolt.law->advance(t.constants, s.rheology, t.force_start, force, next);
      s.rheology = next;
    }
    const double creep_now = s.creep_elongation();
    if (yielding) {
      // The plastic elongation takes up what the spring at N_y and the creep do not.
      s.plastic_elongation = s.elongation - creep_now - force / kb;
    } else {
      force = kb * (s.elongation - s.plastic_elongation - creep_now);  // = (2) to round-off (affine laws)
    }
    s.force = force;
    s.state = yielding ? BoltMode::yielding : BoltMode::elastic;
    // Energy (bolts.hpp, BoltEnergy): the end force over the elongation's parts.
    energy.dissipation += 0.5 * (force - n_start) * (force - n_start) / kb +
                          force * (s.plastic_elongation - plastic_start) + force * (creep_now - creep_start);
    if (s.elongation > bolt.rupture_elongation) {
      // Ruptured at the end of this step: its stored energy is released, and it
      // carries nothing from now on (docs/reference/bolts.md, "Equations").
      energy.dissipation += 0.5 * force * force / kb;
      s.state = BoltMode::ruptured;
      s.force = 0.0;
      s.rupture_time = t_end;
    }
  }
  energy.stored = stored_energy(m, states);
  return energy;
}

}  // namespace rheodda::core
