// Fixed points: penalty springs p holding material points at their initial
// positions. A block held by fixed points under gravity stays put.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

BOOST_AUTO_TEST_SUITE(fixed_point)

BOOST_AUTO_TEST_CASE(block_fixed_at_its_centroid_sags_weight_over_penalty) {
  // One fixed point at the centroid only sees the translation: the static
  // equilibrium is p u = rho g S, i.e. u = rho g S / p.
  Model m;
  m.settings.dt = 0.01;
  m.settings.dynamic_ratio = 0.0;
  m.blocks.push_back(block({{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
  m.fixed_points.push_back({.block = 0, .point = {1.0, 0.5}});
  Engine e(m);
  e.run(20);
  const Material mat;
  const double p = 100.0 * mat.young_modulus;  // the automatic penalty
  const double sag = mat.density * 9.81 * 2.0 / p;
  BOOST_TEST(std::abs(e.point_displacement(0, {1.0, 0.5}).y() + sag) <= 1e-9 * sag);
  BOOST_TEST(std::abs(e.point_displacement(0, {1.0, 0.5}).x()) <= 1e-9 * sag);
}

BOOST_AUTO_TEST_CASE(block_on_two_fixed_corners_stays_put_under_gravity) {
  for (double ratio : {0.0, 1.0}) {
    Model m;
    m.settings.dt = 0.01;
    m.settings.dynamic_ratio = ratio;
    m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
    m.fixed_points.push_back({.block = 0, .point = {0.0, 0.0}});
    m.fixed_points.push_back({.block = 0, .point = {1.0, 0.0}});
    Engine e(m);
    e.run(200);
    // Elastic sag scale of a block on point supports: rho g h^2 / E = 2.6e-6 m.
    const double bound = 1e-5;
    for (const Vec2& c : {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)})
      BOOST_TEST(e.point_displacement(0, c).norm() <= bound);
    // And it does not drift: later steps move it by less than round-off of the sag.
    const Vec2 before = e.point_displacement(0, {0.5, 1.0});
    e.run(200);
    BOOST_TEST((e.point_displacement(0, {0.5, 1.0}) - before).norm() <= 1e-3 * bound);
  }
}

BOOST_AUTO_TEST_SUITE_END()
