// Gravity ramp of the settling stage (core::SettleStage::gravity_ramp;
// docs/reference/engine.md, "Gravity ramp"): gravity that comes on at once sets a block
// resting on its support vibrating about its static position, the first swing
// reaching twice the static settlement (a suddenly applied load), and the work
// of gravity is twice the energy stored at rest; ramped up slowly on the scale
// of the vibration, the block follows its static position without overshoot,
// and the work of gravity is what the springs store (Clapeyron: W = 2 U under a
// load applied at once, W = U under one applied quasi-statically).
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

constexpr double kStage = 0.02;  // settling stage [s]
constexpr double kDt = 1e-5;     // [s]: about 25 steps per period of the block on its contact springs

/// A 1 m x 0.5 m block resting on a fixed base, dynamic, undamped, its first
/// kStage s a settling stage with gravity ramped over `ramp` s (0: at once).
core::Model resting_block(double ramp) {
  core::Model m;
  m.settings.dt = kDt;
  m.settings.settle.until = kStage;
  m.settings.settle.dt = kDt;
  m.settings.settle.max_displacement_ratio = 0.01;
  m.settings.settle.dynamic = true;
  m.settings.settle.gravity_ramp = ramp;
  add_fixed(m, rect(-1.0, -1.0, 3.0, 0.0));
  m.blocks.push_back(block(rect(0.5, 0.0, 1.5, 0.5)));
  return m;
}

struct Settling {
  double largest = 0.0;  ///< largest downward centroid displacement over the run [m]
  double last = 0.0;     ///< downward centroid displacement at the end [m]
  double work = 0.0;     ///< work of gravity [J/m]
  double stored = 0.0;   ///< elastic energy stored at the end (contacts, block, fixed points) [J/m]
  double kinetic = 0.0;  ///< kinetic energy at the end [J/m]
  double residual = 0.0; ///< largest relative residual of the energy balance [-]
};

Settling settle(double ramp, double end) {
  Sim sim(resting_block(ramp), {joint(30.0)});
  const Vec2 c0 = sim.engine.centroid(1);
  Settling s;
  while (sim.engine.time() < end - 1e-12) {
    sim.engine.step();
    s.largest = std::max(s.largest, c0.y() - sim.engine.centroid(1).y());
  }
  s.last = c0.y() - sim.engine.centroid(1).y();
  const core::EnergyBalance& e = sim.engine.energy();
  s.work = e.total.work_gravity;
  s.stored = e.stored.strain + e.stored.fixed + e.stored.contact_normal + e.stored.contact_shear;
  s.kinetic = e.stored.kinetic;
  s.residual = e.max_relative_residual;
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(gravity_ramp)

BOOST_AUTO_TEST_CASE(a_slow_ramp_loads_without_overshoot_and_gravity_at_once_swings_to_twice_the_static_settlement) {
  // Ramped over half the stage (about 400 periods of the block on its springs).
  const Settling ramped = settle(0.5 * kStage, kStage);
  BOOST_TEST_REQUIRE(ramped.last > 0.0);
  BOOST_TEST(ramped.largest <= 1.02 * ramped.last, ramped.largest << " vs " << ramped.last);
  BOOST_TEST(ramped.kinetic < 1e-3 * ramped.stored);
  BOOST_TEST(std::abs(ramped.work - ramped.stored) < 0.02 * ramped.work, ramped.work << " vs " << ramped.stored);
  BOOST_TEST(ramped.residual < 1e-3);

  // At once: the first swing goes to about twice the static settlement (less the
  // scheme's damping), and gravity has done twice what the springs store at the
  // static position.
  const Settling sudden = settle(0.0, 0.5 * kStage);
  BOOST_TEST(sudden.largest > 1.6 * ramped.last, sudden.largest << " vs static " << ramped.last);
  BOOST_TEST(sudden.work > 1.6 * ramped.stored);
  BOOST_TEST(sudden.residual < 1e-3);
  BOOST_TEST_MESSAGE("static settlement " << ramped.last << " m, ramped largest " << ramped.largest
                                          << ", at once largest " << sudden.largest << "; work " << ramped.work
                                          << " / " << sudden.work << " J/m, stored " << ramped.stored);
}

BOOST_AUTO_TEST_CASE(the_ramp_must_end_within_the_settling_stage) {
  core::Model m = resting_block(2.0 * kStage);
  BOOST_CHECK_THROW(core::Engine{m}, core::ModelError);
  m.settings.settle.gravity_ramp = -1.0;
  BOOST_CHECK_THROW(core::Engine{m}, core::ModelError);
  m.settings.settle.gravity_ramp = kStage;  // ending with the stage is allowed
  BOOST_CHECK_NO_THROW(core::Engine{m});
}

BOOST_AUTO_TEST_SUITE_END()
