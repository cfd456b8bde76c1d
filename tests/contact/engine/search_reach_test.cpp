// The contact search of a large model reaches only as far as the motion needs
// (docs/reference/engine.md, "Contact search reach"): the answer is the one the full
// reach (search_factor x max_displacement_ratio x w0) gives, and a step that moves a block beyond
// the reach is redone with a wider search instead of missing a contact.
#include <boost/test/unit_test.hpp>

#include <algorithm>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

struct Outcome {
  Vec2 centroid = Vec2::Zero();   // of the dropped block at the end [m]
  double lowest_y = 1e300;        // lowest vertex of the dropped block over the run [m]
  int widenings = 0;              // steps redone with a wider search (the engine redoes
                                  // them also when min_search_distance covered the motion)
  double max_penetration = 0.0;   // [m]
};

// A 1 m square thrown down at 10 m/s from 1 m above a fixed base 200 m wide
// (w0 = 100 m: with max_displacement_ratio = 0.01 Shi's reach is 2.5 m, while the floor of the
// adaptive reach is 0.1 m of the 1 m blocks), steps of 0.02 s (0.2 m per step
// before the impact); a second block at rest on the base far away.
Outcome drop(double min_search_distance) {
  core::Model m;
  m.settings.dt = 0.02;
  m.settings.max_displacement_ratio = 0.01;
  add_fixed(m, rect(-100.0, -1.0, 100.0, 0.0));
  m.blocks.push_back(block(rect(0.0, 1.0, 1.0, 2.0), Vec2(0.0, -10.0)));
  m.blocks.push_back(block(rect(50.0, 0.0, 51.0, 1.0)));
  contact::ContactSettings cs = core::contact_settings_for(m);
  cs.min_search_distance = min_search_distance;
  contact::ContactSystem contacts({joint(30.0)}, cs);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(m, adapter);
  Outcome o;
  engine.add_observer([&](const core::Engine& e, const core::StepReport& r) {
    o.widenings += r.search_widenings;
    o.max_penetration = std::max(o.max_penetration, r.max_penetration);
    for (const auto& v : e.block(1).vertices) o.lowest_y = std::min(o.lowest_y, v.y());
  });
  while (engine.time() < 1.0 - 1e-9) engine.step();
  o.centroid = engine.block(1).centroid;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_block_thrown_faster_than_the_search_reaches_lands_as_with_shis_full_reach) {
  const Outcome adaptive = drop(0.0);
  const Outcome full = drop(2.5 * 0.01 * 100.0);  // search_factor x max_displacement_ratio x w0
  BOOST_TEST_MESSAGE("widenings " << adaptive.widenings << ", lowest vertex " << adaptive.lowest_y
                                  << " m, final centroid " << adaptive.centroid.transpose());
  // The first steps move the block 0.2 m, twice the floor: the search widened.
  BOOST_TEST(adaptive.widenings > 0);
  // It reached the base and did not pass through it (a missed contact would
  // let it fall on: 10 m/s for 1 s), and it moved as with the full reach.
  BOOST_TEST(adaptive.lowest_y < 1e-3);
  BOOST_TEST(adaptive.lowest_y > -0.01);
  BOOST_TEST((adaptive.centroid - full.centroid).norm() < 1e-9);
  BOOST_TEST(adaptive.max_penetration == full.max_penetration, boost::test_tools::tolerance(1e-6));
}
