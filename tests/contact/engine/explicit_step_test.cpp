// The explicit step (docs/reference/explicit-step.md) against closed forms and against the
// implicit step: free fall, a block sliding down an incline, a block at rest on a slope it
// holds, a block pushed down a slope it holds that stops and sticks, a stack at rest, and
// the same bits whatever the number of threads; each block's cycle against its size; a stop
// asked within the cycles, which abandons the step and changes no bit of the steps after it.
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// The incline of incline_test.cpp (sim.hpp), taken by the explicit step.
core::Model explicit_incline(double alpha, double b, double h, double x0) {
  core::Model m = incline_scene(alpha, b, h, x0);
  m.settings.integrator = core::Integrator::explicit_step;
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(explicit_step)

BOOST_AUTO_TEST_CASE(free_fall_is_exact) {
  // Central difference integrates a constant acceleration exactly: y = g t^2 / 2.
  core::Model m;
  m.settings.dt = 1e-2;
  m.settings.max_displacement_ratio = 1.0;  // steps of 1e-2 s are not cut by the displacement limit
  m.settings.integrator = core::Integrator::explicit_step;
  m.blocks.push_back(block(rect(0.0, 0.0, 1.0, 1.0), Vec2(1.0, 0.0)));
  core::Engine e(std::move(m));
  const Vec2 c0 = e.centroid(0);
  e.run_until(1.0);
  const double t = e.time();
  const Vec2 d = e.point_displacement(0, c0);
  BOOST_TEST(t == 1.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(d.x() == 1.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(d.y() == -0.5 * 9.81 * t * t, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(e.velocity(0)(1) == -9.81 * t, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(sliding_block_follows_half_g_sin_minus_cos_tan_phi_t_squared) {
  // As the implicit step's test (incline_test.cpp): within 1 % once the block has
  // travelled 1 m, for two slope angles.
  for (auto [alpha_deg, phi_deg] : {std::pair{30.0, 20.0}, std::pair{45.0, 30.0}}) {
    const double alpha = deg(alpha_deg), phi = deg(phi_deg), g = 9.81;
    Sim sim(explicit_incline(alpha, 1.0, 0.5, 4.0), {joint(phi_deg)});
    const double travelled = slide_down(sim, alpha, 1.0);
    const double t = sim.engine.time();
    const double closed_form = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(phi)) * t * t;
    BOOST_TEST_MESSAGE("alpha " << alpha_deg << " phi " << phi_deg << ": t = " << t << " s, explicit "
                                << travelled << " m, closed form " << closed_form << " m, "
                                << sim.engine.reports().back().cycles << " cycles per step");
    BOOST_TEST(travelled >= 1.0);
    BOOST_TEST(travelled == closed_form, boost::test_tools::tolerance(0.01));
    BOOST_TEST(sim.engine.reports().back().cycles > 1);
  }
}

BOOST_AUTO_TEST_CASE(block_on_a_slope_it_holds_stays_at_rest) {
  // 20 deg slope, phi 30 deg: the block settles on its springs (under a micrometre) and
  // does not creep down the slope; every contact locked.
  const double alpha = deg(20.0);
  Sim sim(explicit_incline(alpha, 1.0, 0.5, 4.0), {joint(30.0)});
  const Vec2 c0 = sim.engine.centroid(1);
  sim.engine.run_until(1.0);
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  const double along = sim.engine.point_displacement(1, c0).dot(down);
  BOOST_TEST_MESSAGE("along the slope after 1 s: " << along << " m");
  BOOST_TEST(std::abs(along) < 1e-6);
  int locked = 0;
  for (const contact::Contact& c : sim.contacts.contacts()) {
    BOOST_TEST((c.state != contact::ContactState::sliding));
    locked += c.state == contact::ContactState::locked;
  }
  BOOST_TEST(locked >= 2);
}

BOOST_AUTO_TEST_CASE(block_pushed_down_a_slope_it_holds_stops_and_sticks) {
  // As the implicit step's test: pushed at v0 = 1 m/s down a 20 deg slope with phi =
  // 30 deg, the block stops after v0^2 / (2 g (cos(alpha) tan(phi) - sin(alpha))) and
  // stays there, its contacts locked.
  const double alpha = deg(20.0), phi = deg(30.0), g = 9.81, v0 = 1.0;
  const double a = g * (std::cos(alpha) * std::tan(phi) - std::sin(alpha));
  const double t1 = v0 / a, travel_cf = v0 * v0 / (2.0 * a);
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  core::Model m = explicit_incline(alpha, 1.0, 0.5, 4.0);
  m.blocks[1].initial_velocity = v0 * down;
  contact::JointSet j = joint(30.0);
  j.restitution = 0.0;
  Sim sim(std::move(m), {j});
  const Vec2 c0 = sim.engine.centroid(1);
  sim.engine.run_until(t1 + 0.1);
  const double travel = sim.engine.point_displacement(1, c0).dot(down);
  int sliding = 0, closed = 0;
  for (const contact::Contact& c : sim.contacts.contacts()) {
    if (c.state == contact::ContactState::open) continue;
    ++closed;
    sliding += c.state == contact::ContactState::sliding;
  }
  const double speed = sim.engine.velocity(1).head<2>().norm();
  BOOST_TEST_MESSAGE("travel " << travel << " m (closed form " << travel_cf << "), speed " << speed
                               << " m/s, " << sliding << " of " << closed << " contacts sliding");
  BOOST_TEST(travel == travel_cf, boost::test_tools::tolerance(0.01));
  BOOST_TEST(closed >= 2);
  BOOST_TEST(sliding == 0);
  BOOST_TEST(speed < 1e-3 * v0);
}

BOOST_AUTO_TEST_CASE(stack_of_blocks_stays_at_rest) {
  // As the implicit step's stack test: three blocks on a fixed base, 1 s.
  core::Model m;
  m.materials[0].young_modulus = 5e10;
  m.settings.dt = 1e-3;
  m.settings.integrator = core::Integrator::explicit_step;
  add_fixed(m, rect(0.0, -1.0, 3.0, 0.0));
  for (int k = 0; k < 3; ++k) m.blocks.push_back(block(rect(1.0, 0.25 * k, 2.0, 0.25 * (k + 1))));
  Sim sim(std::move(m), {joint(30.0)});
  std::vector<Vec2> c0;
  for (int b = 1; b <= 3; ++b) c0.push_back(sim.engine.centroid(b));
  sim.engine.run(1000);
  for (int b = 1; b <= 3; ++b) {
    const double d = sim.engine.point_displacement(b, c0[b - 1]).norm();
    BOOST_TEST_MESSAGE("block " << b << ": displacement " << d << " m");
    BOOST_TEST(d < 1e-6);
  }
  for (const auto& c : sim.contacts.contacts()) BOOST_TEST((c.state == contact::ContactState::locked));
}

BOOST_AUTO_TEST_CASE(the_same_bits_whatever_the_number_of_threads) {
  // A small running-bond wall, 40 steps at 1, 2 and 3 threads: every vertex and velocity equal
  // to the last bit. Bolted: each brick of the top row to the fixed base and each brick to its
  // right-hand neighbour in its row (33 bolts, enough to be worked in parallel; several on a
  // block, gathered in the bolts' order), the kicked brick's to its neighbour with a yield
  // force it passes; their forces and plastic elongations as well, and the energy balance's
  // dashpot and damping terms booked cycle by cycle (contacts', blocks', bolts') and residual.
  auto run = [](int threads, bool bolted) {
    core::Model m = running_bond_wall(6, 5, core::SolverKind::cholmod);
    m.settings.integrator = core::Integrator::explicit_step;
    m.settings.threads = threads;
    m.blocks.back().initial_velocity = Vec2(0.5, -0.2);
    if (bolted) {
      const int n = static_cast<int>(m.blocks.size());
      auto centre = [&m](int b) {
        Vec2 c = Vec2::Zero();
        for (const Vec2& v : m.blocks[b].vertices) c += v;
        return Vec2(c / static_cast<double>(m.blocks[b].vertices.size()));
      };
      for (int b = n - 6; b < n; ++b) {  // the top row (6 bricks) to the base
        core::Bolt bolt;
        bolt.block_a = b;
        bolt.point_a = centre(b);
        bolt.block_b = 0;
        bolt.point_b = Vec2(centre(b).x(), -0.25);
        bolt.axial_stiffness = 1e7;  // N/m
        m.bolts.push_back(bolt);
      }
      for (int b = 1; b + 1 < n; ++b) {  // neighbours in a row: the next brick, at the same height
        if (std::abs(centre(b + 1).y() - centre(b).y()) > 1e-9) continue;
        core::Bolt bolt;
        bolt.block_a = b;
        bolt.point_a = centre(b);
        bolt.block_b = b + 1;
        bolt.point_b = centre(b + 1);
        bolt.axial_stiffness = 5e6;  // N/m
        m.bolts.push_back(bolt);
      }
      BOOST_TEST_REQUIRE(m.bolts.size() == 33u);
      m.bolts.back().yield_force = 2e3;  // N: the kicked brick pulls its neighbour's bolt beyond it
    }
    Sim sim(std::move(m), {joint(30.0)});
    sim.engine.run(40);
    std::vector<double> out;
    for (int b = 0; b < sim.engine.block_count(); ++b) {
      for (const Vec2& v : sim.engine.vertices(b)) out.push_back(v.x()), out.push_back(v.y());
      for (int i = 0; i < 6; ++i) out.push_back(sim.engine.velocity(b)(i));
    }
    for (const core::BoltState& s : sim.engine.bolts()) out.push_back(s.force), out.push_back(s.plastic_elongation);
    const core::EnergyFlows& e = sim.engine.energy().total;
    for (const double x : {e.dissipation_contact_damping, e.dissipation_block_damping, e.dissipation_bolt, e.residual})
      out.push_back(x);
    if (bolted) {
      const core::BoltState& kicked = sim.engine.bolts().back();
      BOOST_TEST_MESSAGE("threads " << threads << ": the kicked brick's bolt " << core::bolt_mode_name(kicked.state)
                                    << ", force " << kicked.force << " N, plastic elongation "
                                    << kicked.plastic_elongation << " m");
      BOOST_TEST(kicked.plastic_elongation != 0.0);
    }
    return out;
  };
  for (const bool bolted : {false, true}) {
    const std::vector<double> one = run(1, bolted);
    for (int threads : {2, 3}) {
      const std::vector<double> many = run(threads, bolted);
      BOOST_TEST_CONTEXT("threads " << threads << ", bolted " << bolted) {
        BOOST_TEST_REQUIRE(many.size() == one.size());
        std::size_t differ = 0;
        for (std::size_t k = 0; k < one.size(); ++k) differ += many[k] != one[k];
        BOOST_TEST(differ == 0u);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_stop_asked_within_the_cycles_abandons_the_step_and_the_run_goes_on_to_the_same_bits) {
  // Engine::set_stop_request: the cycles look at it every kStopPollCycles cycles. Asked and
  // never answered yes, it changes no bit; answered yes within step 10's cycles, the step is
  // abandoned (StepInterrupted) with the engine and the contacts as after step 9, and the
  // steps taken from there are those of the run that was never stopped, to the last bit.
  const auto state = engine_state;
  auto wall = [] {
    core::Model m = running_bond_wall(6, 5, core::SolverKind::cholmod);
    m.settings.integrator = core::Integrator::explicit_step;
    m.blocks.back().initial_velocity = Vec2(0.5, -0.2);
    return m;
  };
  Sim whole(wall(), {joint(30.0)});
  long asked = 0;
  whole.engine.set_stop_request([&asked] { return ++asked < 0; });  // asked, never yes
  whole.engine.run(10);
  const std::vector<double> after_10 = state(whole);
  whole.engine.run(10);
  BOOST_TEST_REQUIRE(whole.engine.reports().front().cycles > core::Engine::kStopPollCycles);
  BOOST_TEST(asked > 0);

  Sim plain(wall(), {joint(30.0)});  // never asked
  plain.engine.run(20);
  BOOST_TEST((state(plain) == state(whole)));

  Sim stopped(wall(), {joint(30.0)});
  bool stop = false;
  stopped.engine.set_stop_request([&stop] { return stop; });
  stopped.engine.run(10);
  stop = true;
  BOOST_CHECK_THROW(stopped.engine.step(), core::StepInterrupted);
  BOOST_TEST(stopped.engine.step_count() == 10);
  BOOST_TEST((state(stopped) == after_10));
  stop = false;
  stopped.engine.run(10);
  BOOST_TEST(stopped.engine.step_count() == 20);
  BOOST_TEST((state(stopped) == state(whole)));
}

/// A static analysis whose dynamic settling stage (1 ms steps, at most `until` long, ending at
/// rest) is taken in explicit cycles; the blocks are the caller's.
core::Model explicit_settling_model(double until) {
  core::Model m;
  m.settings.dt = 1e-2;
  m.settings.dynamic_ratio = 0.0;
  m.settings.settle.until = until;
  m.settings.settle.dt = 1e-3;
  m.settings.settle.max_displacement_ratio = 1e-3;
  m.settings.settle.dynamic = true;
  m.settings.settle.rest_tolerance = 1e-6;
  m.settings.integrator = core::Integrator::explicit_step;
  return m;
}

BOOST_AUTO_TEST_CASE(a_settling_stage_taken_explicitly_ends_at_rest_where_the_rigid_plastic_impact_does) {
  // A static analysis whose dynamic settling stage (ends at rest, docs/reference/engine.md,
  // "Dynamic stages") drops a block 1 mm (normal to the slope) onto a 20 deg slope with
  // phi 30 deg and plastic impacts: at the impact the normal velocity v cos(alpha) goes, and
  // friction's impulse tan(phi) v cos(alpha) exceeds the tangential v sin(alpha), so the block
  // sticks where it lands (rigid-plastic). Taken explicitly, with and without local damping
  // 0.8, the stage ends at rest there: the vertical fall 1 mm / cos(alpha) within 1 %, no
  // horizontal motion (under 1e-5 m). (The implicit step at the stage's 1 ms steps slides 1.3 mm at the impact:
  // docs/reference/contacts.md, "Contact damping".) Placed touching instead, the block settles
  // on its springs, and local damping brings that to rest no later.
  const double alpha = deg(20.0);
  struct Run {
    Vec2 displacement;
    double end = 0.0;
    bool at_rest = false;
  };
  auto run = [&](double gap, double local_damping) {
    core::Model m = explicit_settling_model(2.0);
    m.settings.stage_local_damping = local_damping;
    m.materials[0].damping_ratio = 1.0;
    add_fixed(m, rect(-1.0, -1.0, 7.0, 0.0, alpha));
    m.blocks.push_back(block(rect(4.0, gap, 5.0, gap + 0.5, alpha)));
    contact::JointSet j = joint(30.0);
    j.restitution = 0.0;
    Sim sim(std::move(m), {j});
    const Vec2 c0 = sim.engine.centroid(1);
    sim.engine.run_until(2.5);
    Run r;
    r.displacement = sim.engine.point_displacement(1, c0);
    BOOST_TEST_REQUIRE(!sim.engine.events().empty());
    r.end = sim.engine.events().front().end_time;
    r.at_rest = sim.engine.events().front().at_rest;
    BOOST_TEST_MESSAGE("gap " << gap << ", local damping " << local_damping << ": stage ends at " << r.end
                              << " s (at rest " << r.at_rest << "), displacement " << r.displacement.transpose()
                              << " m");
    return r;
  };
  for (const double local_damping : {0.0, 0.8}) {
    // It falls vertically until the gap normal to the slope closes, 1 mm / cos(alpha), and stays.
    const Run r = run(0.001, local_damping);
    BOOST_TEST(r.at_rest);
    BOOST_TEST(r.displacement.y() == -0.001 / std::cos(alpha), boost::test_tools::tolerance(0.01));
    BOOST_TEST(std::abs(r.displacement.x()) < 1e-5);
  }
  const Run plain = run(0.0, 0.0), damped = run(0.0, 0.8);
  BOOST_TEST(plain.at_rest);
  BOOST_TEST(damped.at_rest);
  BOOST_TEST((damped.displacement - plain.displacement).norm() < 1e-6);
  BOOST_TEST(damped.end <= plain.end);
}

BOOST_AUTO_TEST_CASE(density_scaling_bounds_the_cycles_of_a_stage_and_keeps_its_state_at_rest) {
  // A static analysis's settling stage (ends at rest) of a 1 m x 0.5 m block carrying a
  // 0.6 m x 0.02 m plate, on a fixed base, placed touching: the plate's strain unknowns on the
  // penalty springs set a cycle far below the block's. With stage_cycles = 20 (density
  // scaling, docs/reference/explicit-step.md) no step of the stage takes more than 20 cycles,
  // the plate's mass is scaled up, the stage still ends at rest, the state at rest is the
  // unscaled one (the stack's settlement on its springs, within 1 % of it), and the energy
  // balance, kept with the scaled masses, closes. It closes less tightly than the unscaled
  // one's: the scaled plate's modes move at 20 cycles per step, near the stable cycle, where
  // central difference's discrete energy departs from the true one by O((omega h)^2) (the
  // stage's first step leaves most of it); the unscaled stage resolves its motion in 2 144
  // cycles per step.
  struct Run {
    double settle_plate = 0.0, settle_block = 0.0, largest_scale = 1.0, residual = 0.0;
    int most_cycles = 0, stage_steps = 0;
    bool at_rest = false;
  };
  auto run = [](int stage_cycles) {
    core::Model m = explicit_settling_model(1.0);
    m.settings.stage_local_damping = 0.8;
    m.settings.stage_cycles = stage_cycles;
    add_fixed(m, rect(-1.0, -1.0, 2.0, 0.0));
    m.blocks.push_back(block(rect(0.0, 0.0, 1.0, 0.5)));
    m.blocks.push_back(block(rect(0.2, 0.5, 0.8, 0.52)));
    Sim sim(std::move(m), {joint(30.0)});
    const Vec2 b0 = sim.engine.centroid(1), p0 = sim.engine.centroid(2);
    Run r;
    sim.engine.add_observer([&](const core::Engine& e, const core::StepReport& rep) {
      if (!e.in_stage() && rep.cycles == 0) return;
      r.most_cycles = std::max(r.most_cycles, rep.cycles);
      r.largest_scale = std::max(r.largest_scale, rep.mass_scale);
      ++r.stage_steps;
    });
    sim.engine.run_until(1.2);
    BOOST_TEST_REQUIRE(!sim.engine.events().empty());
    r.at_rest = sim.engine.events().front().at_rest;
    r.settle_block = -sim.engine.point_displacement(1, b0).y();
    r.settle_plate = -sim.engine.point_displacement(2, p0).y();
    r.residual = sim.engine.energy().relative_residual();
    BOOST_TEST_MESSAGE("stage_cycles " << stage_cycles << ": " << r.stage_steps << " stage steps, at most "
                                       << r.most_cycles << " cycles, largest scale " << r.largest_scale
                                       << ", settlement block " << r.settle_block << " m, plate " << r.settle_plate
                                       << " m, residual " << r.residual);
    return r;
  };
  const Run plain = run(0), scaled = run(20);
  BOOST_TEST(plain.most_cycles > 20);  // the case needs the scaling
  BOOST_TEST(scaled.most_cycles <= 20);
  BOOST_TEST(scaled.largest_scale > 1.0);
  BOOST_TEST(plain.largest_scale == 1.0);
  BOOST_TEST(plain.at_rest);
  BOOST_TEST(scaled.at_rest);
  BOOST_TEST(plain.settle_block > 0.0);
  BOOST_TEST(scaled.settle_block == plain.settle_block, boost::test_tools::tolerance(0.01));
  BOOST_TEST(scaled.settle_plate == plain.settle_plate, boost::test_tools::tolerance(0.01));
  BOOST_TEST(plain.residual < 1e-3);
  BOOST_TEST(scaled.residual < 0.02);
}

BOOST_AUTO_TEST_CASE(each_blocks_cycle_shrinks_with_its_size_and_the_smallest_is_the_scenes) {
  // Two squares on a fixed base, 1 m and 0.25 m, apart, undamped (explicit_damping 0: no
  // dashpot, no strain damping, so that (3) is 2/omega_max). Each rests on two corner
  // contacts of the same penalty springs; its mass and its strain inertia scale as L^2 and
  // L^4, its springs' levers as L: omega_max ~ 1/L, and the small square's cycle is a quarter
  // of the large one's. The scene's cycle is the smaller, set by the small square; the base,
  // held, has none.
  core::Model m;
  m.settings.dt = 1e-3;
  m.settings.integrator = core::Integrator::explicit_step;
  m.settings.explicit_damping = 0.0;
  add_fixed(m, rect(-1.0, -1.0, 4.0, 0.0));
  m.blocks.push_back(block(rect(0.0, 0.0, 1.0, 1.0)));
  m.blocks.push_back(block(rect(2.0, 0.0, 2.25, 0.25)));
  Sim sim(std::move(m), {joint(30.0)});
  const std::vector<double> h = sim.engine.block_cycles();
  const core::Engine::StableCycle c = sim.engine.stable_cycle();
  BOOST_TEST_MESSAGE("cycles: large " << h[1] << " s, small " << h[2] << " s, scene " << c.cycle << " s (block "
                                      << c.block << ")");
  BOOST_TEST_REQUIRE(h.size() == 3u);
  BOOST_TEST(std::isinf(h[0]));
  BOOST_TEST(std::isfinite(h[1]));
  BOOST_TEST(h[2] == 0.25 * h[1], boost::test_tools::tolerance(1e-6));
  BOOST_TEST(c.block == 2);
  BOOST_TEST(c.cycle == h[2]);
}

BOOST_AUTO_TEST_CASE(a_stage_at_rest_by_its_unbalanced_force_ratio_holds_the_stack_in_equilibrium) {
  // The density-scaled stack of the case above, its stage ending at rest by the unbalanced-force
  // ratio (settle.force_ratio, UDEC's test) instead of the kinetic energy. At rest the plate's
  // weight is carried by its contacts: the sum of their normal forces on the plate equals its
  // weight to the ratio's order, and its settlement on the penalty springs equals the
  // kinetic-energy stage's within 1e-3 relative; a tighter ratio takes more steps.
  struct Run {
    double settle_plate = 0.0, carried = 0.0, weight = 0.0;
    int stage_steps = 0;
    bool at_rest = false;
  };
  auto run = [](double force_ratio) {
    core::Model m = explicit_settling_model(1.0);
    m.settings.stage_local_damping = 0.8;
    m.settings.stage_cycles = 20;
    m.settings.settle.force_ratio = force_ratio;
    add_fixed(m, rect(-1.0, -1.0, 2.0, 0.0));
    m.blocks.push_back(block(rect(0.0, 0.0, 1.0, 0.5)));
    m.blocks.push_back(block(rect(0.2, 0.5, 0.8, 0.52)));
    const double g = -m.settings.gravity.y();
    const double density = m.materials.front().density;
    Sim sim(std::move(m), {joint(30.0)});
    const Vec2 p0 = sim.engine.centroid(2);
    sim.engine.run_until(1.2);
    BOOST_TEST_REQUIRE(!sim.engine.events().empty());
    Run r;
    r.at_rest = sim.engine.events().front().at_rest;
    r.stage_steps = sim.engine.events().front().steps;
    r.settle_plate = -sim.engine.point_displacement(2, p0).y();
    r.weight = density * 0.6 * 0.02 * g;
    for (const contact::Contact& c : sim.contacts.contacts())  // the plate rests on the block alone
      if (c.key.vblock == 2 || c.key.eblock == 2) r.carried += std::abs(c.normal_force);
    BOOST_TEST_MESSAGE("force_ratio " << force_ratio << ": " << r.stage_steps << " stage steps, plate "
                                      << r.settle_plate << " m, carried " << r.carried << " of " << r.weight);
    return r;
  };
  const Run energy = run(0.0), loose = run(1e-3), tight = run(1e-6);
  BOOST_TEST(loose.at_rest);
  BOOST_TEST(tight.at_rest);
  BOOST_TEST(tight.stage_steps >= loose.stage_steps);
  BOOST_TEST(tight.carried == tight.weight, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(tight.settle_plate == energy.settle_plate, boost::test_tools::tolerance(1e-3));
}

BOOST_AUTO_TEST_CASE(settings_out_of_range_are_refused) {
  core::Model m = explicit_incline(deg(20.0), 1.0, 0.5, 4.0);
  m.settings.explicit_safety = 1.5;
  BOOST_CHECK_EXCEPTION(core::Engine{m}, core::ModelError,
                        [](const core::ModelError& e) { return e.key() == "settings.explicit_safety"; });
  m.settings.explicit_safety = 0.5;
  m.settings.dynamic_ratio = 0.0;  // static, no dynamic stage: nothing to integrate explicitly
  BOOST_CHECK_EXCEPTION(core::Engine{m}, core::ModelError,
                        [](const core::ModelError& e) { return e.key() == "settings.integrator"; });
}

BOOST_AUTO_TEST_SUITE_END()
