// A DDA run with contacts: model + ContactSystem + adapter + Engine, and
// small geometry helpers for the validation scenes.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "brick_wall.hpp"  // tests/models

namespace rheodda::testing {

using core::Vec2;

inline double deg(double d) { return d * std::numbers::pi / 180.0; }

/// Counter-clockwise rectangle [x0, x1] x [y0, y1] rotated by `angle` [rad] about the origin.
inline std::vector<Vec2> rect(double x0, double y0, double x1, double y1, double angle = 0.0) {
  const Eigen::Rotation2Dd r(angle);
  return {r * Vec2(x0, y0), r * Vec2(x1, y0), r * Vec2(x1, y1), r * Vec2(x0, y1)};
}

inline contact::JointSet joint(double phi_deg) {
  contact::JointSet j;
  j.name = "joint";
  j.friction_angle = phi_deg;
  return j;
}

/// A block of the default material, optionally moving [m/s].
inline core::BlockDef block(std::vector<Vec2> vertices, Vec2 velocity = Vec2::Zero()) {
  core::BlockDef b;
  b.vertices = std::move(vertices);
  b.initial_velocity = velocity;
  return b;
}

/// Adds a block and fixes it at three of its vertices.
inline int add_fixed(core::Model& m, std::vector<Vec2> vertices) {
  m.blocks.push_back(block(vertices));
  const int b = static_cast<int>(m.blocks.size()) - 1;
  for (int k = 0; k < 3; ++k) m.fixed_points.push_back({b, vertices[k]});
  return b;
}

/// Fixed base whose top is the line through the origin at angle alpha [rad], and a block
/// b x h on it, its lower corner at distance x0 up the slope and lifted by `gap` [m]; dt 1 ms.
inline core::Model incline_scene(double alpha, double b, double h, double x0, double gap = 0.0,
                                 core::ContactSolver solver = core::ContactSolver::open_close) {
  core::Model m;
  m.settings.dt = 1e-3;
  m.settings.contact_solver = solver;
  add_fixed(m, rect(-1.0, -1.0, 7.0, 0.0, alpha));
  m.blocks.push_back(block(rect(x0, gap, x0 + b, gap + h, alpha)));
  return m;
}

/// Steps until block 1 of an incline_scene has slid `distance` [m] down the slope at angle
/// alpha [rad] (at most 5 000 steps); returns how far its centroid travelled along it [m].
template <class S>
double slide_down(S& sim, double alpha, double distance) {
  const Vec2 c0 = sim.engine.centroid(1);
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  double travelled = 0.0;
  while (travelled < distance && sim.engine.step_count() < 5000) {
    sim.engine.step();
    travelled = sim.engine.point_displacement(1, c0).dot(down);
  }
  return travelled;
}

/// The benchmarks' running-bond wall (tests/models/brick_wall.hpp) with the solver
/// `solver`, every open-close iterate solved to the full tolerance unless `iterate_tolerance`.
inline core::Model running_bond_wall(int nx, int ny, core::SolverKind solver, double dynamic_ratio = 1.0,
                                     double iterate_tolerance = 0.0) {
  core::Model m = models::running_bond_wall(nx, ny);
  m.settings.solver_iterate_tolerance = iterate_tolerance;
  m.settings.dynamic_ratio = dynamic_ratio;
  m.settings.solver = solver;
  return m;
}

struct Sim {
  Sim(core::Model m, std::vector<contact::JointSet> joints, double penalty_factor = 40.0)
      : contacts(std::move(joints), core::contact_settings_for(m, penalty_factor)),
        adapter(contacts),
        engine(std::move(m), adapter) {}
  /// With contact settings of the caller's (e.g. a scene's: stick_keeps_force).
  Sim(core::Model m, std::vector<contact::JointSet> joints, const contact::ContactSettings& settings)
      : contacts(std::move(joints), settings), adapter(contacts), engine(std::move(m), adapter) {}
  contact::ContactSystem contacts;
  core::ContactAdapter adapter;
  core::Engine engine;

  /// Rotation of block b since the start [rad], counter-clockwise positive.
  double rotation(int b) const {
    const auto& A = engine.block(b).map_A;
    return std::atan2(A(1, 0) - A(0, 1), A(0, 0) + A(1, 1));
  }
};

/// What a step leaves that the next ones depend on, as numbers to compare bit for bit: the
/// blocks' vertices and velocities, the contacts' states, locking points, normal forces and
/// penetrations, the time and the work of gravity so far.
inline std::vector<double> engine_state(const Sim& sim) {
  std::vector<double> out;
  for (int b = 0; b < sim.engine.block_count(); ++b) {
    for (const Vec2& v : sim.engine.vertices(b)) out.push_back(v.x()), out.push_back(v.y());
    for (int i = 0; i < 6; ++i) out.push_back(sim.engine.velocity(b)(i));
  }
  for (const contact::Contact& c : sim.contacts.contacts()) {
    out.push_back(static_cast<double>(c.state));
    out.push_back(c.locking_ratio);
    out.push_back(c.normal_force);
    out.push_back(c.penetration);
  }
  out.push_back(sim.engine.time());
  out.push_back(sim.engine.energy().total.work_gravity);
  return out;
}

}  // namespace rheodda::testing
