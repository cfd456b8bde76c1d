// A block on an incline with the engine: sliding follows the closed form, a
// block thrown up the slope on a soft joint turns back with the friction
// reversed (at every step size), a block pushed down a slope it holds stops
// and sticks (at every step size), and the four classic cases (stable, slides,
// topples, slides and topples) come out as decided by alpha vs phi and b/h vs
// tan(alpha).
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;


BOOST_AUTO_TEST_SUITE(incline)

BOOST_AUTO_TEST_CASE(sliding_block_follows_half_g_sin_minus_cos_tan_phi_t_squared) {
  // Error < 1 % once the block has travelled 1 m, for two slope angles, with
  // either contact solve (docs/reference/contacts.md, "Contact solves").
  for (const auto solver : {core::ContactSolver::open_close, core::ContactSolver::newton})
  for (auto [alpha_deg, phi_deg] : {std::pair{30.0, 20.0}, std::pair{45.0, 30.0}}) {
    const double alpha = deg(alpha_deg), phi = deg(phi_deg), g = 9.81;
    Sim sim(incline_scene(alpha, 1.0, 0.5, 4.0, 0.0, solver), {joint(phi_deg)});
    const double travelled = slide_down(sim, alpha, 1.0);
    const double t = sim.engine.time();
    const double closed_form = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(phi)) * t * t;
    BOOST_TEST_MESSAGE("alpha " << alpha_deg << " phi " << phi_deg << ": t = " << t << " s, DDA "
                                << travelled << " m, closed form " << closed_form << " m");
    BOOST_TEST(travelled >= 1.0);
    BOOST_TEST(travelled == closed_form, boost::test_tools::tolerance(0.01));
  }
}

BOOST_AUTO_TEST_CASE(a_block_that_slipped_slides_on_with_the_residual_friction_angle) {
  // Peak friction 20 deg on a 30 deg slope: the block slips in its first step, which
  // breaks the contacts' intact state (docs/reference/contacts.md, "Friction, cohesion,
  // tension"); from then on they hold only the residual strength (UDEC/3DEC),
  // residual_friction_angle 10 deg and residual_cohesion 0. The first step's
  // acceleration is the peak's, g (sin(alpha) - cos(alpha) tan(phi)), over dt =
  // 1 ms: it moves the block by 1e-6 m, so after 1 m of travel the closed form of
  // the residual friction alone, x = g (sin(alpha) - cos(alpha) tan(phi_r)) t^2 / 2,
  // holds to the 1 % of the peak case above; the peak's closed form is 1.9 x it.
  const double alpha = deg(30.0), phi_r = deg(10.0), g = 9.81;
  contact::JointSet j = joint(20.0);
  j.residual_friction_angle = 10.0;
  j.cohesion = 1000.0;  // [Pa]: far too little to hold 1.3 t on 1 m, lost once slipped
  Sim sim(incline_scene(alpha, 1.0, 0.5, 4.0), {j});
  const double travelled = slide_down(sim, alpha, 1.0);
  const double t = sim.engine.time();
  const double residual = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(phi_r)) * t * t;
  const double peak = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(deg(20.0))) * t * t;
  BOOST_TEST_MESSAGE("residual 10 deg after a slip at peak 20 deg: t = " << t << " s, DDA " << travelled
                     << " m, closed form " << residual << " m (peak's: " << peak << " m)");
  BOOST_TEST(travelled >= 1.0);
  BOOST_TEST(travelled == residual, boost::test_tools::tolerance(0.01));
  for (const contact::Contact& c : sim.contacts.contacts())
    if (c.state != contact::ContactState::open) BOOST_TEST(!c.intact);
}

