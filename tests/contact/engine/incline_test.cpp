// A block on an incline with the engine: sliding follows the closed form, and
// the four classic cases (stable, slides, topples, slides and topples) come out
// as decided by alpha vs phi and b/h vs tan(alpha).
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// Fixed base whose top is the line through the origin at angle alpha, and a
/// block b x h resting on it, its lower corner at distance x0 up the slope.
core::Model incline_scene(double alpha, double b, double h, double x0) {
  core::Model m;
  m.settings.dt = 1e-3;
  add_fixed(m, rect(-1.0, -1.0, 7.0, 0.0, alpha));
  m.blocks.push_back(block(rect(x0, 0.0, x0 + b, h, alpha)));
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(incline)

BOOST_AUTO_TEST_CASE(sliding_block_follows_half_g_sin_minus_cos_tan_phi_t_squared) {
  // Error < 1 % once the block has travelled 1 m, for two slope angles.
  for (auto [alpha_deg, phi_deg] : {std::pair{30.0, 20.0}, std::pair{45.0, 30.0}}) {
    const double alpha = deg(alpha_deg), phi = deg(phi_deg), g = 9.81;
    Sim sim(incline_scene(alpha, 1.0, 0.5, 4.0), {joint(phi_deg)});
    const Vec2 c0 = sim.engine.centroid(1);
    const Vec2 down(-std::cos(alpha), -std::sin(alpha));
    double travelled = 0.0;
    while (travelled < 1.0 && sim.engine.step_count() < 5000) {
      sim.engine.step();
      travelled = sim.engine.point_displacement(1, c0).dot(down);
    }
    const double t = sim.engine.time();
    const double closed_form = 0.5 * g * (std::sin(alpha) - std::cos(alpha) * std::tan(phi)) * t * t;
    BOOST_TEST_MESSAGE("alpha " << alpha_deg << " phi " << phi_deg << ": t = " << t << " s, DDA "
                                << travelled << " m, closed form " << closed_form << " m");
    BOOST_TEST(travelled >= 1.0);
    BOOST_TEST(travelled == closed_form, boost::test_tools::tolerance(0.01));
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
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.name) {
      Sim sim(incline_scene(alpha, c.b, c.h, 3.0), {joint(c.phi_deg)});
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

BOOST_AUTO_TEST_SUITE_END()
