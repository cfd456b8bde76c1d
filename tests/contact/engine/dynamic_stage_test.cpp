// Dynamic stages that end at rest (core::SettleStage::rest_tolerance;
// docs/reference/engine.md, "Dynamic stages"): a mechanism a static step finds is taken
// dynamically until its kinetic energy has decayed, then the static steps go
// on; the settling stage ends the same way; each stage is an event.
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

constexpr double kPhi = 30.0;        // friction angle of the joint [deg]
constexpr double kPushOn = 1.0;      // the push comes on [s]
constexpr double kPushFor = 0.2;     // and lasts [s]
constexpr double kEnd = 2.0;         // [s]

/// A 1 m x 0.5 m block resting on a fixed horizontal base in a static
/// analysis of step dt, with a dynamic settling stage in steps of 1 ms (block
/// damping, plastic impacts) that ends at rest, and collapse stages located
/// within 0.01 s. From t = 1 s for 0.2 s a push of 1.5 times the friction
/// force W tan(phi) acts at its centroid.
core::Model pushed_block(double dt, double rest_tolerance, double& push) {
  core::Model m;
  m.settings.dynamic_ratio = 0.0;
  m.settings.dt = dt;
  m.settings.settle.until = 0.5;  // the longest a stage may last
  m.settings.settle.dt = 1e-3;
  m.settings.settle.max_displacement_ratio = 0.01;
  m.settings.settle.dynamic = true;
  m.settings.settle.rest_tolerance = rest_tolerance;
  m.settings.settle.collapse_dt = 0.01;
  m.materials[0].damping_ratio = 1.0;
  add_fixed(m, rect(-1.0, -1.0, 5.0, 0.0));
  m.blocks.push_back(block(rect(1.0, 0.0, 2.0, 0.5)));
  const double weight = m.materials[0].density * 0.5 * 9.81;  // [N/m]
  push = 1.5 * weight * std::tan(deg(kPhi));
  core::PointLoad load;
  load.block = 1;
  load.point = Vec2(1.5, 0.25);
  load.history = {{0.0, Vec2::Zero()},
                  {kPushOn, Vec2::Zero()},
                  {kPushOn + 1e-9, Vec2(push, 0.0)},
                  {kPushOn + kPushFor, Vec2(push, 0.0)},
                  {kPushOn + kPushFor + 1e-9, Vec2::Zero()}};
  m.point_loads.push_back(load);
  return m;
}

contact::JointSet plastic_joint() {
  contact::JointSet j = joint(kPhi);
  j.restitution = 0.0;
  return j;
}

