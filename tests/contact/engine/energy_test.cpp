// The energy balance with contacts (docs/reference/engine.md, "Energy balance"): a block
// sliding down an incline dissipates N tan(phi) x slip by friction, a block
// dropped onto a base loses its impact energy to the integration and the
// closing contacts, a small brick wall settles, a block dropped on an incline
// settles at two step sizes, and a creeping joint dissipates F x creep; in
// every case the residual of the balance stays below 1 % of the work put in.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "creep_scene.hpp"
#include "brick_wall.hpp"
#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

constexpr double kRho = 2600.0, kG = 9.81;  // default material density [kg/m^3], gravity [m/s^2]

/// The running-bond brick wall of the benchmarks (tests/models/brick_wall.hpp).
core::Model brick_wall(int nx, int ny) { return models::running_bond_wall(nx, ny); }

/// One line with every term of the balance since t = 0, for the test log.
std::string summary(const core::Engine& e) {
  const core::EnergyBalance& b = e.energy();
  const core::EnergyFlows& t = b.total;
  std::ostringstream s;
  s << "KE " << b.stored.kinetic << ", U (blocks, fixed, normal, shear) " << b.stored.strain << ", "
    << b.stored.fixed << ", " << b.stored.contact_normal << ", " << b.stored.contact_shear
    << "; W_g " << t.work_gravity << ", W_l " << t.work_loads << ", restart "
    << t.work_contact_restart << "; friction " << t.dissipation_friction << ", creep "
    << t.dissipation_creep << ", integration " << t.dissipation_integration << ", damping "
    << t.dissipation_contact_damping << ", closing " << t.dissipation_contact_closing
    << ", release " << t.dissipation_contact_release << "; residual " << t.residual
    << " (largest relative " << b.max_relative_residual << ")";
  return s.str();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(energy_balance)

BOOST_AUTO_TEST_CASE(sliding_block_dissipates_n_tan_phi_times_the_slip) {
  const double alpha = deg(30.0), phi = deg(20.0);
  Sim sim(incline_scene(alpha, 1.0, 0.5, 4.0), {joint(20.0)});
  const double travelled = slide_down(sim, alpha, 1.0);
  const core::EnergyBalance& b = sim.engine.energy();
  const double m = kRho * 0.5;  // 1 m x 0.5 m
  BOOST_TEST_MESSAGE("sliding block: travelled " << travelled << " m; " << summary(sim.engine));
  BOOST_TEST(travelled >= 1.0);
  // Gravity: m g sin(alpha) per metre down the slope; friction: N = m g cos(alpha).
  BOOST_TEST(b.total.work_gravity == m * kG * std::sin(alpha) * travelled,
             boost::test_tools::tolerance(1e-3));
  BOOST_TEST(b.total.dissipation_friction == m * kG * std::cos(alpha) * std::tan(phi) * travelled,
             boost::test_tools::tolerance(0.01));
  BOOST_TEST(b.max_relative_residual < 0.01);
}

BOOST_AUTO_TEST_CASE(bouncing_block_loses_its_impact_energy_to_named_terms) {
  // A 1 m square dropped 5 cm onto a fixed base: it hits at 1 m/s after 0.1 s.
  core::Model m;
  m.settings.dt = 1e-3;
  add_fixed(m, rect(-1.0, -1.0, 3.0, 0.0));
  m.blocks.push_back(block(rect(0.5, 0.05, 1.5, 1.05)));
  Sim sim(m, {joint(30.0)});
  double ke_impact = 0.0;
  while (sim.engine.time() < 0.6 - 1e-9) {
    sim.engine.step();
    if (sim.engine.time() < 0.1 + 1e-9) ke_impact = sim.engine.energy().stored.kinetic;
  }
  const core::EnergyBalance& b = sim.engine.energy();
  BOOST_TEST_MESSAGE("bouncing block: KE at impact " << ke_impact << "; " << summary(sim.engine));
  // Free fall until then (the gap closes at t = 0.101 s): KE = m (g t)^2/2.
  BOOST_TEST(ke_impact == 0.5 * kRho * (kG * 0.1) * (kG * 0.1), boost::test_tools::tolerance(1e-9));
  // The block comes to rest: what gravity put in was dissipated (with Shi's
  // scheme and no contact dashpot: by the integration and the contacts that
  // closed and opened; every dissipation term counts, whatever the model has).
  BOOST_TEST(b.stored.kinetic < 1e-3 * ke_impact);
  const double dissipated = b.total.work_gravity + b.total.work_loads +
                            b.total.work_contact_restart - b.total.net_input();
  BOOST_TEST(dissipated > 0.9 * b.total.work_gravity);
  BOOST_TEST(b.max_relative_residual < 0.01);
}

BOOST_AUTO_TEST_CASE(small_brick_wall_settles_with_a_closed_balance) {
  Sim sim(brick_wall(3, 3), {joint(30.0)});
  sim.engine.run(200);
  const core::EnergyBalance& b = sim.engine.energy();
  BOOST_TEST_MESSAGE("3 x 3 wall: " << summary(sim.engine));
  BOOST_TEST(b.total.work_gravity > 0.0);
  BOOST_TEST(b.stored.contact_normal > 0.0);
  BOOST_TEST(b.max_relative_residual < 0.01);
}

BOOST_AUTO_TEST_CASE(block_dropped_on_an_incline_closes_the_balance_at_two_steps) {
  // 30 deg slope, phi = 35 deg (stable at rest), dropped 1 cm: at the smaller
  // step the block slides further (Shi's scheme damps the impact less); the
  // balance says where the energy went at both steps.
  for (const double dt : {1e-3, 1e-4}) {
    core::Model m = incline_scene(deg(30.0), 1.0, 0.5, 3.0, 0.01);
    m.settings.dt = dt;
    Sim sim(m, {joint(35.0)});
    const Vec2 c0 = sim.engine.centroid(1);
    sim.engine.run_until(0.5);
    BOOST_TEST_MESSAGE("dropped on an incline, dt " << dt << ": centroid moved "
                                                    << (sim.engine.centroid(1) - c0).norm() << " m; "
                                                    << summary(sim.engine));
    BOOST_TEST(sim.engine.energy().max_relative_residual < 0.01);
  }
}

BOOST_AUTO_TEST_CASE(contacts_held_locked_outside_their_envelope_are_committed_onto_it_with_the_energy_booked) {
  // A block pushed down a 20 deg slope it holds (phi = 30 deg) stops within a step: its
  // corners chatter between sliding and stuck, and with max_flips 1 the open-close
  // iteration's anti-chattering rule holds them locked after their first change, with
  // shear beyond N tan(phi) (docs/reference/contacts.md, "States and the open-close
  // iteration"). No step may commit such a state: each is committed locked at its strength
  // (its spring slipping plastically) or open, and the spring energy that releases is
  // booked, so the balance stays closed.
  const double alpha = deg(20.0), v0 = 1.0;
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  for (const double dt : {1e-3, 1e-4}) {
    BOOST_TEST_CONTEXT("dt " << dt) {
      core::Model m = incline_scene(alpha, 1.0, 0.5, 4.0);
      m.settings.dt = dt;
      m.blocks[1].initial_velocity = v0 * down;
      contact::JointSet j = joint(30.0);
      contact::ContactSettings settings = core::contact_settings_for(m, 40.0);
      settings.max_flips = 1;
      Sim sim(std::move(m), {j}, settings);
      std::size_t projected = 0;
      double worst = 0.0;  // largest committed excess over the envelope / the largest N
      while (sim.engine.time() < 0.4 - 0.5 * dt) {
        sim.engine.step();
        projected += sim.contacts.last_projections();
        double largest = 0.0, excess = 0.0;
        for (const contact::Contact& c : sim.contacts.contacts()) {
          if (c.state == contact::ContactState::open) continue;
          largest = std::max(largest, std::abs(c.normal_force));
          if (c.state != contact::ContactState::locked) continue;
          excess = std::max({excess, std::abs(c.shear_force) - c.normal_force * std::tan(deg(30.0)),
                             -c.normal_force});
        }
        if (largest > 0.0) worst = std::max(worst, excess / largest);
      }
      const core::EnergyBalance& b = sim.engine.energy();
      BOOST_TEST_MESSAGE("dt " << dt << ": " << projected << " contacts projected, worst committed excess "
                               << worst << " of the largest N; " << summary(sim.engine));
      BOOST_TEST(projected > 0u);             // the rule was exercised
      BOOST_TEST(worst <= 1e-3);              // within the force resolution (1e-3 of the largest N)
      BOOST_TEST(b.total.dissipation_contact_release > 0.0);
      BOOST_TEST(b.max_relative_residual < 0.01);
    }
  }
}

BOOST_AUTO_TEST_CASE(explicit_cycles_book_friction_cycle_by_cycle) {
  // A block pushed at v0 = 1 m/s down a 20 deg slope it holds (phi = 30 deg), taken in the
  // explicit step's cycles (docs/reference/explicit-step.md): it slides, slows and stops
  // within a step, and its corners' states change between the cycles of a step. The book
  // takes what the cycles did (friction: T times the drag of the locking point at each
  // cycle; the springs' energy where they detach and attach), not the step's end force
  // over its end slip, so the friction it books is the closed form's, N tan(phi) x the
  // travel, and the balance closes. (The end-of-step booking gave a relative residual of
  // 2e-3 here.)
  const double alpha = deg(20.0), phi = deg(30.0), v0 = 1.0, g = kG;
  const double t1 = v0 / (g * (std::cos(alpha) * std::tan(phi) - std::sin(alpha)));  // when it stops
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  for (const double t_end : {0.5 * t1, t1 + 0.1}) {
    BOOST_TEST_CONTEXT("until " << t_end << " s") {
      core::Model m = incline_scene(alpha, 1.0, 0.5, 4.0);
      m.settings.integrator = core::Integrator::explicit_step;
      m.blocks[1].initial_velocity = v0 * down;
      Sim sim(std::move(m), {joint(30.0)});
      const Vec2 c0 = sim.engine.centroid(1);
      sim.engine.run_until(t_end);
      const double travel = sim.engine.point_displacement(1, c0).dot(down);
      const core::EnergyBalance& b = sim.engine.energy();
      const double mass = kRho * 0.5;  // 1 m x 0.5 m
      const double friction = mass * g * std::cos(alpha) * std::tan(phi) * travel;
      BOOST_TEST_MESSAGE("explicit, pushed block until " << t_end << " s: travel " << travel
                                                         << " m, friction closed form " << friction << "; "
                                                         << summary(sim.engine));
      BOOST_TEST(b.total.dissipation_friction == friction, boost::test_tools::tolerance(2e-3));
      BOOST_TEST(b.total.dissipation_integration == 0.0);  // the cycles' springs lose none to it
      BOOST_TEST(b.max_relative_residual < 2e-4);
    }
  }
}

BOOST_AUTO_TEST_CASE(creeping_joint_dissipates_the_shear_force_times_the_creep) {
  // The seed's two-block shear creep test (Table 1 row 1): the joint's shear
  // force F2 = tau w is constant, so the creep work over T is F2 d_c(T), d_c
  // the Burgers creep (Kelvin + dashpot) of the closed form; also under step
  // doubling (extrapolated steps).
  const Table1Row& row = kTable1[0];
  for (const double tolerance : {0.0, 1e-6}) {
    CreepScene scene(table1_burgers(row), row.sigma, row.tau, 1.0);
    scene.model.settings.step_tolerance = tolerance;
    Sim sim(scene.model, {scene.joint});
    sim.engine.run_until(200.0);
    const core::EnergyBalance& b = sim.engine.energy();
    const double expected = row.tau * CreepScene::w * table1_burgers(row)->creep_closed_form(row.tau, 200.0);
    BOOST_TEST_MESSAGE("shear creep, step_tolerance " << tolerance << ": creep work expected "
                                                      << expected << "; " << summary(sim.engine));
    BOOST_TEST(b.total.dissipation_creep == expected, boost::test_tools::tolerance(1e-3));
    BOOST_TEST(b.max_relative_residual < 1e-4);
  }
}

BOOST_AUTO_TEST_SUITE_END()
