// BlockSystem::finalize merges repeated pairs into sorted upper blocks; when
// the pairs come in the sequence of the last call (the iterates of one step)
// it reuses that call's merge map. Either way the merged system must be the
// one a fresh merge gives.
#include <boost/test/unit_test.hpp>

#include <map>

#include "rheodda/core/block_system.hpp"

using namespace rheodda::core;

namespace {

Mat6 value(int i, int j, double scale) {
  Mat6 m;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) m(a, b) = scale * (1.0 + i + 10.0 * j + 0.1 * a - 0.01 * b);
  return m;
}

void fill(BlockSystem& s, const std::vector<std::pair<int, int>>& pairs, double scale) {
  s.reset(6);
  for (auto [i, j] : pairs) s.add_stiffness(i, j, value(i, j, scale));
  s.finalize();
}

/// The merged blocks as a dense upper map, from scratch.
std::map<std::pair<int, int>, Mat6> expected(const std::vector<std::pair<int, int>>& pairs,
                                             double scale) {
  std::map<std::pair<int, int>, Mat6> m;
  for (auto [i, j] : pairs) {
    const Mat6 v = value(i, j, scale);
    auto key = std::make_pair(std::min(i, j), std::max(i, j));
    if (!m.count(key)) m[key] = Mat6::Zero();
    m[key] += i < j ? v : Mat6(v.transpose());
  }
  return m;
}

void check(const BlockSystem& s, const std::vector<std::pair<int, int>>& pairs, double scale) {
  const auto want = expected(pairs, scale);
  BOOST_TEST_REQUIRE(s.off_diagonal().size() == want.size());
  std::size_t k = 0;
  int last_j = -1, last_i = -1;
  for (const auto& o : s.off_diagonal()) {
    BOOST_TEST((o.j > last_j || (o.j == last_j && o.i > last_i)));  // sorted by (j, i)
    last_j = o.j;
    last_i = o.i;
    BOOST_TEST((o.k - want.at({o.i, o.j})).norm() == 0.0);
    ++k;
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(block_system)

BOOST_AUTO_TEST_CASE(repeated_sequences_merge_like_a_fresh_sort) {
  const std::vector<std::pair<int, int>> pairs{{0, 1}, {3, 2}, {1, 0}, {4, 5}, {2, 3}, {0, 1}, {5, 0}};
  BlockSystem s;
  fill(s, pairs, 1.0);
  check(s, pairs, 1.0);
  fill(s, pairs, 2.5);  // same sequence, new values: the cached merge
  check(s, pairs, 2.5);
  const std::vector<std::pair<int, int>> other{{1, 4}, {0, 1}, {4, 1}};
  fill(s, other, 1.0);  // another sequence: merged anew
  check(s, other, 1.0);
  fill(s, pairs, 3.0);
  check(s, pairs, 3.0);
}

BOOST_AUTO_TEST_CASE(blocks_added_after_a_finalize_join_the_merged_ones) {
  BlockSystem s;
  s.reset(3);
  s.add_stiffness(0, 1, value(0, 1, 1.0));
  s.finalize();
  s.add_stiffness(1, 0, value(1, 0, 1.0));
  s.add_stiffness(1, 2, value(1, 2, 1.0));
  s.finalize();
  check(s, {{0, 1}, {1, 0}, {1, 2}}, 1.0);
}

BOOST_AUTO_TEST_SUITE_END()
