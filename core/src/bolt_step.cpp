// The bolts in a step (bolts.hpp; docs/reference/bolts.md, "Equations"): their Newton
// terms in the block equations at the iterate, the check of the iterate (yield
// state, law, convergence of the force along the end-of-step axis), and their
// state update when the step is accepted.
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
std::pair<Vec2, Vec2> ends(const Bolt& bolt, const std::vector<BlockState>& blocks) { return bolt_ends(bolt, blocks); }

/// Length when installed, L0 (Bolt::installed_length) [length].
double installed_length(const Bolt& bolt) {
  return bolt.installed_length > 0.0 ? bolt.installed_length : (bolt.point_b - bolt.point_a).norm();
}

/// Unstressed length L_rest = L0 - pretension / k (bolt.hpp) [length].
double rest_length(const Bolt& bolt) { return bolt_rest_length(bolt); }

/// Relative round-off of a position [-]: a hundred times the double's epsilon,
/// for the few operations that make an end's coordinates.
constexpr double kRoundoff = 1e-14;

/// Relative margin of the yield checks, so that a force at N_y to round-off
/// does not flip between the modes from one iterate to the next [-].
constexpr double kYieldMargin = 1e-9;

}  // namespace

std::pair<Vec2, Vec2> bolt_ends(const Bolt& bolt, const std::vector<BlockState>& blocks) {
  const Vec2 a = position(blocks[bolt.block_a], bolt.point_a);
  const Vec2 b = bolt.block_b >= 0 ? position(blocks[bolt.block_b], bolt.point_b) : bolt.point_b;
  return {a, b};
}

double bolt_rest_length(const Bolt& bolt) { return installed_length(bolt) - bolt.pretension / bolt.axial_stiffness; }

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

BoltSet::EndMotion BoltSet::end_motion(const Vec2& c, const Vec2& x, const contact::Vec6& D) {
  // (1) of bolts.hpp: x' = c + u + R(r0) (I + eps) (x - c), as Engine::Impl::accept
  // moves the block (the exact-rotation post-correction, docs/reference/engine.md).
  const Vec2 p = x - c;
  const double r0 = D(2), cr = std::cos(r0), sr = std::sin(r0);
  Eigen::Matrix2d R;
  R << cr, -sr, sr, cr;
  Eigen::Matrix2d A;
  A << 1.0 + D(3), 0.5 * D(5), 0.5 * D(5), 1.0 + D(4);
  EndMotion e;
  e.rho = R * A * p;
  e.x = c + D.head<2>() + e.rho;
  e.G.col(0) = Vec2(1.0, 0.0);
  e.G.col(1) = Vec2(0.0, 1.0);
  e.G.col(2) = Vec2(-e.rho.y(), e.rho.x());  // dR/dr0 = J R, J the quarter turn
  e.G.col(3) = R * Vec2(p.x(), 0.0);
  e.G.col(4) = R * Vec2(0.0, p.y());
  e.G.col(5) = R * Vec2(0.5 * p.y(), 0.5 * p.x());
  return e;  // at D = 0: G = T (contact::displacement_matrix)
}

contact::Mat6 BoltSet::end_hessian(const EndMotion& e, const Eigen::Matrix2d& K2, double curv) {
  contact::Mat6 h = e.G.transpose() * K2 * e.G;
  h(2, 2) += curv;
  return h;
}

BoltSet::Point BoltSet::point(std::size_t k, const Eigen::VectorXd& D) const {
  const Bolt& bolt = model_->bolts[k];
  const Trial& t = trials_[k];
  Point p;
  p.D_a = D.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_a));
  p.a = end_motion(t.c_a, t.x_a, p.D_a);
  if (bolt.block_b >= 0) {
    p.D_b = D.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_b));
    p.b = end_motion(t.c_b, t.x_b, p.D_b);
  } else {
    p.b.x = t.x_b;  // a fixed anchor: G = 0
  }
  const Vec2 d = p.b.x - p.a.x;
  p.L = d.norm();
  p.n = p.L > 0.0 ? Vec2(d / p.L) : Vec2(d);  // ends met: no axis, no force direction
  // (2): the force at this iterate, or the yield force.
  p.N = t.sign != 0 ? t.sign * bolt.yield_force : t.elastic_force(p.L);
  // (4): axial and geometric stiffness, the latter only in tension.
  const double tension = std::max(p.N, 0.0);
  const Eigen::Matrix2d nn = p.n * p.n.transpose();
  p.K2 = (t.sign != 0 ? 0.0 : t.k_eff) * nn;
  if (p.L > 0.0) p.K2 += tension / p.L * (Eigen::Matrix2d::Identity() - nn);
  p.curv_a = std::max(p.N * p.n.dot(p.a.rho), 0.0);
  if (bolt.block_b >= 0) p.curv_b = std::max(-p.N * p.n.dot(p.b.rho), 0.0);
  p.work = p.n.dot(p.b.G * p.D_b - p.a.G * p.D_a);
  return p;
}

