// Polygon integrals against hand values: rectangles, triangles, an L-shape
// (concave), far from the origin, and the orientation normalisation that
// keeps each edge's joint set on the same physical edge.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"
#include "rheodda/core/polygon.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

// Hand values for the rectangle [x1, x2] x [y1, y2].
PolygonIntegrals rectangle_by_hand(double x1, double x2, double y1, double y2) {
  PolygonIntegrals r;
  r.S = (x2 - x1) * (y2 - y1);
  r.Sx = (x2 * x2 - x1 * x1) / 2.0 * (y2 - y1);
  r.Sy = (y2 * y2 - y1 * y1) / 2.0 * (x2 - x1);
  r.Sxx = (x2 * x2 * x2 - x1 * x1 * x1) / 3.0 * (y2 - y1);
  r.Syy = (y2 * y2 * y2 - y1 * y1 * y1) / 3.0 * (x2 - x1);
  r.Sxy = (x2 * x2 - x1 * x1) / 2.0 * (y2 * y2 - y1 * y1) / 2.0;
  return r;
}

void check_close(const PolygonIntegrals& got, const PolygonIntegrals& want, double rel) {
  const double scale = std::abs(want.Sxx) + std::abs(want.Syy) + std::abs(want.S);
  BOOST_TEST(std::abs(got.S - want.S) <= rel * (std::abs(want.S) + 1e-300));
  BOOST_TEST(std::abs(got.Sx - want.Sx) <= rel * scale);
  BOOST_TEST(std::abs(got.Sy - want.Sy) <= rel * scale);
  BOOST_TEST(std::abs(got.Sxx - want.Sxx) <= rel * scale);
  BOOST_TEST(std::abs(got.Syy - want.Syy) <= rel * scale);
  BOOST_TEST(std::abs(got.Sxy - want.Sxy) <= rel * scale);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(polygon)

BOOST_AUTO_TEST_CASE(rectangle_integrals_match_hand_values) {
  const std::vector<Vec2> v{{1.0, -2.0}, {4.0, -2.0}, {4.0, 0.5}, {1.0, 0.5}};
  check_close(polygon_integrals(v), rectangle_by_hand(1.0, 4.0, -2.0, 0.5), 1e-14);
}

BOOST_AUTO_TEST_CASE(right_triangle_integrals_match_hand_values) {
  // Triangle (0,0), (a,0), (0,b): S = ab/2, Sx = a^2 b/6, Sy = a b^2/6,
  // Sxx = a^3 b/12, Syy = a b^3/12, Sxy = a^2 b^2/24.
  const double a = 3.0, b = 2.0;
  const std::vector<Vec2> v{{0.0, 0.0}, {a, 0.0}, {0.0, b}};
  PolygonIntegrals want;
  want.S = a * b / 2.0;
  want.Sx = a * a * b / 6.0;
  want.Sy = a * b * b / 6.0;
  want.Sxx = a * a * a * b / 12.0;
  want.Syy = a * b * b * b / 12.0;
  want.Sxy = a * a * b * b / 24.0;
  check_close(polygon_integrals(v), want, 1e-14);
}

BOOST_AUTO_TEST_CASE(concave_l_shape_equals_sum_of_its_rectangles) {
  // L = [0,2]x[0,1] united with [0,1]x[1,3].
  const std::vector<Vec2> v{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const auto a = rectangle_by_hand(0, 2, 0, 1), b = rectangle_by_hand(0, 1, 1, 3);
  PolygonIntegrals want;
  want.S = a.S + b.S;
  want.Sx = a.Sx + b.Sx;
  want.Sy = a.Sy + b.Sy;
  want.Sxx = a.Sxx + b.Sxx;
  want.Syy = a.Syy + b.Syy;
  want.Sxy = a.Sxy + b.Sxy;
  check_close(polygon_integrals(v), want, 1e-14);
  BOOST_TEST(is_simple_polygon(v));
}

BOOST_AUTO_TEST_CASE(central_moments_stay_accurate_far_from_the_origin) {
  // Rectangle 3 x 2 centred at (1e6, -2e6): central Sxx = b a^3/12, Syy = a b^3/12, Sxy = 0.
  const double a = 3.0, b = 2.0, cx = 1e6, cy = -2e6;
  const std::vector<Vec2> v{{cx - a / 2, cy - b / 2}, {cx + a / 2, cy - b / 2},
                            {cx + a / 2, cy + b / 2}, {cx - a / 2, cy + b / 2}};
  Vec2 c;
  const auto m = central_integrals(v, &c);
  BOOST_TEST(std::abs(m.S - a * b) <= 1e-9 * a * b);
  BOOST_TEST(std::abs(m.Sxx - b * a * a * a / 12.0) <= 1e-9 * b * a * a * a / 12.0);
  BOOST_TEST(std::abs(m.Syy - a * b * b * b / 12.0) <= 1e-9 * a * b * b * b / 12.0);
  BOOST_TEST(std::abs(m.Sxy) <= 1e-9);
  BOOST_TEST((c - Vec2(cx, cy)).norm() <= 1e-9);
}

BOOST_AUTO_TEST_CASE(clockwise_input_is_reversed_and_joint_sets_follow_their_edges) {
  // Clockwise L-shape; edge k (vertex k -> k+1) labelled 10 + k.
  std::vector<Vec2> v{{0, 3}, {1, 3}, {1, 1}, {2, 1}, {2, 0}, {0, 0}};
  const std::vector<Vec2> given = v;
  std::vector<int> js{10, 11, 12, 13, 14, 15};
  BOOST_TEST(polygon_integrals(v).S < 0.0);
  BOOST_TEST(normalise_orientation(v, js));
  BOOST_TEST(polygon_integrals(v).S == 4.0, boost::test_tools::tolerance(1e-14));
  const std::size_t n = v.size();
  for (std::size_t j = 0; j < n; ++j) {
    // The new edge j must be the given edge labelled js[j], traversed either way.
    const std::size_t k = static_cast<std::size_t>(js[j] - 10);
    const Vec2 &a = given[k], &b = given[(k + 1) % n];
    const Vec2 &p = v[j], &q = v[(j + 1) % n];
    BOOST_TEST(((p == a && q == b) || (p == b && q == a)));
  }
  // A counter-clockwise polygon is left alone.
  std::vector<int> js2 = js;
  std::vector<Vec2> v2 = v;
  BOOST_TEST(!normalise_orientation(v2, js2));
  BOOST_TEST((js2 == js));
}

BOOST_AUTO_TEST_CASE(engine_normalises_clockwise_blocks_keeping_joint_sets) {
  Model m;
  m.settings.gravity = Vec2::Zero();
  m.blocks.push_back(block({{0, 0}, {0, 1}, {2, 1}, {2, 0}}, {1, 2, 3, 4}));
  Engine e(m);
  BOOST_TEST(e.area(0) == 2.0, boost::test_tools::tolerance(1e-14));
  // Given edge 0 = (0,0)-(0,1) had joint set 1; it is now the edge (0,1)->(0,0).
  const auto vs = e.vertices(0);
  const auto& js = e.block(0).edge_joint_set;
  for (std::size_t j = 0; j < vs.size(); ++j)
    if (vs[j] == Vec2(0, 1)) BOOST_TEST(js[j] == 1);
}

BOOST_AUTO_TEST_CASE(self_intersecting_polygons_are_not_simple) {
  BOOST_TEST(!is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 1}, {1, 0}, {0, 1}}));  // bow-tie
  BOOST_TEST(!is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 0}, {0, 1}}));  // repeated vertex
  BOOST_TEST(is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
}

BOOST_AUTO_TEST_SUITE_END()
