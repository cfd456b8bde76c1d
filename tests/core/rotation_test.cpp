// Exact-rotation post-correction: a free block spinning (dynamic, no gravity)
// keeps its area over 1e4 steps to 1e-9 relative, and turns by exactly
// omega t (the scheme gives D = v dt for a free rigid motion). Without the
// correction the first-order rotation would scale the area by (1 + r0^2)
// per step: (1 + 1e-6)^1e4 - 1 = 1e-2 here.
// Also: the whole engine state saved mid-run and restored replays the same run.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

Model spinning(std::vector<Vec2> vertices, double omega, double dt) {
  Model m;
  m.settings.dt = dt;
  m.settings.dynamic_ratio = 1.0;
  m.settings.gravity = Vec2::Zero();
  m.settings.max_displacement_ratio = 0.01;
  m.blocks.push_back(block(std::move(vertices)));
  m.blocks.back().initial_angular_velocity = omega;
  return m;
}

Vec2 rotated(const Vec2& p, const Vec2& c, double angle) {
  const Vec2 d = p - c;
  return c + Vec2(std::cos(angle) * d.x() - std::sin(angle) * d.y(),
                  std::sin(angle) * d.x() + std::cos(angle) * d.y());
}

}  // namespace

BOOST_AUTO_TEST_SUITE(rotation)

BOOST_AUTO_TEST_CASE(spinning_square_keeps_its_area_over_ten_thousand_steps) {
  const double omega = 1.0, dt = 1e-3;
  Engine e(spinning({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, omega, dt));
  const double a0 = e.area(0);
  e.run(10000);
  BOOST_TEST(e.reports().back().cuts == 0);
  BOOST_TEST(std::abs(e.area(0) - a0) <= 1e-9 * a0);
  const double angle = omega * e.time();
  const Vec2 c(0.5, 0.5);
  BOOST_TEST((e.centroid(0) - c).norm() <= 1e-12);
  BOOST_TEST((e.point_position(0, {1.0, 1.0}) - rotated({1.0, 1.0}, c, angle)).norm() <= 1e-9);
  BOOST_TEST((e.vertices(0)[0] - rotated({0.0, 0.0}, c, angle)).norm() <= 1e-9);
  BOOST_TEST(std::abs(e.velocity(0)(2) - omega) <= 1e-12);
}

BOOST_AUTO_TEST_CASE(spinning_concave_block_keeps_its_area_and_shape) {
  // The L-shape couples rotation and strain in its mass matrix; a rigid spin
  // must still produce no strain.
  const double omega = 2.0, dt = 5e-4;
  const std::vector<Vec2> L{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  Engine e(spinning(L, omega, dt));
  const double a0 = e.area(0);
  const Vec2 c0 = e.centroid(0);
  e.run(10000);
  BOOST_TEST(std::abs(e.area(0) - a0) <= 1e-9 * a0);
  BOOST_TEST(e.stress(0).norm() <= 1e-6);  // [Pa], against E = 1e10 Pa
  const double angle = omega * e.time();
  for (const Vec2& p : L) BOOST_TEST((e.point_position(0, p) - rotated(p, c0, angle)).norm() <= 1e-9);
}

BOOST_AUTO_TEST_CASE(restored_state_replays_the_same_run) {
  Model m = spinning({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0, 1e-3);
  m.settings.gravity = {0.0, -9.81};
  m.settings.max_displacement_ratio = 1.0;
  m.measurement_points.push_back({.block = 0, .point = {1.0, 0.0}});
  Engine e(m);
  e.run(10);
  const EngineState saved = e.save();
  e.run(10);
  const std::vector<Vec2> first(e.vertices(0).begin(), e.vertices(0).end());
  const Vec6 v_first = e.velocity(0);
  e.restore(saved);
  BOOST_TEST(e.step_count() == 10);
  BOOST_TEST(e.measurements()[0].size() == 11u);
  e.run(10);
  BOOST_TEST(e.step_count() == 20);
  for (std::size_t k = 0; k < first.size(); ++k) BOOST_TEST((e.vertices(0)[k] - first[k]).norm() == 0.0);
  BOOST_TEST((e.velocity(0) - v_first).norm() == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