/// The settling stage of `at_rest` (a rest_tolerance) and of `longest` (none, the stage runs
/// its full length), both run to 0.9 s: each one's event and the block's settlement [m].
struct SettlingPair {
  core::StageEvent at_rest, longest;
  double settlement_at_rest = 0.0, settlement_longest = 0.0;
};
SettlingPair settle_both(const core::Model& at_rest, const core::Model& longest, const contact::JointSet& j) {
  Sim a(at_rest, {j});
  Sim b(longest, {j});
  const Vec2 c0 = a.engine.centroid(1);
  a.engine.run_until(0.9);
  b.engine.run_until(0.9);
  BOOST_REQUIRE(a.engine.events().size() == 1u);
  BOOST_REQUIRE(b.engine.events().size() == 1u);
  return {a.engine.events()[0], b.engine.events()[0], a.engine.point_displacement(1, c0).y(),
          b.engine.point_displacement(1, c0).y()};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(dynamic_stages)

BOOST_AUTO_TEST_CASE(a_pushed_block_slides_stops_and_the_stage_ends_at_rest) {
  // While pushed the block accelerates at a1 = (F - mu W)/m = g tan(phi)/2;
  // after the push friction stops it at a2 = g tan(phi): it slides
  // x = a1 T^2/2 + (a1 T)^2/(2 a2) = 0.015 g tan(phi) (T = 0.2 s) and stops at
  // t = 1.3 s. The collapse stage starts within collapse_dt before the push,
  // ends at rest soon after the stop - well before its longest, 0.5 s - and the
  // static steps after it leave the block where it stopped.
  const double gt = 9.81 * std::tan(deg(kPhi));
  const double closed_form = 0.015 * gt;
  double push = 0.0;
  Sim sim(pushed_block(0.1, 1e-3, push), {plastic_joint()});
  const Vec2 c0 = sim.engine.centroid(1);
  sim.engine.run_until(kEnd);
  const double slide = sim.engine.point_displacement(1, c0).x();
  const auto& events = sim.engine.events();
  BOOST_TEST_MESSAGE("slide " << slide << " m (closed form " << closed_form << "), " << events.size() << " stages");
  for (const auto& e : events)
    BOOST_TEST_MESSAGE("  " << core::stage_kind_name(e.kind) << " " << e.start_time << " - " << e.end_time << " s, "
                            << e.steps << " steps, at rest " << e.at_rest << ", blocks " << e.blocks_involved
                            << ", largest " << e.largest_displacement << " m, KE peak " << e.kinetic_energy_peak
                            << " end " << e.kinetic_energy_end << ", work " << e.work << ", dissipated "
                            << e.energy_dissipated);
  BOOST_TEST(slide == closed_form, boost::test_tools::tolerance(0.02));
  BOOST_REQUIRE(events.size() == 2u);  // the settling stage, then the push's
  const core::StageEvent& settle = events[0];
  BOOST_TEST((settle.kind == core::StageKind::settling));
  BOOST_TEST(settle.at_rest);
  BOOST_TEST(settle.blocks_involved == 0);  // the block only settles on its joint
  const core::StageEvent& e = events[1];
  BOOST_TEST((e.kind == core::StageKind::mechanism));
  BOOST_TEST(e.at_rest);
  BOOST_TEST(e.start_time >= kPushOn - 0.01 - 1e-9);
  BOOST_TEST(e.start_time <= kPushOn + 1e-9);
  BOOST_TEST(e.end_time >= 1.3 - 0.01);
  BOOST_TEST(e.end_time < 1.3 + 0.1);  // at rest well before its longest (1.5 s)
  BOOST_TEST(e.blocks_involved == 1);
  BOOST_TEST(e.largest_displacement == closed_form, boost::test_tools::tolerance(0.05));
  // The push's work went into friction (the stage's dissipation) and the
  // kinetic energy it left is a sliver of it.
  BOOST_TEST(e.work == push * slide * 2.0 / 3.0, boost::test_tools::tolerance(0.05));
  BOOST_TEST(e.kinetic_energy_end <= 1e-3 * e.work);
  BOOST_TEST(e.energy_dissipated == e.work, boost::test_tools::tolerance(0.02));
  BOOST_TEST(!sim.engine.in_stage());
  BOOST_TEST(sim.engine.energy().relative_residual() < 1e-3);
}

BOOST_AUTO_TEST_CASE(the_settling_stage_ends_at_rest_where_its_longest_run_ends) {
  // A block set on its base settles on the joint's normal spring; with block
  // damping the stage comes to rest in a few of the block's periods instead of
  // running its full 0.5 s, and the creep that follows starts from the same
  // state (the same settlement to 1e-6 relative).
  double push = 0.0;
  const SettlingPair r = settle_both(pushed_block(0.1, 1e-3, push), pushed_block(0.1, 0.0, push), plastic_joint());
  const core::StageEvent& a = r.at_rest;
  const core::StageEvent& b = r.longest;
  BOOST_TEST_MESSAGE("settling stage: at rest at " << a.end_time << " s after " << a.steps << " steps; longest "
                                                   << b.end_time << " s, " << b.steps << " steps");
  BOOST_TEST(a.at_rest);
  BOOST_TEST(!b.at_rest);
  BOOST_TEST(b.end_time == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(a.steps < b.steps / 2);
  BOOST_TEST(r.settlement_at_rest < 0.0);
  BOOST_TEST(r.settlement_at_rest == r.settlement_longest, boost::test_tools::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(a_stiff_mode_the_step_does_not_resolve_does_not_keep_the_stage_going) {
  // Stage steps of 50 ms, hundreds of the block's period on the joint's penalty spring
  // (omega dt >> 1), no block or contact damping: the block sinks onto its spring in the
  // first step and is held there, D ~ 0 from then on, while Shi's velocity update
  // v' = 2 D/dt - v changes the sign of its velocity at every step with no loss. The
  // kinetic energy of those end velocities never decays; the stage's rest test reads the
  // motion of the steps (docs/reference/engine.md, "Dynamic stages") and ends it at rest
  // after its first steps, where the stage run to its longest leaves the block at the
  // same settlement.
  double push = 0.0;
  auto settling = [&](double rest_tolerance) {
    core::Model m = pushed_block(0.1, rest_tolerance, push);
    m.settings.settle.dt = 0.05;
    m.settings.settle.max_displacement_ratio = 0.05;
    m.materials[0].damping_ratio = 0.0;
    return m;
  };
  const SettlingPair r = settle_both(settling(1e-6), settling(0.0), joint(kPhi));
  const core::StageEvent& a = r.at_rest;
  const core::StageEvent& b = r.longest;
  BOOST_TEST_MESSAGE("settling stage of 50 ms steps: at rest " << a.at_rest << " at " << a.end_time << " s after "
                                                               << a.steps << " steps, kinetic energy at its end "
                                                               << a.kinetic_energy_end << " J/m, at the longest's end "
                                                               << b.kinetic_energy_end << " J/m, work " << a.work);
  BOOST_TEST(a.at_rest);
  BOOST_TEST(a.steps < b.steps);
  // The end velocities still carry the unresolved mode at the longest stage's end: a rest
  // test on their energy would have run the stage to its longest.
  BOOST_TEST(b.kinetic_energy_end > 1e-6 * b.work);
  BOOST_TEST(r.settlement_at_rest < 0.0);
  BOOST_TEST(r.settlement_at_rest == r.settlement_longest, boost::test_tools::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(rest_tolerance_needs_a_dynamic_settling_stage_and_a_fraction) {
  double push = 0.0;
  auto refused = [](const core::Model& m) {
    BOOST_CHECK_EXCEPTION(core::Engine{m}, core::ModelError,
                          [](const core::ModelError& e) { return e.key() == "settings.settle.rest_tolerance"; });
  };
  core::Model m = pushed_block(0.1, 1e-3, push);
  m.settings.settle.dynamic = false;
  m.settings.settle.collapse_dt = 0.0;
  m.materials[0].damping_ratio = 0.0;
  refused(m);
  refused(pushed_block(0.1, 1.0, push));
  refused(pushed_block(0.1, -1e-3, push));
}

BOOST_AUTO_TEST_SUITE_END()
