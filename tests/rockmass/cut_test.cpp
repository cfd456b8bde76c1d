// Tests of rockmass/: portable random numbers, joint generation and the exact cutter.
// Each test names the behaviour it proves; areas are compared with closed forms.
#define BOOST_TEST_MODULE rheodda rockmass
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "rheodda/rockmass/cut.hpp"
#include "rheodda/rockmass/generate.hpp"
#include "rheodda/rockmass/random.hpp"
#include "rheodda/scene/geometry.hpp"

using namespace rheodda::rockmass;

namespace {

// Traces and checksum of the_same_seed_gives_the_same_traces_bit_for_bit (see there).
constexpr std::size_t kExpectedTraces = 153;
constexpr std::uint64_t kExpectedChecksum = 0x44889e45511cff21ull;

Region rectangle(double w, double h) { return {{{0, 0}, {w, 0}, {w, h}, {0, h}}, {}}; }

/// Area of the blocks' union equals the region's and no two blocks overlap (scene's own overlap test).
void check_tiling(const Region& region, const CutResult& r) {
  double sum = 0.0;
  std::vector<rheodda::scene::BlockDescription> blocks;
  for (const Block& b : r.blocks) {
    BOOST_TEST(b.area > 0.0);
    BOOST_TEST(b.polygon.size() == b.edge_tag.size());
    BOOST_TEST(std::abs(b.area - polygon_area(b.polygon)) <= 1e-15 * std::abs(b.area));
    for (int t : b.edge_tag) BOOST_TEST(t >= kBoundaryTag);
    sum += b.area;
    rheodda::scene::BlockDescription d;
    for (const Point& p : b.polygon) d.polygon.push_back({p[0], p[1]});
    blocks.push_back(std::move(d));
  }
  double area = std::abs(polygon_area(region.outer));
  for (const auto& h : region.holes) area -= std::abs(polygon_area(h));
  BOOST_TEST(std::abs(sum - area) <= 1e-12 * area);
  BOOST_TEST(r.area_error <= 1e-12);
  const double tol = 1e-9 * 2.0 * rheodda::scene::half_model_size(blocks);
  BOOST_TEST(rheodda::scene::overlapping_blocks(blocks, tol).empty());
}

/// Number of edges of `b` carrying tag t.
int edges_with(const Block& b, int t) { return static_cast<int>(std::count(b.edge_tag.begin(), b.edge_tag.end(), t)); }

std::uint64_t fnv1a(const std::vector<Trace>& traces) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    for (int k = 0; k < 8; ++k) {
      h ^= (bits >> (8 * k)) & 0xFF;
      h *= 1099511628211ull;
    }
  };
  for (const Trace& t : traces) mix(t.a[0]), mix(t.a[1]), mix(t.b[0]), mix(t.b[1]);
  return h;
}

}  // namespace

BOOST_AUTO_TEST_CASE(portable_functions_agree_with_the_c_library_to_a_few_ulp) {
  for (double x = 1e-300; x < 1e300; x *= 3.7) {
    const double e = std::log(x);
    BOOST_TEST(std::abs(portable_log(x) - e) <= 4e-16 * std::max(1.0, std::abs(e)));
  }
  for (double x = -700.0; x < 700.0; x += 0.37)
    BOOST_TEST(std::abs(portable_exp(x) - std::exp(x)) <= 4e-16 * std::exp(x) * std::max(1.0, std::abs(x)));
  for (double x = -7.0; x < 7.0; x += 0.013) {
    BOOST_TEST(std::abs(portable_sin(x) - std::sin(x)) <= 1e-15);
    BOOST_TEST(std::abs(portable_cos(x) - std::cos(x)) <= 1e-15);
  }
}

