// Contact damping (JointSet::restitution; docs/reference/contacts.md, "Contact damping"):
// a block that lands on one vertex rebounds with the joint set's coefficient of
// restitution e (the linear spring-dashpot contact of Cundall & Strack 1979:
// a free damped half-oscillation returns e = exp(-zeta pi / sqrt(1 - zeta^2)));
// e = 0 does not rebound; and the energy the dashpots take is in the balance.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <optional>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// A triangle pointing down (its centroid above its lowest vertex, so the
/// contact force makes no moment) moving down at v0 = 5 cm/s, 0.1 mm above a
/// held base, no gravity; a stiff block on a soft contact (penalty 1e9 N/m
/// against E = 1e11 Pa), so the impact is the contact's oscillation, and slow
/// enough that it stays within the allowed penetration (0.1 mm; a deeper one
/// would raise the penalty within the impact). Returns the block's vertical
/// velocity / v0 after `duration` [s] and the balance.
struct Drop {
  double velocity = 0.0;  ///< upward, as a multiple of the impact speed [-]
  core::EnergyBalance energy;
};

Drop drop(std::optional<double> restitution, double dt, double duration = 0.02) {
  core::Model m;
  m.settings.dt = dt;
  m.settings.gravity = Vec2::Zero();
  m.materials[0].young_modulus = 1e11;
  add_fixed(m, rect(-1.0, -1.0, 1.0, 0.0));
  const double v0 = 0.05;
  m.blocks.push_back(block({{0.0, 1e-4}, {0.5, 1.0001}, {-0.5, 1.0001}}, Vec2(0.0, -v0)));
  contact::JointSet j = joint(30.0);
  j.restitution = restitution;
  Sim sim(m, {j}, 1e9 / 1e11);
  while (sim.engine.time() < duration - 1e-12) sim.engine.step();
  return {sim.engine.velocity(1).y() / v0, sim.engine.energy()};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(contact_damping)

BOOST_AUTO_TEST_CASE(a_vertex_impact_rebounds_with_the_joint_sets_restitution) {
  // Contact period pi sqrt(m / p_n) = 3.6 ms for the 1300 kg/m triangle: 360 steps.
  for (const double e : {0.2, 0.5, 0.8}) {
    const Drop d = drop(e, 1e-5);
    BOOST_TEST_MESSAGE("restitution " << e << ": rebound " << d.velocity << " x v0");
    BOOST_TEST(d.velocity == e, boost::test_tools::tolerance(0.02));
    BOOST_TEST(d.energy.total.dissipation_contact_damping > 0.0);
    BOOST_TEST(d.energy.max_relative_residual < 0.01);
  }
}

BOOST_AUTO_TEST_CASE(zero_restitution_does_not_rebound) {
  const Drop d = drop(0.0, 1e-5);
  BOOST_TEST_MESSAGE("restitution 0: velocity " << d.velocity << " x v0");
  BOOST_TEST(std::abs(d.velocity) < 0.01);
  // Its kinetic energy (1300 x 0.05^2 / 2 = 1.6 J/m) went into the dashpot.
  BOOST_TEST(d.energy.total.dissipation_contact_damping > 0.9 * 0.5 * 1300.0 * 0.05 * 0.05);
  BOOST_TEST(d.energy.max_relative_residual < 0.01);
}

BOOST_AUTO_TEST_CASE(without_a_restitution_the_resolved_contact_is_elastic) {
  // Shi's undamped spring: only the scheme's damping (about omega dt / 4 =
  // 2e-4 here) takes energy, so the block leaves at nearly its impact speed.
  const Drop d = drop(std::nullopt, 1e-5);
  BOOST_TEST_MESSAGE("no restitution: rebound " << d.velocity << " x v0");
  BOOST_TEST(d.velocity > 0.98);
  BOOST_TEST(d.energy.total.dissipation_contact_damping == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