BOOST_AUTO_TEST_CASE(block_thrown_up_a_soft_joint_turns_back_with_friction_reversed) {
  // Thrown up a 30 deg slope at v0 = 2 m/s on a joint with phi = 20 deg and a
  // soft shear spring (1e6 Pa/m): the block decelerates by
  // g (sin(alpha) + cos(alpha) tan(phi)), stops at t1 = v0 / a_up, stretches
  // its spring to the friction limit, and slides back accelerating by
  // g (sin(alpha) - cos(alpha) tan(phi)) (closed form below). Friction resists
  // every step of the way (its dissipation never falls), at 1 ms and at 0.1 ms.
  // Before the slide-reversal test took its resolution from the normal spring
  // (docs/notes/contact-solves.md, "Friction that pushed"), it was the force resolution over
  // the soft shear spring, 2e-5 m: near the turn the step's backward slip stayed
  // below it, friction kept pushing the block down the slope, and the smaller
  // step turned back faster (the error grows as dt shrinks).
  const double alpha = deg(30.0), phi = deg(20.0), g = 9.81, v0 = 2.0;
  const double a_up = g * (std::sin(alpha) + std::cos(alpha) * std::tan(phi));
  const double a_down = g * (std::sin(alpha) - std::cos(alpha) * std::tan(phi));
  const double t1 = v0 / a_up, t_end = t1 + 0.7;
  const Vec2 up(std::cos(alpha), std::sin(alpha));
  for (const double dt : {1e-3, 1e-4}) {
    BOOST_TEST_CONTEXT("dt " << dt) {
      core::Model m = incline_scene(alpha, 1.0, 0.5, 2.0);
      m.settings.dt = dt;
      m.blocks[1].initial_velocity = v0 * up;
      contact::JointSet j = joint(20.0);
      j.shear_stiffness = 1e6;  // Pa/m
      Sim sim(std::move(m), {j});
      const Vec2 c0 = sim.engine.centroid(1);
      double highest = 0.0, friction = 0.0, friction_drop = 0.0;
      while (sim.engine.time() < t_end - 0.5 * dt) {
        sim.engine.step();
        highest = std::max(highest, sim.engine.point_displacement(1, c0).dot(up));
        const double f = sim.engine.energy().total.dissipation_friction;
        friction_drop = std::max(friction_drop, friction - f);
        friction = f;
      }
      const double back = highest - sim.engine.point_displacement(1, c0).dot(up);
      const double highest_cf = v0 * v0 / (2.0 * a_up);
      // Back from the highest point: stopped, the block rides its joint's shear
      // spring k (restarted unstretched where it stopped, Shi's rule) under the
      // slope's pull G until the spring carries the friction F, then slides:
      // x(t) = (G/k)(1 - cos(w t)), w = sqrt(k/m), until k x = F, i.e. at
      // cos(w ts) = 1 - F/G with speed (G/(m w)) sin(w ts); then
      // x = F/k + v_s (t - ts) + a_down (t - ts)^2 / 2.
      const double mass = 2600.0 * 0.5;                    // kg (1 m x 0.5 m)
      const double k = 1e6 * 1.0;                           // N/m: 1e6 Pa/m over the 1 m base
      const double G = mass * g * std::sin(alpha);          // N
      const double F = mass * g * std::cos(alpha) * std::tan(phi);  // N
      const double w = std::sqrt(k / mass);
      const double ts = std::acos(1.0 - F / G) / w;
      const double vs = G / (mass * w) * std::sin(w * ts);
      const double tr = t_end - t1 - ts;
      const double back_cf = F / k + vs * tr + 0.5 * a_down * tr * tr;
      BOOST_TEST_MESSAGE("dt " << dt << ": up " << highest << " m (closed form " << highest_cf
                               << "), back " << back << " m (closed form " << back_cf
                               << "), friction dissipation " << friction << " J, largest drop "
                               << friction_drop << " J");
      BOOST_TEST(highest == highest_cf, boost::test_tools::tolerance(0.01));
      BOOST_TEST(back == back_cf, boost::test_tools::tolerance(0.005));
      BOOST_TEST(friction_drop <= 1e-6 * friction);
    }
  }
}

BOOST_AUTO_TEST_CASE(block_pushed_down_a_slope_it_holds_stops_and_sticks_at_every_step) {
  // Pushed down a 20 deg slope at v0 = 1 m/s on a joint with phi = 30 deg: the
  // block decelerates by a = g (cos(alpha) tan(phi) - sin(alpha)), stops after
  // v0^2 / (2 a) = 0.254 m, and stays where it stopped: its contacts lock. At
  // every step size. Plastic impacts (restitution 0): undamped, the block's
  // elastic vibration after the stop rattles its corners at 1e-5 s (contacts
  // open and close) and it walks on down the slope at ~1 mm/s.
  const double alpha = deg(20.0), phi = deg(30.0), g = 9.81, v0 = 1.0;
  const double a = g * (std::cos(alpha) * std::tan(phi) - std::sin(alpha));
  const double t1 = v0 / a, travel_cf = v0 * v0 / (2.0 * a);
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  for (const double dt : {1e-3, 1e-4, 1e-5}) {
    BOOST_TEST_CONTEXT("dt " << dt) {
      core::Model m = incline_scene(alpha, 1.0, 0.5, 4.0);
      m.settings.dt = dt;
      m.blocks[1].initial_velocity = v0 * down;
      contact::JointSet j = joint(30.0);
      j.restitution = 0.0;
      Sim sim(std::move(m), {j});
      const Vec2 c0 = sim.engine.centroid(1);
      while (sim.engine.time() < t1 + 0.1 - 0.5 * dt) sim.engine.step();
      const double travel = sim.engine.point_displacement(1, c0).dot(down);
      int sliding = 0, closed = 0;
      for (const contact::Contact& c : sim.contacts.contacts()) {
        if (c.state == contact::ContactState::open) continue;
        ++closed;
        if (c.state == contact::ContactState::sliding) ++sliding;
      }
      const double speed = sim.engine.velocity(1).head<2>().norm();
      BOOST_TEST_MESSAGE("dt " << dt << ": travel " << travel << " m (closed form " << travel_cf
                               << "), speed " << speed << " m/s, " << sliding << " of " << closed
                               << " closed contacts sliding 0.1 s after the stop");
      BOOST_TEST(travel == travel_cf, boost::test_tools::tolerance(0.01));
      BOOST_TEST(closed >= 2);
      BOOST_TEST(sliding == 0);
      BOOST_TEST(speed < 1e-3 * v0);
    }
  }
}

