// Fuzzing the rock-mass cutter: random joint sets with non-persistent traces on a
// concave region with a hole, over many seeds. Every cut must conserve the area
// (1e-12 relative), give blocks that never overlap and tag every edge; the only
// error allowed is the clear one for a block that would enclose a hole or another
// block. Also built and run alone under AddressSanitizer (scripts/test.sh).
#define BOOST_TEST_MODULE rheodda rockmass fuzz
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "rheodda/rockmass/cut.hpp"
#include "rheodda/rockmass/generate.hpp"
#include "rheodda/scene/geometry.hpp"

using namespace rheodda::rockmass;

BOOST_AUTO_TEST_CASE(random_non_persistent_sets_conserve_area_and_never_overlap) {
  // A slope profile (concave at the toe and the crest) with a tunnel-like hole.
  const Region region{{{0, 0}, {60, 0}, {60, 30}, {40, 30}, {20, 10}, {0, 10}},
                      {{{44, 12}, {50, 12}, {52, 16}, {47, 20}, {42, 16}}}};
  const double area = polygon_area(region.outer) - std::abs(polygon_area(region.holes[0]));
  int cut = 0, enclosed = 0, refused_by_loader = 0;
  std::size_t blocks_total = 0;
  for (std::uint64_t seed = 1; seed <= 120; ++seed) {
    std::mt19937_64 pick(seed);  // the scenario (not the generation: that is the library's)
    auto u = [&](double a, double b) { return a + (b - a) * double(pick() >> 11) * 0x1.0p-53; };
    std::vector<Trace> traces;
    const int sets = 2 + int(pick() % 2);
    for (int k = 0; k < sets; ++k) {
      JointSetGeneration g;
      g.tag = k;
      g.dip = u(0, 90);
      g.dips_right = pick() % 2 == 0;
      g.spacing = u(2.0, 6.0);
      g.spacing_distribution = static_cast<SpacingDistribution>(pick() % 4);
      g.spacing_deviation = 0.3 * g.spacing;
      if (pick() % 4 != 0) {
        g.trace_length = u(5, 30);
        g.gap = u(0.5, 8);
      }
      g.dip_spread = pick() % 2 ? u(0, 10) : 0.0;
      const auto t = generate_traces(g, {0, 0, 60, 30}, seed, k);
      traces.insert(traces.end(), t.begin(), t.end());
    }
    // Half the scenarios also get a trace along a region edge and one through a vertex.
    if (seed % 2 == 0) {
      traces.push_back({{-5, 0}, {70, 0}, 0});
      traces.push_back({{10, 0}, {30, 20}, 1});  // through the crest-side vertex (20, 10)
    }
    CutOptions options;
    options.sliver_area = seed % 3 == 0 ? 0.05 : 0.0;
    BOOST_TEST_CONTEXT("seed " << seed << ", " << traces.size() << " traces") {
      CutResult r;
      try {
        r = cut_blocks(region, traces, options);
      } catch (const CutError& e) {
        BOOST_TEST(std::string(e.what()).find("DDA blocks are simple polygons") != std::string::npos, e.what());
        ++enclosed;
        continue;
      }
      ++cut;
      blocks_total += r.blocks.size();
      double sum = 0.0;
      std::vector<rheodda::scene::BlockDescription> blocks;
      for (const Block& b : r.blocks) {
        BOOST_TEST(b.area > 0.0);
        BOOST_TEST(b.edge_tag.size() == b.polygon.size());
        for (int t : b.edge_tag) BOOST_TEST((t >= kBoundaryTag && t < sets));
        if (options.sliver_area > 0.0) BOOST_TEST(b.area >= options.sliver_area);
        sum += b.area;
        rheodda::scene::BlockDescription d;
        for (const Point& p : b.polygon) d.polygon.push_back({p[0], p[1]});
        blocks.push_back(std::move(d));
      }
      BOOST_TEST(std::abs(sum - area) <= 1e-12 * area);
      BOOST_TEST(rheodda::scene::overlapping_blocks(blocks, 1e-9 * 60).empty());
      // Blocks the scene loader accepts (at its tolerance 1e-9 of the model size).
      // Known limit: two traces crossing at a grazing angle (< ~1e-7 rad) leave a
      // needle the loader refuses with "folds back on itself at vertex k" (a clear
      // error naming the block); counted, and must stay rare.
      for (const auto& b : blocks)
        if (const auto defect = rheodda::scene::polygon_defect(b.polygon, 1e-9 * 60)) {
          BOOST_TEST_MESSAGE("seed " << seed << ": a block the loader refuses: " << *defect);
          ++refused_by_loader;
          break;
        }
    }
  }
  BOOST_TEST_MESSAGE(cut << " cuts with " << blocks_total << " blocks, " << enclosed
                          << " refused (a hole no joint reaches), " << refused_by_loader
                          << " with a block the loader refuses (needle)");
  BOOST_TEST(cut >= 115);                // a refused cut is the rare exception
  BOOST_TEST(refused_by_loader <= 3);    // measured: 2 of 120 (seeds 23 and 101)
}
