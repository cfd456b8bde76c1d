// A stack of blocks on a fixed base stays at rest.
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

BOOST_AUTO_TEST_SUITE_END()
