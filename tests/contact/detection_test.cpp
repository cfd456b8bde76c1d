// Narrow phase: each contact type, the angle rule and edge-edge halving.
#include <boost/test/unit_test.hpp>
#include <numbers>

#include "rheodda/contact/detection.hpp"
#include "test_blocks.hpp"

using namespace rheodda::contact;
using rheodda::contact::testing::Scene;
using rheodda::contact::testing::rotated_square;

namespace {
constexpr double d0 = 1e-3;  // search distance [m]
std::vector<DetectedContact> detect(const Scene& s, std::span<const ContactKey> previous = {}) {
  std::vector<std::pair<int, int>> pairs;
  const int n = static_cast<int>(s.views().size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) pairs.emplace_back(i, j);
  return detect_contacts(s.views(), pairs, {d0, 3.0}, previous);
}
}  // namespace

BOOST_AUTO_TEST_SUITE(detection)

BOOST_AUTO_TEST_CASE(tilted_corner_above_an_edge_is_one_vertex_edge_contact) {
  Scene s;
  s.add_rect(0, 0, 2, 1);  // base; top edge is edge 2 ((2,1) -> (0,1))
  auto sq = rotated_square({0, 0}, 0.5, 20.0 * std::numbers::pi / 180.0);
  const Vec2 lowest = sq[0];
  for (Vec2& v : sq) v += Vec2(1.0, 1.0 + 0.3 * d0) - lowest;  // lowest vertex 0.3 d0 above (1, 1)
  s.add(sq);
  const auto c = detect(s);
  BOOST_TEST_REQUIRE(c.size() == 1u);
  BOOST_TEST((c[0].key == ContactKey{1, 0, 0, 2}));
  BOOST_TEST((c[0].kind == ContactKind::vertex_edge));
  BOOST_TEST(c[0].length == 0.0);
}

BOOST_AUTO_TEST_CASE(corner_beyond_search_distance_is_no_contact) {
  Scene s;
  s.add_rect(0, 0, 2, 1);
  auto sq = rotated_square({0, 0}, 0.5, 20.0 * std::numbers::pi / 180.0);
  const Vec2 lowest = sq[0];
  for (Vec2& v : sq) v += Vec2(1.0, 1.0 + 1.5 * d0) - lowest;
  s.add(sq);
  BOOST_TEST(detect(s).empty());
}

BOOST_AUTO_TEST_CASE(vertex_vertex_angle_rule_picks_the_edge_the_corner_faces) {
  // Lowest corner of a square tilted 20 deg right next to the top-right corner
  // (1, 1) of the base, slightly left of it: it enters the base's top edge,
  // not the base's right edge, and the base corner enters none of its edges.
  Scene s;
  s.add_rect(0, 0, 1, 1);  // edge 1: right side, edge 2: top
  auto sq = rotated_square({0, 0}, 0.5, 20.0 * std::numbers::pi / 180.0);
  const Vec2 lowest = sq[0];
  for (Vec2& v : sq) v += Vec2(1.0 - 0.3 * d0, 1.0 + 0.2 * d0) - lowest;
  s.add(sq);
  const auto c = detect(s);
  BOOST_TEST_REQUIRE(c.size() == 1u);
  BOOST_TEST((c[0].key == ContactKey{1, 0, 0, 2}));
  BOOST_TEST((c[0].kind == ContactKind::vertex_vertex));

  // Mirror: the corner slightly right of (1, 1), below the top: it enters the right side.
  Scene m;
  m.add_rect(0, 0, 1, 1);
  auto sq2 = rotated_square({0, 0}, 0.5, (90.0 + 20.0) * std::numbers::pi / 180.0);
  // vertex 3 is now the lowest-left... choose the vertex with the smallest x.
  int left = 0;
  for (int k = 1; k < 4; ++k) if (sq2[k].x() < sq2[left].x()) left = k;
  const Vec2 lv = sq2[left];
  for (Vec2& v : sq2) v += Vec2(1.0 + 0.2 * d0, 1.0 - 0.3 * d0) - lv;
  m.add(sq2);
  const auto c2 = detect(m);
  BOOST_TEST_REQUIRE(c2.size() == 1u);
  BOOST_TEST((c2[0].key == ContactKey{1, left, 0, 1}));
}