void BoltSet::begin_step(const Model& m, const std::vector<BlockState>& blocks,
                         const std::vector<BoltState>& committed, double dt) {
  model_ = &m;
  start_ = committed;
  trials_.assign(m.bolts.size(), Trial{});
  if (previous_.size() != m.bolts.size()) previous_.resize(m.bolts.size());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6 * static_cast<Eigen::Index>(blocks.size()));
  for (std::size_t k = 0; k < m.bolts.size(); ++k) {
    const Bolt& bolt = m.bolts[k];
    const BoltState& s = committed[k];
    Trial& t = trials_[k];
    if (s.state == BoltMode::ruptured) continue;
    const auto [xa, xb] = ends(bolt, blocks);
    const double L = (xb - xa).norm();
    if (!(L > 0.0)) continue;  // ends met: no axis this step (docs/reference/bolts.md, "Limits")
    t.length_start = L;
    t.c_a = blocks[bolt.block_a].centroid;
    t.x_a = xa;
    t.x_b = xb;
    if (bolt.block_b >= 0) t.c_b = blocks[bolt.block_b].centroid;
    t.active = true;
    t.force_start = s.force;
    if (bolt.law) t.constants = bolt.law->step_constants(dt, laws::automatic_scheme(*bolt.law, bolt.axial_stiffness, dt));
    linearize(k, s.force);
    t.sign = s.state == BoltMode::yielding ? (s.force >= 0.0 ? 1 : -1) : 0;
    t.at = point(k, zero);  // D^0 = 0: Shi's spring along the start axis, and the geometric stiffness
  }
}

void BoltSet::assemble(contact::SystemSink& sink) const {
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    const Trial& t = trials_[k];
    if (!t.active) continue;
    const Bolt& bolt = model_->bolts[k];
    const int a = bolt.block_a, b = bolt.block_b;
    const Point& p = t.at;
    // (4) and (5): K += H, F += H D^j - dPi/dD(D^j).
    const contact::Mat6 h_aa = end_hessian(p.a, p.K2, p.curv_a);
    sink.add_stiffness(a, a, h_aa);
    contact::Vec6 f_a = h_aa * p.D_a + p.N * p.a.G.transpose() * p.n;
    if (b >= 0) {
      const contact::Mat6 h_bb = end_hessian(p.b, p.K2, p.curv_b);
      const contact::Mat6 h_ab = -p.a.G.transpose() * p.K2 * p.b.G;
      sink.add_stiffness(b, b, h_bb);
      sink.add_stiffness(a, b, h_ab);
      f_a += h_ab * p.D_b;
      sink.add_load(b, h_bb * p.D_b + h_ab.transpose() * p.D_a - p.N * p.b.G.transpose() * p.n);
    }
    sink.add_load(a, f_a);
  }
}

