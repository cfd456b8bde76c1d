// The step limit's test of the static steps by cycles (core/src/cycle_kernels.hpp,
// moves_beyond; (3) of core/src/explicit_static.cpp): each block's bound of its vertices'
// displacement first, its vertices only where the bound does not rule the limit out. The
// answer must be the vertex-by-vertex test's, max_k,v |T(v) D_k| > allowed, exactly: here
// on random blocks and unknowns, with limits drawn around and exactly at the largest
// displacement.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "cycle_kernels.hpp"

using namespace rheodda::core;

namespace {

/// The vertex-by-vertex largest displacement (as Engine::Impl::max_vertex_displacement).
double largest_displacement(const std::vector<BlockState>& blocks, const Eigen::VectorXd& d) {
  double worst = 0.0;
  for (std::size_t k = 0; k < blocks.size(); ++k)
    for (const Vec2& v : blocks[k].vertices)
      worst = std::max(worst, (rheodda::contact::displacement_matrix(blocks[k].centroid, v) *
                               d.segment<6>(6 * static_cast<Eigen::Index>(k)))
                                  .squaredNorm());
  return std::sqrt(worst);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(step_limit)

BOOST_AUTO_TEST_CASE(the_bound_never_falls_below_a_vertex_displacement) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    BlockState b;
    b.centroid = Vec2(10.0 * u(rng), 10.0 * u(rng));
    const int n = 3 + trial % 6;
    for (int i = 0; i < n; ++i) b.vertices.push_back(b.centroid + Vec2(3.0 * u(rng), 3.0 * u(rng)));
    Vec6 D;
    for (int i = 0; i < 6; ++i) D(i) = std::pow(10.0, -4.0 * (u(rng) + 1.0)) * u(rng);
    const double bound = cycles::vertex_displacement_bound(D, cycles::vertex_radii({b})[0]);
    for (const Vec2& v : b.vertices)
      BOOST_TEST((rheodda::contact::displacement_matrix(b.centroid, v) * D).norm() <= bound * (1.0 + 1e-14));  // round-off
  }
}

BOOST_AUTO_TEST_CASE(the_test_is_the_vertex_by_vertex_one) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int beyond = 0, within = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<BlockState> blocks(20);
    for (BlockState& b : blocks) {
      b.centroid = Vec2(50.0 * u(rng), 50.0 * u(rng));
      for (int i = 0; i < 5; ++i) b.vertices.push_back(b.centroid + Vec2(u(rng), u(rng)));
    }
    Eigen::VectorXd d(6 * 20);
    for (Eigen::Index i = 0; i < d.size(); ++i) d(i) = 1e-3 * u(rng) * (i % 6 < 2 ? 1.0 : 1e-2);
    const std::vector<double> radius = cycles::vertex_radii(blocks);
    const double largest = largest_displacement(blocks, d);
    // Limits around the largest displacement, and exactly at it and at its neighbours.
    for (const double allowed : {0.5 * largest, 0.999 * largest, std::nextafter(largest, 0.0), largest,
                                 std::nextafter(largest, 1.0), 1.001 * largest, 2.0 * largest}) {
      const bool expected = largest > allowed;
      BOOST_TEST(cycles::moves_beyond(blocks, radius, d, allowed) == expected, "allowed " << allowed);
      (expected ? beyond : within) += 1;
    }
  }
  BOOST_TEST(beyond > 0);
  BOOST_TEST(within > 0);
}

BOOST_AUTO_TEST_SUITE_END()