BOOST_AUTO_TEST_CASE(four_cases_stable_slides_topples_slides_and_topples) {
  // alpha = 30 deg (tan = 0.577). At rest the block slides iff alpha > phi and
  // topples iff b/h < tan(alpha) (Hoek & Bray). While it slides, the friction
  // force at the base shifts the normal force downhill by tan(phi) h / 2, so a
  // sliding block keeps toppling only if b/h < tan(phi); and a block that
  // starts toppling loads its pivot corner, which sticks unless phi is well
  // below alpha. The "slides and topples" case therefore takes phi = 10 deg
  // (tan = 0.176) and b/h = 0.15.
  const double alpha = deg(30.0);
  struct Case {
    const char* name;
    double phi_deg, b, h;
    bool slides, topples;
  };
  const Case cases[] = {{"stable", 40.0, 1.0, 1.0, false, false},
                        {"slides", 20.0, 1.0, 1.0, true, false},
                        {"topples", 40.0, 0.4, 1.0, false, true},
                        {"slides and topples", 10.0, 0.15, 1.0, true, true}};
  for (const auto solver : {core::ContactSolver::open_close, core::ContactSolver::newton})
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.name << (solver == core::ContactSolver::newton ? " (newton)" : " (open-close)")) {
      Sim sim(incline_scene(alpha, c.b, c.h, 3.0, 0.0, solver), {joint(c.phi_deg)});
      // The downhill bottom corner: the pivot of toppling, it moves only by slip.
      const Vec2 pivot = sim.engine.vertices(1)[0];
      const Vec2 down(-std::cos(alpha), -std::sin(alpha));
      sim.engine.run(600);  // 0.6 s
      const double slip = sim.engine.point_displacement(1, pivot).dot(down);
      const double rot = std::abs(sim.rotation(1));
      BOOST_TEST_MESSAGE(c.name << ": slip " << slip << " m, rotation " << rot * 180 / std::numbers::pi
                                << " deg");
      if (c.slides) BOOST_TEST(slip > 0.05);
      else BOOST_TEST(std::abs(slip) < 1e-3);
      if (c.topples) BOOST_TEST(rot > deg(5.0));
      else BOOST_TEST(rot < deg(0.1));
    }
  }
}

BOOST_AUTO_TEST_CASE(a_joint_in_tension_holds_by_the_mohr_coulomb_envelope_below_its_cohesion) {
  // Mohr-Coulomb with a tension cut-off (docs/reference/contacts.md, "Friction, cohesion,
  // tension"; contact/strength.hpp): within the tensile strength the envelope holds as it
  // is, tau_max = c + sigma_n tan(phi) with sigma_n < 0, as UDEC's Coulomb slip. A 1 x 0.5 m
  // block glued to a flat base by c = 10 kPa and T = 20 kPa, phi = 30 deg, under a body
  // force that pulls it off the base by rho h g_n = 6.5 kPa and along it by rho h g_t: the
  // joint's strength is c - 6.5 kPa tan(30 deg) = 6.247 kPa. At a shear of 3 kPa it holds
  // (every contact intact and locked, the block still), at 8 kPa it slips in its first step
  // (the cohesion alone, 10 kPa, would hold it). A static step, implicit and by cycles.
  const double rho = 2600.0, h = 0.5, g_n = 5.0, c = 1.0e4, T = 2.0e4, phi = 30.0;
  const double strength = c - rho * h * g_n * std::tan(deg(phi));  // [Pa]
  BOOST_TEST(strength == 6247.2, boost::test_tools::tolerance(1e-4));
  for (const bool cycles : {false, true})
    for (const double shear : {3000.0, 8000.0}) {  // rho h g_t [Pa]
      BOOST_TEST_CONTEXT((cycles ? "by cycles" : "implicit") << ", shear " << shear << " Pa") {
        core::Model m = incline_scene(0.0, 1.0, h, 2.0);
        m.settings.dynamic_ratio = 0.0;  // static
        m.settings.gravity = Vec2(-shear / (rho * h), g_n);
        if (cycles) {
          m.settings.integrator = core::Integrator::explicit_step;
          m.settings.static_force_ratio = 1e-6;
        }
        contact::JointSet j = joint(phi);
        j.cohesion = c;
        j.tensile_strength = T;
        Sim sim(m, {j});
        const Vec2 c0 = sim.engine.centroid(1);
        sim.engine.step();
        bool closed = false, all_intact = true;
        for (const contact::Contact& k : sim.contacts.contacts()) {
          if (k.state == contact::ContactState::open) continue;
          closed = true;
          all_intact = all_intact && k.intact && k.state == contact::ContactState::locked;
        }
        const double moved = sim.engine.point_displacement(1, c0).norm();
        BOOST_TEST_MESSAGE("closed " << closed << ", intact and locked " << all_intact << ", moved " << moved
                                     << " m");
        if (shear < strength) {
          BOOST_TEST(closed);
          BOOST_TEST(all_intact);
          BOOST_TEST(moved < 1e-5);
        } else {
          BOOST_TEST(!(closed && all_intact));
        }
      }
    }
}

BOOST_AUTO_TEST_SUITE_END()
