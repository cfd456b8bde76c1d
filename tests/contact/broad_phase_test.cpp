// The grid broad phase finds exactly the block pairs an all-pairs check finds.
#include <boost/test/unit_test.hpp>
#include <random>

#include "rheodda/contact/broad_phase.hpp"

using namespace rheodda::contact;

BOOST_AUTO_TEST_SUITE(broad_phase)

BOOST_AUTO_TEST_CASE(grid_finds_exactly_the_brute_force_pairs_on_a_random_scene) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> pos(0.0, 50.0), size(0.05, 1.5);
  std::vector<Box> boxes;
  for (int i = 0; i < 3000; ++i) {
    const Vec2 lo(pos(rng), pos(rng));
    boxes.push_back({lo, lo + Vec2(size(rng), size(rng))});
  }
  // A few large blocks (a base, a wall) that cover many cells.
  boxes.push_back({{-1.0, -2.0}, {51.0, 0.5}});
  boxes.push_back({{20.0, 0.0}, {21.0, 51.0}});
  boxes.push_back({{-5.0, -5.0}, {60.0, 60.0}});
  BroadPhase bp;
  const auto grid = bp.find_pairs(boxes);
  const auto brute = brute_force_pairs(boxes);
  BOOST_TEST(brute.size() > 3000u);
  BOOST_TEST(grid.size() == brute.size());
  BOOST_TEST((grid == brute));
}

BOOST_AUTO_TEST_CASE(boxes_touching_at_a_side_are_a_pair_and_boxes_apart_are_not) {
  std::vector<Box> boxes{{{0, 0}, {1, 1}}, {{1, 0}, {2, 1}}, {{2.5, 0}, {3, 1}}};
  BroadPhase bp;
  const auto pairs = bp.find_pairs(boxes);
  BOOST_TEST_REQUIRE(pairs.size() == 1u);
  BOOST_TEST(pairs[0].first == 0);
  BOOST_TEST(pairs[0].second == 1);
}

BOOST_AUTO_TEST_SUITE_END()