int BoltSet::check(const Eigen::VectorXd& D) {
  int changes = 0;
  for (std::size_t k = 0; k < trials_.size(); ++k) {
    Trial& t = trials_[k];
    if (!t.active) continue;
    const Bolt& bolt = model_->bolts[k];
    const Point before = t.at;
    // What (5) predicts for the generalized force (3) at D: the linear model of D^j.
    const contact::Vec6 dDa = D.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_a)) - before.D_a;
    const contact::Vec6 dDb =
        bolt.block_b >= 0 ? contact::Vec6(D.segment<6>(6 * static_cast<Eigen::Index>(bolt.block_b)) - before.D_b)
                          : contact::Vec6::Zero();
    const contact::Mat6 h_aa = end_hessian(before.a, before.K2, before.curv_a);
    const contact::Mat6 h_bb = end_hessian(before.b, before.K2, before.curv_b);
    const contact::Mat6 h_ab = -before.a.G.transpose() * before.K2 * before.b.G;
    const contact::Vec6 pred_a = -before.N * before.a.G.transpose() * before.n + h_aa * dDa + h_ab * dDb;
    const contact::Vec6 pred_b = before.N * before.b.G.transpose() * before.n + h_ab.transpose() * dDa + h_bb * dDb;
    // The elastic trial force at D, exact on the moved geometry (2).
    t.at = point(k, D);
    const double trial = t.sign != 0 ? t.elastic_force(t.at.L) : t.at.N;
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
      const laws::Linearization lin_before = t.lin;
      linearize(k, force);
      const double moved = std::abs(t.lin.h - lin_before.h) + std::abs((t.lin.c - lin_before.c) * force);
      if (moved > kYieldMargin * (std::abs(t.s0) + std::abs(t.lin.h) + std::abs(force) / bolt.axial_stiffness))
        ++changes;
    }
    t.at = point(k, D);  // in the mode and linearization now in force
    // Newton: the force (3) at D against the prediction of (5), per end; the
    // rotation and strain rows (force x length) over the end's lever arm.
    const contact::Vec6 exact_a = -t.at.N * t.at.a.G.transpose() * t.at.n;
    const contact::Vec6 exact_b = t.at.N * t.at.b.G.transpose() * t.at.n;
    auto misfit = [](const contact::Vec6& r, const Vec2& rho) {
      const double arm = rho.norm();
      double m = r.head<2>().cwiseAbs().maxCoeff();
      if (arm > 0.0) m = std::max(m, r.tail<4>().cwiseAbs().maxCoeff() / arm);
      return m;
    };
    // Relative to the force, and not below the force of the round-off of the
    // ends' coordinates, kRoundoff (|x_a| + |x_b|) (a bolt that carries little).
    const double off = std::max(misfit(exact_a - pred_a, t.at.a.rho), misfit(exact_b - pred_b, t.at.b.rho));
    const double floor = t.k_eff * kRoundoff * (t.x_a.norm() + t.x_b.norm());
    if (off > kNewtonTolerance * (std::abs(t.at.N) + std::abs(t.force_start)) + floor) ++changes;
  }
  return changes;
}

BoltEnergy BoltSet::commit(const Model& m, const std::vector<BlockState>& blocks, double t_end,
                           std::vector<BoltState>& states) {
  BoltEnergy energy;
  for (std::size_t k = 0; k < m.bolts.size(); ++k) {
    const Bolt& bolt = m.bolts[k];
    BoltState& s = states[k];
    // A ruptured bolt keeps the length and elongation it ruptured at
    // (docs/reference/bolts.md, "Equations"): it has no ends to measure between.
    if (s.state == BoltMode::ruptured) continue;
    const auto [xa, xb] = ends(bolt, blocks);
    s.length = (xb - xa).norm();
    s.elongation = s.length - rest_length(bolt);  // exact, on the moved geometry
    if (k >= trials_.size() || !trials_[k].active) continue;
    const Trial& t = trials_[k];
    const double kb = bolt.axial_stiffness;
    const double n_start = s.force, plastic_start = s.plastic_elongation, creep_start = s.creep_elongation();
    // The plastic elongation the explicit step's cycles took (bolt_cycles.cpp; 0 implicitly).
    s.plastic_elongation += t.cycle_plastic;
    const double plastic_cycled = s.plastic_elongation;
    // The end force: the yield force, or (2) on the exact elongation; an elastic
    // trial that ends beyond N_y on the exact geometry yields as well.
    double force = t.sign != 0 ? t.sign * bolt.yield_force
                               : t.k_eff * (s.elongation - plastic_cycled - creep_start - t.lin.h);
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
    // Energy (bolts.hpp, BoltEnergy): the end force over the elongation's parts,
    // and what its work in the step's equations, N n . (G_b D_b - G_a D_a) (bolts.hpp,
    // (3)), exceeds its work over the length's change: the integration's share of
    // the axis's turn, N L theta^2 / 2 for a turn theta (docs/reference/bolts.md, "Energy").
    // A step taken in cycles follows the force along the step: no integration share and no
    // turn of the axis, but the cycles' plastic and dashpot work (bolt_cycles.cpp).
    if (t.cycled)
      energy.dissipation +=
          t.cycle_work + force * (s.plastic_elongation - plastic_cycled) + force * (creep_now - creep_start);
    else
      energy.dissipation += 0.5 * (force - n_start) * (force - n_start) / kb +
                            force * (s.plastic_elongation - plastic_start) + force * (creep_now - creep_start) +
                            force * (t.at.work - (s.length - t.length_start));
    if (previous_.size() == m.bolts.size())  // the curvature of the force (bolt_creep_error.cpp)
      previous_[k] = {true, n_start, t.constants.dt, force, s.elongation};
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
