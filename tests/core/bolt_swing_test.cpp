// A block hanging from a bolt, which the bolt's force along its end-of-step axis
// (core/src/bolts.hpp, (1)-(5); docs/reference/bolts.md, "Equations") holds at any
// step: a static block settles where its centroid hangs below the bolt, whatever
// dt, and a bolted pendulum under the trapezoidal rule keeps its energy to the
// rule's second order.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iomanip>
#include <numbers>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

constexpr double kG = 9.81;          // m/s^2
constexpr double kDensity = 2600.0;  // kg/m^3 (the default material)

/// A static model of a 1 m x 1 m block (0..1, 0..1) hanging under gravity from a
/// bolt of stiffness k whose end is on its top edge at x = x_end, to an anchor
/// fixed 2 m above it.
Model hanging_block(double dt, double x_end, double k) {
  Model m;
  m.settings.dt = dt;
  m.settings.dynamic_ratio = 0.0;
  m.settings.gravity = {0.0, -kG};
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  Bolt b;
  b.block_a = 0;
  b.point_a = {x_end, 1.0};
  b.point_b = {x_end, 3.0};
  b.axial_stiffness = k;
  m.bolts.push_back(b);
  return m;
}

/// What the runs of hanging_block measure.
struct Hanging {
  double largest_sway = 0.0;  ///< largest |x of the centroid - x of the anchor| after the first step [m]
  int steps = 0, cuts = 0;
  int cut_steps = 0;    ///< steps up to the last one that was cut
  int short_steps = 0;  ///< steps shorter than dt
};