BOOST_AUTO_TEST_CASE(edge_edge_contact_is_two_vertex_edge_contacts_with_half_the_shared_length) {
  Scene s;
  s.add_rect(0, 0, 1, 1);
  s.add_rect(0.2, 1.0, 0.8, 1.5);  // bottom edge 0 lies on the base's top edge 2
  const auto c = detect(s);
  BOOST_TEST_REQUIRE(c.size() == 2u);
  BOOST_TEST((c[0].key == ContactKey{1, 0, 0, 2}));
  BOOST_TEST((c[1].key == ContactKey{1, 1, 0, 2}));
  for (const auto& k : c) {
    BOOST_TEST((k.kind == ContactKind::edge_edge));
    BOOST_TEST(k.length == 0.3, boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(offset_edge_edge_puts_one_contact_on_each_block) {
  Scene s;
  s.add_rect(0, 0, 1, 1);
  s.add_rect(0.5, 1.0, 1.5, 1.5);  // overhangs the base by 0.5
  const auto c = detect(s);
  BOOST_TEST_REQUIRE(c.size() == 2u);
  // base corner (1, 1) = vertex 2 of block 0 on the upper block's bottom edge 0,
  // upper block's vertex 0 on the base's top edge 2.
  BOOST_TEST((c[0].key == ContactKey{0, 2, 1, 0}));
  BOOST_TEST((c[1].key == ContactKey{1, 0, 0, 2}));
  BOOST_TEST(c[0].length + c[1].length == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(c[0].length == 0.25, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(equal_stacked_blocks_resolve_coincident_corners_into_two_half_length_contacts) {
  Scene s;
  s.add_rect(0, 0, 1, 1);
  s.add_rect(0, 1, 1, 2);
  const auto c = detect(s);
  BOOST_TEST_REQUIRE(c.size() == 2u);
  double total = 0.0;
  for (const auto& k : c) {
    // each resolved contact is a vertex on the facing horizontal edge
    const bool upper_on_base = k.key.vblock == 1 && k.key.eblock == 0 && k.key.edge == 2;
    const bool base_on_upper = k.key.vblock == 0 && k.key.eblock == 1 && k.key.edge == 0;
    BOOST_TEST((upper_on_base || base_on_upper));
    BOOST_TEST((k.kind == ContactKind::edge_edge));
    total += k.length;
  }
  BOOST_TEST(total == 1.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(angle_rule_tie_keeps_the_contact_of_the_last_step) {
  Scene s;
  s.add_rect(0, 0, 1, 1);
  s.add_rect(0, 1, 1, 2);
  const auto first = detect(s);
  BOOST_TEST_REQUIRE(first.size() == 2u);
  // Offer the swapped alternative of the first contact as the previous one.
  const ContactKey k = first[0].key;
  const ContactKey alt = k.vblock == 1 ? ContactKey{0, 3, 1, 0} : ContactKey{1, 0, 0, 2};
  std::vector<ContactKey> prev{alt};
  const auto again = detect(s, prev);
  bool kept = false;
  for (const auto& c : again) kept |= c.key == alt;
  BOOST_TEST(kept);
}

BOOST_AUTO_TEST_CASE(corner_in_a_notch_touches_both_edges_of_the_notch) {
  // Stepped base: a reflex vertex at (1, 0) between the tread (1,0)->(0,0) and
  // the riser (1,1)->(1,0); a block's corner sits in it.
  Scene s;
  s.add({{0, -1}, {2, -1}, {2, 1}, {1, 1}, {1, 0}, {0, 0}});
  s.add_rect(0.2, 0.0, 1.0, 0.5);
  const auto c = detect(s);
  // corner (1, 0) = vertex 1 of block 1 on the riser (edge 3) and on the tread (edge 4),
  // plus the block's other bottom corner on the tread.
  bool riser = false, tread = false;
  for (const auto& k : c) {
    riser |= k.key == ContactKey{1, 1, 0, 3};
    tread |= k.key == ContactKey{1, 1, 0, 4};
  }
  BOOST_TEST(riser);
  BOOST_TEST(tread);
}

BOOST_AUTO_TEST_CASE(a_corner_past_the_notch_along_one_edge_touches_that_edge_only) {
  // The notch of the test above; the block's corner has moved 0.5 mm along the
  // tread past the riser's foot (x = 0.9995) and sits 0.2 mm below the riser's
  // lower end (y = -0.0002, inside the tread by the penalty overlap).
  auto keys = [](const std::vector<DetectedContact>& c) {
    bool riser = false, tread = false;
    for (const auto& k : c) {
      riser |= k.key == ContactKey{1, 1, 0, 3};
      tread |= k.key == ContactKey{1, 1, 0, 4};
    }
    return std::pair{riser, tread};
  };
  Scene s;
  s.add({{0, -1}, {2, -1}, {2, 1}, {1, 1}, {1, 0}, {0, 0}});
  s.add({{0.1995, -0.0002}, {0.9995, -0.0002}, {0.9995, 0.4998}, {0.1995, 0.4998}});
  std::vector<std::pair<int, int>> pairs{{0, 1}};
  // Within the reach (the allowed penetration, 0.5 mm here): still in the notch, both edges.
  auto [riser, tread] = keys(detect_contacts(s.views(), pairs, {d0, 3.0, 5e-4}, {}));
  BOOST_TEST(riser);
  BOOST_TEST(tread);
  // With a reach of 0.1 mm the corner is 0.2 mm below the riser's end: the tread alone.
  std::tie(riser, tread) = keys(detect_contacts(s.views(), pairs, {d0, 3.0, 1e-4}, {}));
  BOOST_TEST(!riser);
  BOOST_TEST(tread);
  // Even when the riser contact existed in the last step: its line would hold the corner in tension.
  const std::vector<ContactKey> previous{ContactKey{1, 1, 0, 3}, ContactKey{1, 1, 0, 4}};
  std::tie(riser, tread) = keys(detect_contacts(s.views(), pairs, {d0, 3.0, 1e-4}, previous));
  BOOST_TEST(!riser);
  BOOST_TEST(tread);
}

BOOST_AUTO_TEST_CASE(straight_angle_vertices_never_enter_an_edge) {
  // The base's top is split at (1, 0) (a straight angle); the block lies across it.
  Scene s;
  s.add({{0, -1}, {2, -1}, {2, 0}, {1, 0}, {0, 0}});
  s.add_rect(0.5, 0.0, 1.5, 0.5);
  for (const auto& k : detect(s)) BOOST_TEST(!(k.key.vblock == 0 && k.key.vertex == 3));
}

BOOST_AUTO_TEST_CASE(a_vertex_near_a_corner_enters_the_edge_it_lies_along_not_one_it_lies_beyond) {
  // Two blocks of a generated rock mass (bench/scenes/jointed-slope-cohesionless.yaml
  // scaled to 1 021 blocks, blocks 458 and 460) sharing a 4.7 mm edge between
  // vertices 0 and 4 of the first. Vertex 4 of the second (on the shared edge's
  // end) is within the search distance of vertex 0 of the first; the angle rule
  // scores the first block's edge 0 best, whose line the vertex lies 2 mm behind
  // but beyond its end: taken as the entrance, that was a spring pushing with
  // p_n x 2 mm from the first step. The vertex lies along the shared edge
  // (edge 4), and that is its entrance, with no penetration.
  Scene s;
  s.add({{5.8184765764427375, 15.505570963047253}, {5.423605791326956, 15.900441748163034},
         {5.33129923193458, 15.866844908116684}, {5.7298310885258035, 15.468313051525463},
         {5.820081486141942, 15.501161509888426}});
  s.add({{6.4821990597100765, 15.74215259825179}, {6.307494018747157, 16.222150753362303},
         {5.645376445179023, 15.981159664998941}, {5.8184765764427375, 15.505570963047253},
         {5.820081486141942, 15.501161509888426}});
  const std::vector<std::pair<int, int>> pairs{{0, 1}};
  const auto found = detect_contacts(s.views(), pairs, {0.0385, 3.0}, {});
  BOOST_TEST_REQUIRE(!found.empty());
  for (const auto& c : found) {
    const BlockView& vb = s.views()[c.key.vblock];
    const BlockView& eb = s.views()[c.key.eblock];
    const Vec2 p = vb.vertices[c.key.vertex];
    const Vec2 a = eb.vertices[c.key.edge], b = eb.vertices[(c.key.edge + 1) % eb.vertices.size()];
    const Vec2 t = (b - a).normalized();
    const double behind = (a - p).x() * (b - p).y() - (a - p).y() * (b - p).x();  // > 0: p behind the line
    const double r = t.dot(p - a) / (b - a).norm();
    BOOST_TEST_CONTEXT("vertex " << c.key.vblock << "." << c.key.vertex << " edge " << c.key.eblock << "."
                                 << c.key.edge) {
      // Every contact's vertex lies along its entrance edge, or is not behind its line.
      BOOST_TEST((behind / (b - a).norm() <= 1e-9 || (r >= -1e-9 && r <= 1.0 + 1e-9)));
    }
  }
}

BOOST_AUTO_TEST_CASE(a_corner_paired_with_a_vertex_of_a_straight_side_enters_no_edge_the_angle_rule_refuses) {
  // Two blocks of the generated 744-block slope (bench/scenes/jointed-slope-cohesionless.yaml,
  // blocks 98 and 106 at 52 d) sharing a face, its two ends 0.7 and 1.2 mm apart and open.
  // The first block's side beyond the shared face is straight through its vertex 1, 58.8 mm
  // from its corner 0. With a search distance of 62.5 mm (the static step's) the second
  // block's corner (vertex 2) was paired with vertex 1 too, and entered edge 0, whose line
  // it lies 0.3 mm behind beyond the corner: a spring pushing with p_n x 0.3 mm from the
  // step start, where the blocks do not touch. Vertex 1 is no corner, and the corner's
  // wedge crosses the line of either edge at it (score -0.91, below -sin 3 deg): the angle
  // rule admits no candidate of that pair, and the contacts are the shared face's two
  // ends, whatever the last step's were.
  Scene s;
  s.add({{9.668130344720666, 8.270402047691343}, {9.613391426416978, 8.250579284301999},
         {8.983200640486231, 8.022366465584913}, {9.42930387294238, 7.574814153707516},
         {10.114233577176808, 7.822849735814109}});
  s.add({{12.46785402996989, 9.28737045051805}, {10.790403224816506, 8.677852745193416},
         {9.668802023017575, 8.270308280277025}, {10.115393895874774, 7.823263912967147},
         {10.638795381782717, 8.013446821267097}, {12.663439526704952, 8.749120528967172}});
  const std::vector<std::pair<int, int>> pairs{{0, 1}};
  const std::vector<ContactKey> last{{0, 0, 1, 2}, {0, 4, 1, 2}};  // the face's two ends
  for (const auto& previous : {std::vector<ContactKey>{}, last}) {
    const auto found = detect_contacts(s.views(), pairs, {0.0625, 3.0}, previous);
    BOOST_TEST_CONTEXT("with the last step's contacts: " << !previous.empty()) {
      BOOST_TEST(found.size() == 2u);
      for (const auto& c : found) {
        BOOST_TEST_CONTEXT("vertex " << c.key.vblock << "." << c.key.vertex << " edge " << c.key.eblock << "."
                                     << c.key.edge) {
          BOOST_TEST((c.kind == ContactKind::edge_edge));
          BOOST_TEST(!(c.key.vblock == 1 && c.key.vertex == 2 && c.key.edge == 0));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
