// Contact identity survives sliding along a surface made of many edges.
#include <boost/test/unit_test.hpp>
#include <map>
#include <set>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

BOOST_AUTO_TEST_SUITE(transfer)

BOOST_AUTO_TEST_CASE(contact_identity_survives_100_steps_of_sliding_over_many_edges) {
  core::Model m;
  m.settings.dt = 1e-3;
  // Base whose top y = 0 is split into 60 collinear edges of 0.05 m.
  std::vector<Vec2> base{{0.0, -0.5}, {3.0, -0.5}};
  for (int k = 60; k >= 0; --k) base.emplace_back(0.05 * k, 0.0);
  add_fixed(m, base);
  m.blocks.push_back(block(rect(0.21, 0.0, 0.71, 0.25), Vec2(3.0, 0.0)));
  Sim sim(std::move(m), {joint(10.0)});
  std::map<int, std::uint64_t> id;       // bottom vertex of the block -> contact id
  std::map<int, std::set<int>> edges;    // bottom vertex -> base edges visited
  for (int s = 0; s < 100; ++s) {
    sim.engine.step();
    std::map<int, int> seen;
    for (const auto& c : sim.contacts.contacts()) {
      if (c.key.vblock != 1 || c.key.eblock != 0) continue;
      ++seen[c.key.vertex];
      if (s == 0) id[c.key.vertex] = c.id;
      BOOST_TEST(c.id == id[c.key.vertex]);
      BOOST_TEST((c.state != contact::ContactState::open));
      edges[c.key.vertex].insert(c.key.edge);
    }
    BOOST_TEST(seen[0] == 1);  // each bottom vertex: exactly one contact, every step
    BOOST_TEST(seen[1] == 1);
  }
  const double moved = sim.engine.centroid(1).x() - 0.46;
  BOOST_TEST_MESSAGE("moved " << moved << " m; edges visited " << edges[0].size() << ", "
                              << edges[1].size());
  BOOST_TEST(moved > 0.25);
  BOOST_TEST(edges[0].size() >= 5u);
  BOOST_TEST(edges[1].size() >= 5u);
}

BOOST_AUTO_TEST_SUITE_END()
