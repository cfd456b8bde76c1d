// The energy balance of blocks without contacts (docs/reference/engine.md, "Energy
// balance"): free fall turns the work of gravity into kinetic energy exactly;
// a square on a centroid spring (fixed point) and a free block vibrating
// elastically from an initial stress keep KE + U with the trapezoidal rule and
// lose, with Shi's scheme, exactly the integration dissipation the balance
// derives (k Delta^2/2 per spring per step); a static analysis's inertia term
// absorbs all the work.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

Model falling_square(double dynamic_ratio) {
  Model m;
  m.settings.dt = 0.01;
  m.settings.max_displacement_ratio = 1.0;  // no cut: the fall is 0.5 m in 100 steps
  m.settings.dynamic_ratio = dynamic_ratio;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  return m;
}

/// A unit square held at its centroid by a fixed point, k = m omega^2, started
/// with velocity v0 (tests/core/dynamics_test.cpp): omega dt = 0.1.
constexpr double rho = 2600.0, omega = 10.0, v0 = 0.01, dt = 0.01;
Model oscillator(TimeIntegration scheme) {
  Model m;
  m.settings.dt = dt;
  m.settings.gravity = Vec2::Zero();
  m.settings.time_integration = scheme;
  m.settings.fixed_point_stiffness = rho * omega * omega;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  m.blocks[0].initial_velocity = {v0, 0.0};
  m.fixed_points.push_back({0, {0.5, 0.5}});
  return m;
}

