// Polygon checks behind the loader: area, simplicity, containment, overlap, contact estimate.
#include <boost/test/unit_test.hpp>

#include "rheodda/scene/geometry.hpp"

using namespace rheodda::scene;

namespace {
BlockDescription block(std::vector<Point> p) {
  BlockDescription b;
  b.polygon = std::move(p);
  b.edge_joint_set.assign(b.polygon.size(), 0);
  return b;
}
const std::vector<Point> kUnit{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
// L-shape (concave), counter-clockwise, area 3.
const std::vector<Point> kL{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
}  // namespace

BOOST_AUTO_TEST_SUITE(scene_geometry)

BOOST_AUTO_TEST_CASE(signed_area_is_positive_counter_clockwise_and_exact_for_concave) {
  BOOST_TEST(signed_area(kUnit) == 1.0);
  BOOST_TEST(signed_area(kL) == 3.0);
  BOOST_TEST(signed_area({{0, 0}, {0, 1}, {1, 1}, {1, 0}}) == -1.0);
}

BOOST_AUTO_TEST_CASE(simple_polygons_pass_defects_are_named) {
  BOOST_TEST(!polygon_defect(kUnit, 1e-12).has_value());
  BOOST_TEST(!polygon_defect(kL, 1e-12).has_value());
  BOOST_TEST(polygon_defect({{0, 0}, {2, 2}, {2, 0}, {0, 1}}, 1e-12)->find("not simple") != std::string::npos);
  BOOST_TEST(polygon_defect({{0, 0}, {1, 0}, {2, 0}}, 1e-12)->find("degenerate") != std::string::npos);
  // A spike folding back along an edge.
  BOOST_TEST(polygon_defect({{0, 0}, {2, 0}, {1, 0}, {1, 1}}, 1e-12).has_value());
  // Two non-adjacent edges touching at a point (pinched polygon).
  BOOST_TEST(polygon_defect({{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1.0}}, 1e-12).has_value());
}

BOOST_AUTO_TEST_CASE(containment_includes_the_boundary_within_tolerance) {
  BOOST_TEST(contains(kL, {0.5, 1.5}, 0.0));
  BOOST_TEST(!contains(kL, {1.5, 1.5}, 1e-9));  // in the notch of the L
  BOOST_TEST(contains(kL, {1.5, 1.0}, 1e-9));   // on the notch's edge
  BOOST_TEST(boundary_distance(kUnit, {0.5, 0.5}) == 0.5);
  const Point p = interior_point(kL);
  BOOST_TEST(contains(kL, p, 0.0));
  BOOST_TEST(boundary_distance(kL, p) > 0.0);
}

BOOST_AUTO_TEST_CASE(touching_blocks_do_not_overlap_intersecting_ones_do) {
  const std::vector<Point> right{{1, 0}, {2, 0}, {2, 1}, {1, 1}};      // shares an edge
  const std::vector<Point> corner{{1, 1}, {2, 1}, {2, 2}, {1, 2}};     // shares a vertex
  const std::vector<Point> shifted{{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  const std::vector<Point> inside{{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  const std::vector<Point> cross{{0.4, -1}, {0.6, -1}, {0.6, 2}, {0.4, 2}};  // no vertex inside the unit square
  BOOST_TEST(!interiors_overlap(kUnit, right, 1e-9));
  BOOST_TEST(!interiors_overlap(kUnit, corner, 1e-9));
  BOOST_TEST(interiors_overlap(kUnit, shifted, 1e-9));
  BOOST_TEST(interiors_overlap(kUnit, inside, 1e-9));
  BOOST_TEST(interiors_overlap(inside, kUnit, 1e-9));
  BOOST_TEST(interiors_overlap(kUnit, cross, 1e-9));
  BOOST_TEST(interiors_overlap(kUnit, kUnit, 1e-9));
  // The L's notch holds a unit square without overlap.
  BOOST_TEST(!interiors_overlap(kL, {{1, 1}, {2, 1}, {2, 2}, {1, 2}}, 1e-9));
}

BOOST_AUTO_TEST_CASE(overlap_search_finds_exactly_the_overlapping_pairs_of_a_grid) {
  std::vector<BlockDescription> blocks;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      blocks.push_back(block({{double(i), double(j)}, {i + 1.0, double(j)}, {i + 1.0, j + 1.0}, {double(i), j + 1.0}}));
  BOOST_TEST(overlapping_blocks(blocks, 1e-9).empty());
  blocks.push_back(block({{3.5, 3.5}, {4.5, 3.5}, {4.5, 4.5}, {3.5, 4.5}}));  // covers 4 cells
  const auto pairs = overlapping_blocks(blocks, 1e-9);
  BOOST_TEST(pairs.size() == 4u);
  for (const auto& [i, j] : pairs) BOOST_TEST(j == 400);
}

BOOST_AUTO_TEST_CASE(contact_estimate_counts_two_points_per_face_to_face_contact) {
  // A block on a wider base: 2 contacts (the ends of the shared segment), one pair.
  std::vector<BlockDescription> blocks{block({{0, 0}, {4, 0}, {4, 1}, {0, 1}}), block({{1, 1}, {2, 1}, {2, 2}, {1, 2}})};
  ContactEstimate e = estimate_contacts(blocks, 0.01);
  BOOST_TEST(e.block_pairs == 1);
  BOOST_TEST(e.vertex_edge == 2);
  // Two equal blocks stacked exactly: vertex-vertex pairs count once each.
  blocks[0] = block({{1, 0}, {2, 0}, {2, 1}, {1, 1}});
  e = estimate_contacts(blocks, 0.01);
  BOOST_TEST(e.vertex_edge == 2);
  // Far apart: none.
  blocks[1] = block({{10, 10}, {11, 10}, {11, 11}, {10, 11}});
  BOOST_TEST(estimate_contacts(blocks, 0.01).block_pairs == 0);
  BOOST_TEST(half_model_size(blocks) == 5.5);
}

BOOST_AUTO_TEST_SUITE_END()
