// A stack of blocks on a fixed base stays at rest; a damped wall at rest has no
// more joints sliding at their friction limit the smaller the step.
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

BOOST_AUTO_TEST_SUITE(stack)

BOOST_AUTO_TEST_CASE(stack_of_blocks_at_rest_stays_at_rest_for_ten_thousand_steps) {
  // Granite-like blocks 1 m x 0.25 m: the elastic and penalty settlement of
  // the stack under its own weight (~2e-7 m) is within the bound, so the bound
  // tests that nothing drifts, rocks or slides.
  core::Model m;
  m.materials[0].young_modulus = 5e10;  // [Pa]
  m.settings.dt = 1e-3;
  add_fixed(m, rect(0.0, -1.0, 3.0, 0.0));
  for (int k = 0; k < 3; ++k)
    m.blocks.push_back(block(rect(1.0, 0.25 * k, 2.0, 0.25 * (k + 1))));
  Sim sim(std::move(m), {joint(30.0)});
  std::vector<Vec2> c0;
  for (int b = 1; b <= 3; ++b) c0.push_back(sim.engine.centroid(b));
  sim.engine.run(10000);
  BOOST_TEST(sim.engine.step_count() == 10000);
  const double size = 1.0;  // block width [m]
  for (int b = 1; b <= 3; ++b) {
    const double d = sim.engine.point_displacement(b, c0[b - 1]).norm();
    BOOST_TEST_MESSAGE("block " << b << ": displacement " << d << " m");
    BOOST_TEST(d < 1e-6 * size);
  }
  for (const auto& c : sim.contacts.contacts())
    BOOST_TEST((c.state == contact::ContactState::locked));
}


namespace {

/// Running-bond wall of `courses` courses of bricks 0.2 m x 0.1 m, `bricks`
/// long, on a fixed base; E 5 GPa, nu 0.25, critically damped blocks and
/// plastic impacts (the damped wall of docs/notes/step-controls.md, smaller), penalty
/// 50 E, stick_keeps_force (a dynamic scene's default), dt and max_displacement_ratio from the level (halved per level). Returns the mean over the
/// closed contacts of |shear displacement| [m] after 20 ms and counts the
/// contacts sliding then.
struct WallRest {
  double mean_shear = 0.0;
  int sliding = 0, closed = 0;
};

WallRest damped_wall_at_rest(int bricks, int courses, int level) {
  const double w = 0.2, h = 0.1, scale = std::ldexp(1.0, -level);
  core::Model m;
  m.materials[0].young_modulus = 5e9;   // Pa
  m.materials[0].poisson_ratio = 0.25;
  m.materials[0].damping_ratio = 1.0;
  m.settings.dt = 3.125e-5 * scale;     // s
  m.settings.max_displacement_ratio = 1.25e-5 * scale;
  add_fixed(m, rect(-0.5, -0.5, bricks * w + 0.5, 0.0));
  for (int r = 0; r < courses; ++r) {
    std::vector<double> cuts{0.0};
    if (r % 2 == 1) cuts.push_back(0.5 * w);
    while (cuts.back() + w < bricks * w - 1e-9) cuts.push_back(cuts.back() + w);
    cuts.push_back(bricks * w);
    for (size_t k = 0; k + 1 < cuts.size(); ++k)
      m.blocks.push_back(block(rect(cuts[k], r * h, cuts[k + 1], (r + 1) * h)));
  }
  contact::JointSet j = joint(30.0);
  j.restitution = 0.0;
  contact::ContactSettings settings = core::contact_settings_for(m, 50.0);
  settings.stick_keeps_force = true;  // as a dynamic scene (docs/notes/contact-solves.md, "Stick and slip")
  Sim sim(std::move(m), {j}, settings);
  while (sim.engine.time() < 0.02 - 1e-12) sim.engine.step();
  WallRest out;
  for (const auto& c : sim.contacts.contacts()) {
    if (c.state == contact::ContactState::open) continue;
    ++out.closed;
    if (c.state == contact::ContactState::sliding) ++out.sliding;
    out.mean_shear += std::abs(c.shear_displacement);
  }
  out.mean_shear /= std::max(out.closed, 1);
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(damped_wall_at_rest_has_no_more_sliding_joints_the_smaller_the_step) {
  // A 3-brick, 14-course damped wall stands. At 20 ms, at dt 31, 16, 7.8 and
  // 3.9 us (max_displacement_ratio halved with it), the contacts still sliding - at their
  // friction limit - are a few, and no more at the finer steps than at the
  // coarser ones. Before the slide-reversal test counted the step's inertia
  // (ContactSettings::reversal_at_normal_resolution; docs/reference/contacts.md,
  // "Contacts that stop") the counts were 0, 2, 8, 14: a contact whose
  // friction exceeded its drive moved backwards by less than the fixed
  // resolution f_res / p_n once dt was small (its backward slip shrinks as
  // dt^2) and stayed sliding, more of them the smaller the step.
  std::vector<WallRest> levels;
  for (int level = 0; level < 4; ++level) {
    levels.push_back(damped_wall_at_rest(3, 14, level));
    BOOST_TEST_MESSAGE("level " << level << ": mean |shear displacement| " << levels.back().mean_shear
                                << " m, " << levels.back().sliding << " of " << levels.back().closed
                                << " closed contacts sliding");
    BOOST_TEST(levels.back().closed > 100);
  }
  const int coarse = std::max(levels[0].sliding, levels[1].sliding);
  BOOST_TEST(levels[2].sliding <= coarse);
  BOOST_TEST(levels[3].sliding <= coarse);
}

BOOST_AUTO_TEST_SUITE_END()