/// Runs the hanging block to t_end, then checks the closed form: at rest the
/// block's centroid is below the anchor (the bolt's force through it: no moment,
/// no sideways force), N = W = rho g S and the elongation is W/k (Hooke).
Hanging settle(double dt, double x_end, double t_end) {
  const double k = 1.0e7;  // N/m
  Engine e(hanging_block(dt, x_end, k));
  Hanging h;
  while (e.time() < t_end - 1e-9 * t_end) {
    const StepReport r = e.step();
    ++h.steps;
    h.cuts += r.cuts;
    if (r.cuts > 0) h.cut_steps = h.steps;
    if (r.dt < dt * (1.0 - 1e-12)) ++h.short_steps;
    if (h.steps > 1) h.largest_sway = std::max(h.largest_sway, std::abs(e.centroid(0).x() - x_end));
  }
  const double W = kDensity * kG * e.area(0);  // on the current area, as DDA's body force
  const BoltState& s = e.bolts().at(0);
  BOOST_TEST(std::abs(s.force - W) <= 1e-9 * W);
  BOOST_TEST(std::abs(s.elongation - W / k) <= 1e-6 * W / k);
  BOOST_TEST(std::abs(e.centroid(0).x() - x_end) <= 1e-9);
  BOOST_TEST((s.state == BoltMode::elastic));
  // The bolt's end is where the block was moved to (the rotation of the block
  // about the end), straight above the centroid.
  const Vec2 end = e.point_position(0, {x_end, 1.0});
  BOOST_TEST(std::abs(end.x() - x_end) <= 1e-9);
  BOOST_TEST(e.energy().max_relative_residual <= 1e-6);
  return h;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(bolt_swing)

BOOST_AUTO_TEST_CASE(a_symmetric_hanging_block_stays_at_rest_at_half_second_steps) {
  // Round-off used to seed a swing that grew x(-4.8) per step at dt = 0.5 s: the
  // bolt's pull was along the start axis and only the inertia 2M/dt^2 resisted
  // the sideways motion. The geometric stiffness N/L across the axis and the
  // block's N |x - c| in rotation about the end hold it.
  const Hanging h = settle(0.5, 0.5, 200.0);
  BOOST_TEST_MESSAGE("symmetric, dt = 0.5 s: " << h.steps << " steps, " << h.cuts << " cuts, largest sway "
                                               << h.largest_sway << " m");
  BOOST_TEST(h.largest_sway <= 1e-12);
  BOOST_TEST(h.cuts == 0);
}

BOOST_AUTO_TEST_CASE(a_block_hung_off_centre_settles_below_the_bolt_at_creep_steps) {
  // The end 2 cm off the block's centre line: the block turns by atan(0.02/0.5)
  // about it until its centroid is below the anchor. At dt = 0.01 d it used to
  // go on swinging (272 252 steps and 91 693 cuts for 1 d, its top 18 % off the
  // equilibrium). The first step, from an unstressed bolt, has no geometric
  // stiffness to go by and is cut until the inertia holds it; from then on the
  // steps grow back to dt.
  const double dt = 864.0;  // s
  const Hanging h = settle(dt, 0.52, 100.0 * dt);
  BOOST_TEST_MESSAGE("2 cm off centre, dt = 0.01 d: " << h.steps << " steps (" << h.short_steps << " shorter than dt), "
                                                     << h.cuts << " cuts, the last in step " << h.cut_steps);
  // The cuts: the first step's, until the inertia holds the block on its
  // unstressed bolt, then one wherever a step would move it further than max_displacement_ratio w0
  // while it turns (0.04 rad); after c cuts by dt_cut = 0.3 the steps grow back
  // by dt_growth = 1.5 per step, c ln(1/0.3)/ln(1.5) ~ 3 c steps (measured: 11
  // cuts, the last in step 12, 33 steps shorter than dt).
  BOOST_TEST(h.cut_steps <= 20);
  BOOST_TEST(h.short_steps <= 3 * h.cuts + 5);
}

namespace {

/// A bolted pendulum: a 0.2 m square hanging from a fixed anchor by a bolt of
/// length L whose end is at its centroid (no moment: a point mass), released at
/// rest at theta0 from the vertical with the bolt's tension m g cos(theta0) (so
/// that it starts in radial equilibrium), dynamic, trapezoidal rule, no damping.
/// Returns the largest angle in the second of two periods [rad] and the largest
/// departure of the mechanical energy (kinetic + the bolt's + m g y) from its
/// start over the two periods, over the swing's energy m g L (1 - cos theta0) [-].
/// Integrator::explicit_step: taken in central-difference cycles instead, without the
/// cycles' dashpots (explicit_damping 0).
std::pair<double, double> pendulum(double dt, double theta0, Integrator integrator = Integrator::implicit) {
  const double L = 2.0, k = 1.0e7, side = 0.2;  // m, N/m, m
  const double m_block = kDensity * side * side;
  Model m;
  m.settings.dt = dt;
  m.settings.dynamic_ratio = 1.0;
  m.settings.gravity = {0.0, -kG};
  m.settings.max_displacement_ratio = 0.1;  // 1 cm per step (w0 is half the block's size): no step is cut
  m.settings.integrator = integrator;
  if (integrator == Integrator::implicit) m.settings.time_integration = TimeIntegration::trapezoidal;
  m.settings.explicit_damping = 0.0;
  m.settings.threads = 1;  // one block: threads would only wait for each other (same bits)
  const Vec2 anchor(0.0, L);
  const Vec2 c(L * std::sin(theta0), L - L * std::cos(theta0));
  m.blocks.push_back(block({c + Vec2(-0.1, -0.1), c + Vec2(0.1, -0.1), c + Vec2(0.1, 0.1), c + Vec2(-0.1, 0.1)}));
  Bolt b;
  b.block_a = 0;
  b.point_a = c;
  b.point_b = anchor;
  b.axial_stiffness = k;
  b.pretension = m_block * kG * std::cos(theta0);
  m.bolts.push_back(b);
  Engine e(m);
  // Period of the pendulum, to second order in the amplitude (Landau & Lifshitz,
  // "Mechanics", 1976, sec. 28): T = 2 pi sqrt(L/g) (1 + theta0^2/16).
  const double period = 2.0 * std::numbers::pi * std::sqrt(L / kG) * (1.0 + theta0 * theta0 / 16.0);
  const double swing = m_block * kG * L * (1.0 - std::cos(theta0));
  const double e0 = e.energy().stored.bolt;
  double amplitude = 0.0, drift = 0.0;
  while (e.time() < 2.0 * period) {
    BOOST_TEST(e.step().cuts == 0);
    const Vec2 x = e.centroid(0);
    const double mech = e.energy().stored.kinetic + e.energy().stored.bolt + m_block * kG * (x.y() - c.y());
    drift = std::max(drift, std::abs(mech - e0) / swing);
    if (e.time() > period) amplitude = std::max(amplitude, std::atan2(std::abs(x.x() - anchor.x()), anchor.y() - x.y()));
  }
  return {amplitude, drift};
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_bolted_pendulum_keeps_its_energy_to_second_order) {
  // With the pull along the start axis the pendulum gained energy at first order
  // in dt over a run: 10 deg -> 10.29 deg in two periods at dt = 2 ms. With the
  // force along the end-of-step axis the trapezoidal rule is of second order:
  // the energy's departure falls by ~4 per halving of dt.
  const double theta0 = 10.0 * std::numbers::pi / 180.0;
  const auto [a4, d4] = pendulum(4e-3, theta0);
  const auto [a2, d2] = pendulum(2e-3, theta0);
  const auto [a1, d1] = pendulum(1e-3, theta0);
  const double deg = 180.0 / std::numbers::pi;
  BOOST_TEST_MESSAGE(std::setprecision(10) << "bolted pendulum, amplitude in the second period at dt 4, 2, 1 ms: "
                     << a4 * deg << ", " << a2 * deg << ", " << a1 * deg << " deg; energy departure "
                     << d4 << ", " << d2 << ", " << d1);
  BOOST_TEST(d4 / d2 > 3.0);
  BOOST_TEST(d2 / d1 > 3.0);
  // Second-order bounds at dt = 2 ms, (omega dt)^2 with omega = sqrt(g/L): on the
  // energy, and on the amplitude (whose peak the steps sample to within
  // theta0 (omega dt)^2 / 8 alone).
  const double w_dt = std::sqrt(kG / 2.0) * 2e-3;
  BOOST_TEST(d2 <= w_dt * w_dt);
  BOOST_TEST(std::abs(a2 - theta0) <= w_dt * w_dt * theta0);
}

BOOST_AUTO_TEST_CASE(a_bolted_pendulum_taken_by_the_explicit_step_keeps_its_energy) {
  // The pendulum in the explicit step's cycles, whose length is set by the bolt's and the
  // block's stiffness (far below dt): the bounds of the implicit step's test at dt = 2 ms on
  // the energy and on the amplitude, (omega dt)^2 and (omega dt)^2 theta0 with
  // omega = sqrt(g/L); the force turns with the bolt at every cycle.
  const double theta0 = 10.0 * std::numbers::pi / 180.0;
  const auto [a2, d2] = pendulum(2e-3, theta0, Integrator::explicit_step);
  BOOST_TEST_MESSAGE(std::setprecision(10) << "bolted pendulum, explicit step, dt 2 ms: amplitude in the second period "
                     << a2 * 180.0 / std::numbers::pi << " deg; energy departure " << d2);
  const double w_dt = std::sqrt(kG / 2.0) * 2e-3;
  BOOST_TEST(d2 <= w_dt * w_dt);
  BOOST_TEST(std::abs(a2 - theta0) <= w_dt * w_dt * theta0);
}

BOOST_AUTO_TEST_SUITE_END()