/// A free 2 m x 1 m block released from a uniaxial initial stress: its strain
/// modes vibrate (no gravity, nothing else).
Model prestressed_block(TimeIntegration scheme) {
  Model m;
  m.settings.dt = 2e-5;  // omega dt ~ 0.1 for the slowest strain mode
  m.settings.gravity = Vec2::Zero();
  m.settings.time_integration = scheme;
  m.blocks.push_back(block({{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
  m.blocks[0].initial_stress = {-1e6, 0.0, 0.0};  // 1 MPa compression in x
  return m;
}

double stored_mechanical(const EnergyBalance& e) {
  return e.stored.kinetic + e.stored.strain + e.stored.fixed;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(energy)

BOOST_AUTO_TEST_CASE(free_fall_turns_the_work_of_gravity_into_kinetic_energy) {
  Engine e(falling_square(1.0));
  e.run(100);
  const EnergyBalance& b = e.energy();
  const double m = rho * 1.0, g = 9.81, t = e.time();
  // W_g = m g (g t^2/2) = KE = m (g t)^2/2.
  BOOST_TEST(b.total.work_gravity == 0.5 * m * g * g * t * t, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(b.stored.kinetic == b.total.work_gravity, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(std::abs(b.total.dissipation_integration) <= 1e-12 * b.total.work_gravity);
  BOOST_TEST(std::abs(b.total.residual) <= 1e-10 * b.total.work_gravity);
  BOOST_TEST(b.max_relative_residual <= 1e-10);
  BOOST_TEST(e.reports().back().energy.work_gravity > 0.0);
}

BOOST_AUTO_TEST_CASE(static_analysis_inertia_absorbs_the_work_of_gravity) {
  // Each static step starts at rest: the block falls g dt^2/2 and the inertia
  // term 2 M D/dt^2 takes all of gravity's work.
  Engine e(falling_square(0.0));
  e.run(10);
  const EnergyBalance& b = e.energy();
  BOOST_TEST(b.stored.kinetic == 0.0);
  BOOST_TEST(b.total.integration_inertia == b.total.work_gravity, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(b.total.dissipation_integration == b.total.work_gravity, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::abs(b.total.residual) <= 1e-12 * b.total.work_gravity);
}

BOOST_AUTO_TEST_CASE(trapezoidal_rule_keeps_the_energy_of_a_spring_and_dissipates_nothing) {
  Engine e(oscillator(TimeIntegration::trapezoidal));
  const double e0 = 0.5 * rho * v0 * v0;  // m = rho S, S = 1
  BOOST_TEST(stored_mechanical(e.energy()) == e0, boost::test_tools::tolerance(1e-14));
  // The first step uses Shi's scheme (it yields the acceleration): it loses
  // k (v0 dt)^2/2 ~ (omega dt)^2 e0 to the integration.
  e.step();
  const double first = e.energy().total.dissipation_integration;
  BOOST_TEST(first > 0.0);
  BOOST_TEST(first <= 1.1 * omega * omega * dt * dt * e0);
  const double e1 = stored_mechanical(e.energy());
  const double period = 2.0 * std::numbers::pi / omega;
  while (e.time() < 20 * period) {
    e.step();
    BOOST_TEST(stored_mechanical(e.energy()) == e1, boost::test_tools::tolerance(1e-9));
  }
  BOOST_TEST(std::abs(e.energy().total.dissipation_integration - first) <= 1e-9 * e0);
  BOOST_TEST(e.energy().max_relative_residual <= 1e-9);
}

BOOST_AUTO_TEST_CASE(shi_scheme_loses_exactly_its_integration_dissipation) {
  Engine e(oscillator(TimeIntegration::shi));
  const double e0 = stored_mechanical(e.energy());
  const double period = 2.0 * std::numbers::pi / omega;
  while (e.time() < 20 * period) e.step();
  const EnergyBalance& b = e.energy();
  const double lost = e0 - stored_mechanical(b);
  BOOST_TEST_MESSAGE("shi oscillator: lost " << lost / e0 << " of e0, integration dissipation "
                                             << b.total.dissipation_integration / e0);
  BOOST_TEST(lost > 0.9 * e0);  // amplitude x 0.05 after 20 periods
  BOOST_TEST(b.total.dissipation_integration == lost, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(b.max_relative_residual <= 1e-9);
}

BOOST_AUTO_TEST_CASE(elastic_vibration_from_an_initial_stress) {
  // Trapezoidal: KE + U_b stays put (no integration dissipation after the
  // first step); Shi: what it loses is the integration dissipation. Both to
  // the block's strain, ~1e-4 here: the stored energies follow the deformed
  // block (its area S and mass matrix change with the strain) while a step's
  // equations use the step-start ones, so the balance closes to O(strain)
  // (measured: largest relative residual 3.9e-4; 3.9e-5 with E ten times larger).
  for (const auto scheme : {TimeIntegration::trapezoidal, TimeIntegration::shi}) {
    Engine e(prestressed_block(scheme));
    const double e0 = stored_mechanical(e.energy());
    BOOST_TEST(e0 == 0.5 * 2.0 * 1e12 / 1e10, boost::test_tools::tolerance(1e-12));  // S sigma^2/(2E)
    e.step();
    const double first = e.energy().total.dissipation_integration;
    double ke_max = 0.0;
    for (int k = 0; k < 2000; ++k) {
      e.step();
      ke_max = std::max(ke_max, e.energy().stored.kinetic);
    }
    const EnergyBalance& b = e.energy();
    const double lost = e0 - stored_mechanical(b);
    BOOST_TEST_MESSAGE((scheme == TimeIntegration::shi ? "shi" : "trapezoidal")
                       << " prestressed block: e0 " << e0 << ", largest KE " << ke_max << ", lost "
                       << lost / e0 << " of e0, integration " << b.total.dissipation_integration / e0
                       << " (first step " << first / e0 << "), largest relative residual "
                       << b.max_relative_residual);
    BOOST_TEST(ke_max > 0.3 * e0);  // it does vibrate
    if (scheme == TimeIntegration::trapezoidal) {
      BOOST_TEST(std::abs(b.total.dissipation_integration - first) <= 1e-6 * e0);
      BOOST_TEST(std::abs(lost - first) <= 1e-3 * e0);
    } else {
      BOOST_TEST(lost > 0.1 * e0);
    }
    BOOST_TEST(b.max_relative_residual <= 1e-3);
  }
}

BOOST_AUTO_TEST_CASE(save_and_restore_carry_the_balance) {
  Engine a(oscillator(TimeIntegration::trapezoidal));
  a.run(10);
  const EngineState mid = a.save();
  a.run(10);
  Engine b(oscillator(TimeIntegration::trapezoidal));
  b.restore(mid);
  b.run(10);
  BOOST_TEST(b.energy().total.dissipation_integration == a.energy().total.dissipation_integration);
  BOOST_TEST(b.energy().stored.kinetic == a.energy().stored.kinetic);
  BOOST_TEST(b.energy().total.residual == a.energy().total.residual);
}

BOOST_AUTO_TEST_SUITE_END()
