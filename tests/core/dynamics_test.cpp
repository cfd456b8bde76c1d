// Time integration of the inertia terms. A square held at its centroid by a
// fixed point of stiffness k is a one-degree-of-freedom oscillator
// (m = rho S, omega = sqrt(k/m)); started with velocity v0 it should swing
// with amplitude v0/omega for ever. Shi's scheme (beta = 1/2, gamma = 1)
// damps it (algorithmic damping ratio ~ omega dt/4 for small omega dt, so
// exp(-pi n omega dt / 2) after n periods); the trapezoidal rule keeps the
// amplitude. Both integrate free fall exactly.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

constexpr double rho = 2600.0, omega = 10.0, v0 = 0.01, dt = 0.01;  // omega dt = 0.1

Model oscillator(TimeIntegration scheme) {
  Model m;
  m.settings.dt = dt;
  m.settings.gravity = Vec2::Zero();
  m.settings.time_integration = scheme;
  m.settings.fixed_point_stiffness = rho * 1.0 * omega * omega;  // k = m omega^2, m = rho S, S = 1
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  m.blocks[0].initial_velocity = {v0, 0.0};
  m.fixed_points.push_back({0, {0.5, 0.5}});
  return m;
}

/// Largest |x displacement| of the centroid over the last period of `periods`.
double amplitude_after(TimeIntegration scheme, int periods) {
  Engine e(oscillator(scheme));
  const double period = 2.0 * std::numbers::pi / omega;
  double amp = 0.0;
  while (e.time() < periods * period) {
    e.step();
    if (e.time() > (periods - 1) * period) amp = std::max(amp, std::abs(e.centroid(0).x() - 0.5));
  }
  return amp;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(dynamics)

BOOST_AUTO_TEST_CASE(trapezoidal_rule_keeps_the_amplitude_of_a_free_vibration) {
  const double exact = v0 / omega;
  // Sampling a period at omega dt = 0.1 misses the peak by at most 1 - cos(0.05) ~ 1.3e-3.
  BOOST_TEST(std::abs(amplitude_after(TimeIntegration::trapezoidal, 20) - exact) <= 5e-3 * exact);
}

BOOST_AUTO_TEST_CASE(shi_scheme_damps_a_free_vibration) {
  const double exact = v0 / omega;
  const double amp1 = amplitude_after(TimeIntegration::shi, 1);
  const double amp20 = amplitude_after(TimeIntegration::shi, 20);
  // Decay over 19 periods ~ exp(-pi 19 omega dt / 2) = 0.05: it is well below half.
  BOOST_TEST(amp1 < exact);
  BOOST_TEST(amp20 < 0.2 * amp1);
}

BOOST_AUTO_TEST_CASE(trapezoidal_rule_integrates_free_fall_exactly) {
  Model m;
  m.settings.dt = 0.01;
  m.settings.max_displacement_ratio = 1.0;
  m.settings.time_integration = TimeIntegration::trapezoidal;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  Engine e(m);
  e.run(100);
  const double t = e.time(), g = 9.81;
  BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 - 0.5 * g * t * t)) <= 1e-12 * 0.5 * g * t * t);
  BOOST_TEST(std::abs(e.velocity(0)(1) + g * t) <= 1e-12 * g * t);
}

BOOST_AUTO_TEST_CASE(trapezoidal_rule_is_refused_in_a_static_analysis) {
  Model m = oscillator(TimeIntegration::trapezoidal);
  m.blocks[0].initial_velocity = Vec2::Zero();
  m.settings.dynamic_ratio = 0.0;
  try {
    Engine e(m);
    BOOST_FAIL("expected a ModelError");
  } catch (const ModelError& err) {
    BOOST_TEST(err.key() == "settings.time_integration");
  }
}

BOOST_AUTO_TEST_SUITE_END()
