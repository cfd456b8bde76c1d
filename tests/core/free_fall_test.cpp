// Free fall: with Shi's Newmark scheme (beta = 1/2, gamma = 1) a constant
// acceleration is integrated exactly, D = v dt + g dt^2/2, so the centroid
// follows y0 + vy t - g t^2/2 to round-off (dda.md, validation cases).
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

Model falling_square(double dt) {
  Model m;
  m.settings.dt = dt;
  m.settings.max_displacement_ratio = 1.0;  // allow large steps: the scheme is exact, no cut needed
  m.settings.dynamic_ratio = 1.0;
  m.settings.gravity = {0.0, -9.81};
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(free_fall)

BOOST_AUTO_TEST_CASE(free_fall_follows_half_g_t_squared_to_round_off) {
  const double g = 9.81, dt = 0.01;
  Model m = falling_square(dt);
  m.measurement_points.push_back({.block = 0, .point = {1.0, 1.0}});
  Engine e(m);
  const int steps = 100;
  for (int k = 1; k <= steps; ++k) {
    const StepReport r = e.step();
    BOOST_TEST(r.cuts == 0);
    BOOST_TEST(r.dt == dt);
    const double t = k * dt;
    BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 - 0.5 * g * t * t)) <= 1e-12 * (1.0 + 0.5 * g * t * t));
    BOOST_TEST(std::abs(e.centroid(0).x() - 0.5) <= 1e-13);
    BOOST_TEST(std::abs(e.velocity(0)(1) + g * t) <= 1e-12 * g * t);
  }
  const double t = steps * dt;
  const auto& samples = e.measurements().at(0);
  BOOST_TEST(samples.size() == static_cast<std::size_t>(steps + 1));
  BOOST_TEST(std::abs(samples.back().displacement.y() + 0.5 * g * t * t) <= 1e-12 * 0.5 * g * t * t);
  BOOST_TEST(std::abs(samples.back().displacement.x()) <= 1e-13);
  // Rigid motion: no stress, no rotation, area unchanged.
  BOOST_TEST(e.stress(0).norm() <= 1e-6);  // stress unit here: Pa, with E = 1e10 Pa
  BOOST_TEST(std::abs(e.area(0) - 1.0) <= 1e-13);
}

BOOST_AUTO_TEST_CASE(a_dynamic_settling_stage_carries_velocity_then_the_static_analysis_starts_at_rest) {
  // A static analysis (dynamic_ratio 0) with a dynamic settling stage
  // (SettleStage::dynamic) until 0.1 s: in the stage the square falls
  // freely, y = -g t^2/2 and v = -g t to round-off; the first static step after
  // it starts at rest (D = g dt^2/2, Shi's static step), and the kinetic energy
  // the stage left, m (g t1)^2 / 2, is booked as dissipated by the time
  // integration: the balance closes. Without the stage's flag the same model is
  // static throughout. A damping_ratio needs dynamic steps somewhere.
  const double g = 9.81, dt = 0.01, t1 = 0.1;
  Model m = falling_square(dt);
  m.settings.dynamic_ratio = 0.0;
  m.settings.settle.until = t1;
  m.settings.settle.dt = dt;
  m.settings.settle.max_displacement_ratio = 1.0;
  m.settings.settle.dynamic = true;
  m.materials[0].damping_ratio = 0.05;  // allowed: the stage has dynamic steps
  const double mass = m.materials[0].density * 1.0;  // 1 m x 1 m
  Engine e(m);
  for (int k = 1; k <= 10; ++k) {
    e.step();
    const double t = k * dt;
    BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 - 0.5 * g * t * t)) <= 1e-12 * (1.0 + 0.5 * g * t * t));
    BOOST_TEST(std::abs(e.velocity(0)(1) + g * t) <= 1e-12 * g * t);
  }
  BOOST_TEST(e.time() == t1, boost::test_tools::tolerance(1e-12));
  const double ke = 0.5 * mass * (g * t1) * (g * t1);
  BOOST_TEST(e.energy().stored.kinetic == ke, boost::test_tools::tolerance(1e-9));
  const double y1 = e.centroid(0).y();
  e.step();  // static: from rest
  BOOST_TEST(std::abs(e.centroid(0).y() - (y1 - 0.5 * g * dt * dt)) <= 1e-12);
  BOOST_TEST(e.velocity(0).norm() == 0.0);
  BOOST_TEST(e.energy().stored.kinetic == 0.0);
  BOOST_TEST(e.energy().total.dissipation_integration >= ke);
  BOOST_TEST(e.energy().max_relative_residual < 1e-9);

  Model s = m;
  s.settings.settle.dynamic = false;
  BOOST_CHECK_THROW(Engine{s}, ModelError);  // damping_ratio in a wholly static run
  s.materials[0].damping_ratio = 0.0;
  Engine st(s);
  st.step();
  BOOST_TEST(std::abs(st.centroid(0).y() - (0.5 - 0.5 * g * dt * dt)) <= 1e-12);
  BOOST_TEST(st.velocity(0).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(projectile_keeps_its_horizontal_velocity) {
  const double g = 9.81, dt = 0.02, vx = 3.0, vy = 4.0;
  Model m = falling_square(dt);
  m.blocks[0].initial_velocity = {vx, vy};
  Engine e(m);
  e.run(50);
  const double t = e.time();
  BOOST_TEST(std::abs(t - 1.0) <= 1e-13);
  BOOST_TEST(std::abs(e.centroid(0).x() - (0.5 + vx * t)) <= 1e-12 * (0.5 + vx * t));
  BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 + vy * t - 0.5 * g * t * t)) <= 1e-12 * 5.0);
  BOOST_TEST(std::abs(e.velocity(0)(0) - vx) <= 1e-12 * vx);
}

BOOST_AUTO_TEST_CASE(run_until_lands_on_the_end_time) {
  const double g = 9.81;
  Model m = falling_square(0.03);
  Engine e(m);
  e.run_until(0.1);  // 3 full steps and one of 0.01
  BOOST_TEST(std::abs(e.time() - 0.1) <= 1e-15);
  BOOST_TEST(e.step_count() == 4);
  BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 - 0.5 * g * 0.01)) <= 1e-13);
}

BOOST_AUTO_TEST_CASE(static_analysis_carries_no_velocity) {
  // dynamic_ratio = 0: each step starts at rest, so a free block falls only
  // g dt^2/2 per step and no velocity is ever stored.
  const double g = 9.81, dt = 0.01;
  Model m = falling_square(dt);
  m.settings.dynamic_ratio = 0.0;
  Engine e(m);
  e.run(10);
  BOOST_TEST(e.velocity(0).norm() == 0.0);
  BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 - 10 * 0.5 * g * dt * dt)) <= 1e-13);
}

BOOST_AUTO_TEST_SUITE_END()