BOOST_AUTO_TEST_CASE(spacing_distributions_have_the_requested_mean_and_deviation) {
  // 2e4 lines of each distribution over a tall box; sample mean within 3 standard errors.
  const Box box{0, 0, 1, 2e4};
  for (auto dist : {SpacingDistribution::constant, SpacingDistribution::normal, SpacingDistribution::exponential,
                    SpacingDistribution::log_normal}) {
    JointSetGeneration s;
    s.dip = 0.0;
    s.spacing = 1.0;
    s.spacing_deviation = 0.3;
    s.spacing_distribution = dist;
    const auto traces = generate_traces(s, box, 7, 0);
    std::vector<double> y;
    for (const Trace& t : traces) y.push_back(t.a[1]);
    std::sort(y.begin(), y.end());
    double m = 0.0, m2 = 0.0;
    for (std::size_t i = 1; i < y.size(); ++i) m += y[i] - y[i - 1];
    m /= double(y.size() - 1);
    for (std::size_t i = 1; i < y.size(); ++i) m2 += (y[i] - y[i - 1] - m) * (y[i] - y[i - 1] - m);
    const double sd = std::sqrt(m2 / double(y.size() - 2));
    const double expected_sd = dist == SpacingDistribution::constant ? 0.0
                               : dist == SpacingDistribution::exponential ? 1.0 : 0.3;
    BOOST_TEST_INFO("distribution " << spacing_distribution_name(dist) << ": mean " << m << ", sd " << sd);
    BOOST_TEST(std::abs(m - 1.0) <= 3.0 * std::max(expected_sd, 1e-3) / std::sqrt(double(y.size())) + 1e-12);
    BOOST_TEST(std::abs(sd - expected_sd) <= 0.05 * std::max(expected_sd, 1e-3) + 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(persistence_is_trace_length_over_trace_length_plus_gap) {
  JointSetGeneration s;
  s.dip = 30.0;
  s.spacing = 0.5;
  s.trace_length = 3.0;
  s.gap = 1.0;
  const Box box{0, 0, 400, 400};
  double len = 0.0;
  for (const Trace& t : generate_traces(s, box, 3, 0)) len += std::hypot(t.b[0] - t.a[0], t.b[1] - t.a[1]);
  // Lines cover the box at density 1/spacing: total line length = box area / spacing.
  const double persistence = len / (400.0 * 400.0 / 0.5);
  BOOST_TEST(std::abs(persistence - 0.75) <= 0.01);
}

BOOST_AUTO_TEST_CASE(two_orthogonal_persistent_sets_on_a_rectangle_give_the_exact_blocks) {
  // 10 x 6 rectangle, horizontal joints every 2 (y = 0 and 6 lie on the boundary),
  // vertical joints every 2.5 (x = 0 and 10 on the boundary): 4 x 3 blocks of 2.5 x 2.
  JointSetGeneration h, v;
  h.tag = 0, h.dip = 0.0, h.spacing = 2.0, h.origin = Point{0, 0};
  v.tag = 1, v.dip = 90.0, v.spacing = 2.5, v.origin = Point{0, 0};
  const Region region = rectangle(10, 6);
  const Box box{0, 0, 10, 6};
  auto traces = generate_traces(h, box, 1, 0);
  const auto tv = generate_traces(v, box, 1, 1);
  traces.insert(traces.end(), tv.begin(), tv.end());
  const CutResult r = cut_blocks(region, traces);
  BOOST_TEST(r.blocks.size() == 12u);
  for (const Block& b : r.blocks) {
    BOOST_TEST(b.area == 5.0);
    BOOST_TEST(b.polygon.size() == 4u);
    BOOST_TEST(edges_with(b, 0) + edges_with(b, 1) + edges_with(b, kBoundaryTag) == 4);
  }
  // Corner blocks have 2 boundary edges, the others 1 (row middle) or 2, the middle two none.
  int boundary_edges = 0;
  for (const Block& b : r.blocks) boundary_edges += edges_with(b, kBoundaryTag);
  BOOST_TEST(boundary_edges == 2 * 4 + 2 * 3);
  BOOST_TEST(r.joint_length.at(0) == 2 * 10.0);  // y = 2, 4
  BOOST_TEST(r.joint_length.at(1) == 3 * 6.0);   // x = 2.5, 5, 7.5
  BOOST_TEST(r.joint_length.at(kBoundaryTag) == 32.0);
  // Ordered by the lowest, then leftmost, vertex.
  const auto& first = r.blocks[0].polygon;
  BOOST_TEST((std::find(first.begin(), first.end(), Point{0.0, 0.0}) != first.end()));
  const auto& last = r.blocks.back().polygon;
  BOOST_TEST((std::find(last.begin(), last.end(), Point{10.0, 6.0}) != last.end()));
  check_tiling(region, r);
}

BOOST_AUTO_TEST_CASE(a_trace_through_a_vertex_cuts_the_square_into_two_triangles) {
  const Region sq = rectangle(1, 1);
  const CutResult r = cut_blocks(sq, {{{-1, -1}, {2, 2}, 0}});
  BOOST_TEST(r.blocks.size() == 2u);
  for (const Block& b : r.blocks) {
    BOOST_TEST(b.area == 0.5);
    BOOST_TEST(b.polygon.size() == 3u);
    BOOST_TEST(edges_with(b, 0) == 1);
  }
  check_tiling(sq, r);
}

BOOST_AUTO_TEST_CASE(coincident_traces_cut_once_and_the_edge_takes_the_smaller_tag) {
  const Region sq = rectangle(1, 1);
  const CutResult r = cut_blocks(sq, {{{0.5, -1}, {0.5, 2}, 3}, {{0.5, 0}, {0.5, 1}, 1}, {{0.5, 0.2}, {0.5, 0.7}, 2}});
  BOOST_TEST(r.blocks.size() == 2u);
  for (const Block& b : r.blocks) {
    BOOST_TEST(b.area == 0.5);
    BOOST_TEST(edges_with(b, 1) == 1);  // one edge from (0.5,0) to (0.5,1): the vertices of the shorter trace dropped
    BOOST_TEST(b.polygon.size() == 4u);
  }
  check_tiling(sq, r);
}

BOOST_AUTO_TEST_CASE(a_trace_along_the_boundary_leaves_one_block_with_a_boundary_edge) {
  const Region sq = rectangle(1, 1);
  const CutResult r = cut_blocks(sq, {{{-1, 0}, {2, 0}, 0}, {{0.2, 1}, {0.7, 1}, 0}});
  BOOST_TEST(r.blocks.size() == 1u);
  BOOST_TEST(r.blocks[0].area == 1.0);
  BOOST_TEST(r.blocks[0].polygon.size() == 4u);
  BOOST_TEST(edges_with(r.blocks[0], kBoundaryTag) == 4);
  check_tiling(sq, r);
}

BOOST_AUTO_TEST_CASE(a_trace_ending_exactly_on_another_makes_a_t_junction) {
  // x = 0.5 across; y = 0.5 from the left side to exactly x = 0.5: blocks 0.5, 0.25, 0.25.
  const Region sq = rectangle(1, 1);
  const CutResult r = cut_blocks(sq, {{{0.5, 0}, {0.5, 1}, 0}, {{0, 0.5}, {0.5, 0.5}, 1}});
  BOOST_TEST(r.blocks.size() == 3u);
  std::vector<double> areas;
  for (const Block& b : r.blocks) areas.push_back(b.area);
  std::sort(areas.begin(), areas.end());
  BOOST_TEST(areas == (std::vector<double>{0.25, 0.25, 0.5}), boost::test_tools::per_element());
  // The right block keeps the T vertex (0.5, 0.5): 5 vertices, two edges of set 0.
  const auto right = std::find_if(r.blocks.begin(), r.blocks.end(), [](const Block& b) { return b.area == 0.5; });
  BOOST_TEST(right->polygon.size() == 5u);
  BOOST_TEST(edges_with(*right, 0) == 2);
  check_tiling(sq, r);
}

BOOST_AUTO_TEST_CASE(dead_end_traces_are_removed_as_in_dc) {
  // One trace ends inside the square, one crosses it: 2 blocks, the dead end is gone.
  const Region sq = rectangle(1, 1);
  const CutResult r = cut_blocks(sq, {{{0.5, -1}, {0.5, 2}, 0}, {{0, 0.3}, {0.3, 0.3}, 1}, {{0.6, 0.6}, {0.8, 0.9}, 1}});
  BOOST_TEST(r.blocks.size() == 2u);
  BOOST_TEST(r.dangling_removed >= 2);
  for (const Block& b : r.blocks) {
    BOOST_TEST(b.area == 0.5);
    BOOST_TEST(b.polygon.size() == 4u);  // the vertex where the dead end met the boundary is dropped
    BOOST_TEST(edges_with(b, 1) == 0);
  }
  BOOST_TEST(r.joint_length.count(1) == 0u);
  check_tiling(sq, r);
}

BOOST_AUTO_TEST_CASE(concave_blocks_are_kept) {
  // An L-shaped region cut by one vertical trace: an L (concave) and a rectangle.
  const Region l{{{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}, {}};
  const CutResult r = cut_blocks(l, {{{2, -1}, {2, 5}, 0}});
  BOOST_TEST(r.blocks.size() == 2u);
  std::vector<double> areas{r.blocks[0].area, r.blocks[1].area};
  std::sort(areas.begin(), areas.end());
  BOOST_TEST(areas[0] == 1.0);
  BOOST_TEST(areas[1] == 4.0);
  check_tiling(l, r);
}

BOOST_AUTO_TEST_CASE(a_hole_cut_by_a_joint_leaves_two_blocks_with_the_hole_on_their_boundary) {
  Region r{{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{1, 1}, {3, 1}, {3, 3}, {1, 3}}}};
  const CutResult c = cut_blocks(r, {{{-1, 2}, {5, 2}, 0}});
  BOOST_TEST(c.blocks.size() == 2u);
  for (const Block& b : c.blocks) BOOST_TEST(b.area == 6.0);
  BOOST_TEST(c.region_area == 12.0);
  check_tiling(r, c);
}

BOOST_AUTO_TEST_CASE(a_hole_in_a_block_without_joints_is_a_clear_error) {
  // The block around the hole is bounded by the region's boundary only: nothing to extend.
  Region r{{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{{1, 1}, {3, 1}, {3, 3}, {1, 3}}}};
  try {
    cut_blocks(r, {});
    BOOST_FAIL("no error");
  } catch (const CutError& e) {
    BOOST_TEST(std::string(e.what()).find("simple polygons") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(a_block_enclosed_by_joints_is_separated_by_extending_a_trace) {
  // Four traces close a 2 x 2 square inside a 10 x 10 region that no other joint cuts:
  // the outer block would have a hole. One trace is extended up to the top (a bridge),
  // then one to the right side: blocks 4, 24 (x 4..10, y 6..10) and 72.
  const Region sq = rectangle(10, 10);
  const CutResult r = cut_blocks(sq, {{{4, 4}, {6, 4}, 0}, {{6, 4}, {6, 6}, 1}, {{6, 6}, {4, 6}, 0}, {{4, 6}, {4, 4}, 1}});
  BOOST_TEST(r.extended_traces == 2);
  std::vector<double> areas;
  for (const Block& b : r.blocks) areas.push_back(b.area);
  std::sort(areas.begin(), areas.end());
  BOOST_TEST(areas == (std::vector<double>{4, 24, 72}), boost::test_tools::per_element());
  check_tiling(sq, r);
  for (const Block& b : r.blocks) BOOST_TEST(!rheodda::scene::polygon_defect(b.polygon, 1e-8).has_value());
}

BOOST_AUTO_TEST_CASE(near_parallel_traces_are_cut_exactly) {
  // Two traces at 2e-6 to each other across a 1 x 1 square cross at x = 0.5 (exactly,
  // in the arrangement): two wedges of 2e-6 x 0.5 / 2 = 5e-7 and two of 0.5 - 5e-7.
  const Region sq = rectangle(1, 1);
  const double e = 1e-6;
  const CutResult r = cut_blocks(sq, {{{0, 0.5 - e}, {1, 0.5 + e}, 0}, {{0, 0.5 + e}, {1, 0.5 - e}, 1}});
  BOOST_TEST(r.blocks.size() == 4u);
  std::vector<double> areas;
  for (const Block& b : r.blocks) areas.push_back(b.area);
  std::sort(areas.begin(), areas.end());
  BOOST_TEST(std::abs(areas[0] - 5e-7) <= 1e-15);
  BOOST_TEST(std::abs(areas[1] - 5e-7) <= 1e-15);
  BOOST_TEST(std::abs(areas[2] - (0.5 - 5e-7)) <= 1e-15);
  BOOST_TEST(std::abs(areas[3] - (0.5 - 5e-7)) <= 1e-15);
  check_tiling(sq, r);
  // At 1e-13 the wedges are 2e-13 thick at the sides, below the weld distance (1e-9 of the
  // region): their vertices weld, they collapse and are reported; the area still sums.
  const double f = 1e-13;
  const CutResult thin = cut_blocks(sq, {{{0, 0.5 - f}, {1, 0.5 + f}, 0}, {{0, 0.5 + f}, {1, 0.5 - f}, 1}});
  BOOST_TEST(thin.blocks.size() == 2u);
  BOOST_TEST(thin.collapsed_blocks == 2);
  check_tiling(sq, thin);
}

BOOST_AUTO_TEST_CASE(a_hole_inside_a_block_is_reached_by_a_joint_parallel_to_the_blocks_joints) {
  // A 2 x 2 hole in the middle of a 10 x 6 rectangle cut only at x = 1: the right block
  // would enclose it; no trace ends where its continuation meets it, so a joint parallel
  // to x = 1 is added from a corner of the hole (x = 4 or 6) and a second one closes the bridge.
  Region r{{{0, 0}, {10, 0}, {10, 6}, {0, 6}}, {{{4, 2}, {6, 2}, {6, 4}, {4, 4}}}};
  const CutResult c = cut_blocks(r, {{{1, -1}, {1, 7}, 0}});
  BOOST_TEST(c.added_traces >= 1);
  BOOST_TEST(c.extended_traces >= 2);
  BOOST_TEST(c.blocks.size() == 3u);
  check_tiling(r, c);
  for (const Block& b : c.blocks) {
    BOOST_TEST(!rheodda::scene::polygon_defect(b.polygon, 1e-8).has_value());
    for (std::size_t k = 0; k < b.polygon.size(); ++k)  // every joint edge is vertical, as x = 1
      if (b.edge_tag[k] == 0) BOOST_TEST(b.polygon[k][0] == b.polygon[(k + 1) % b.polygon.size()][0]);
  }
}

BOOST_AUTO_TEST_CASE(slivers_below_the_threshold_are_merged_into_their_neighbour) {
  // A trace 1e-3 above the bottom makes a 1e-3 sliver; with sliver_area 0.01 it joins the block above.
  const Region sq = rectangle(1, 1);
  const std::vector<Trace> t{{{-1, 0.001}, {2, 0.001}, 0}, {{0.5, -1}, {0.5, 2}, 1}};
  BOOST_TEST(cut_blocks(sq, t).blocks.size() == 4u);
  const CutResult r = cut_blocks(sq, t, {0.01});
  BOOST_TEST(r.merged_slivers == 2);
  BOOST_TEST(r.blocks.size() == 2u);
  for (const Block& b : r.blocks) BOOST_TEST(std::abs(b.area - 0.5) <= 1e-15);
  check_tiling(sq, r);
}

BOOST_AUTO_TEST_CASE(the_same_seed_gives_the_same_traces_bit_for_bit) {
  // The checksum was computed by this test on x86-64 (glibc); the generator uses
  // std::mt19937_64 and IEEE + - * / only, so every conforming machine gives it.
  JointSetGeneration s;
  s.dip = 35.0;
  s.spacing = 1.5;
  s.spacing_distribution = SpacingDistribution::log_normal;
  s.spacing_deviation = 0.5;
  s.trace_length = 6.0;
  s.gap = 2.0;
  s.dip_spread = 5.0;
  const Box box{0, 0, 50, 30};
  const auto a = generate_traces(s, box, 2026, 1);
  const auto b = generate_traces(s, box, 2026, 1);
  BOOST_TEST(fnv1a(a) == fnv1a(b));
  BOOST_TEST(fnv1a(a) != fnv1a(generate_traces(s, box, 2027, 1)));
  BOOST_TEST_MESSAGE("checksum " << std::hex << fnv1a(a) << std::dec << " of " << a.size() << " traces");
  BOOST_TEST(a.size() == kExpectedTraces);
  BOOST_TEST(fnv1a(a) == kExpectedChecksum);
}

BOOST_AUTO_TEST_CASE(the_area_check_holds_a_million_blocks_and_still_sees_one_missing) {
  // issue 43: the blocks' areas were summed in plain floating point against a relative
  // 1e-12, whose rounding grows with the count: a valid cut of 1e6 blocks was refused
  // ("the region's boundary crosses itself"), and at map coordinates each area about the
  // origin lost its digits. 1000 x 1000 cells of an irregular grid at x ~ 5e5, y ~ 4e6 m
  // (every vertex shared by its four cells, as the cutter's blocks share theirs) tile the
  // square exactly; block_area_check accepts them and refuses them without one cell.
  const int n = 1000;
  const double x0 = 500123.456789, y0 = 4000987.654321, size = 97.5310864;  // [m]: map coordinates
  // Vertex (i, j) of the grid, moved within its cell; the square's sides stay straight.
  auto vertex = [&](int i, int j) {
    const double di = i == 0 || i == n ? 0.0 : 0.3 * std::sin(1.7 * i + 2.3 * j);
    const double dj = j == 0 || j == n ? 0.0 : 0.3 * std::cos(2.9 * i - 1.1 * j);
    return Point{x0 + size * (i + di) / n, y0 + size * (j + dj) / n};
  };
  const Region region{{vertex(0, 0), vertex(n, 0), vertex(n, n), vertex(0, n)}, {}};
  std::vector<Block> blocks;
  blocks.reserve(std::size_t(n) * n);
  double plain = 0.0;  // the old check: areas about the origin, summed in order
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Block b;
      b.polygon = {vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)};
      b.edge_tag = {0, 0, 0, 0};
      double about_origin = 0.0;
      for (std::size_t k = 0; k < 4; ++k) {
        const Point& p = b.polygon[k];
        const Point& q = b.polygon[(k + 1) % 4];
        about_origin += p[0] * q[1] - q[0] * p[1];
      }
      plain += 0.5 * about_origin;
      blocks.push_back(std::move(b));
    }
  const double area = (region.outer[1][0] - region.outer[0][0]) * (region.outer[2][1] - region.outer[1][1]);
  BOOST_TEST(std::abs(plain - area) / area > 1e-12);  // what the old check refused
  const AreaCheck ok = block_area_check(blocks, region);
  BOOST_TEST(ok.ok(), ok.block_sum << " against " << ok.region_area << ", bound " << ok.bound);
  BOOST_TEST(ok.bound < 1e-9 * area);  // and the bound stays a small part of a cell (1e-6 of the area)
  blocks.erase(blocks.begin() + 500500);
  BOOST_TEST(!block_area_check(blocks, region).ok());
}
