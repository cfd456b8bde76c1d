// Water in the joints (core/water.hpp; docs/reference/water.md): the exact load terms of
// the hydrostatic pressure on block edges against closed forms and an
// independent quadrature, the surface's interpolation in time, buoyancy through
// the engine, and the model checks.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/water.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

constexpr double kGammaW = 9810.0;  // [N/m^3]

/// Water at a constant level h [m].
Water level(double h) {
  Water w;
  w.unit_weight = kGammaW;
  w.history.push_back({0.0, {{-1e3, h}, {1e3, h}}});
  return w;
}

/// Reference: int_0^1 T(x(s))^T (-p(s)) nL ds by the composite midpoint rule
/// on n pieces (independent of the splitting and Simpson's rule of water_edge_load).
Vec6 edge_load_quadrature(const Water& w, const Vec2& a, const Vec2& b, const Vec2& c, double t, int n) {
  const Vec2 e = b - a, nL(e.y(), -e.x());
  Vec6 F = Vec6::Zero();
  for (int k = 0; k < n; ++k) {
    const Vec2 x = a + (k + 0.5) / n * e;
    F += rheodda::contact::displacement_matrix(c, x).transpose() * (-water_pressure(w, x, t) * nL) / n;
  }
  return F;
}

double rel(const Vec6& a, const Vec6& b) { return (a - b).norm() / b.norm(); }

}  // namespace

BOOST_AUTO_TEST_SUITE(water)

BOOST_AUTO_TEST_CASE(a_submerged_polygon_gets_the_buoyancy_gamma_w_A_and_the_mean_pressure_on_its_strains) {
  // Wholly below the level h, by the divergence theorem with p = gamma_w (h - y):
  //   (u0, v0): -int grad p dA = (0, gamma_w A)           (Archimedes)
  //   r0:       gamma_w int (x - x0) dA = 0                (buoyancy at the centroid)
  //   ex, ey:   -int p dA = -gamma_w (h - y0) A            (all-round pressure)
  //   gxy:      gamma_w/2 int (x - x0) dA = 0
  // for a rectangle and a concave L-shaped block, to round-off.
  const std::vector<std::vector<Vec2>> shapes{
      {{0, 0}, {2, 0}, {2, 1}, {0, 1}},
      {{1, -2}, {4, -2}, {4, -1}, {2, -1}, {2, 1.5}, {1, 1.5}}};
  for (const auto& v : shapes) {
    const PolygonIntegrals g = polygon_integrals(v);
    const Vec2 c = g.centroid();
    const double h = 7.5;
    Vec6 expected = Vec6::Zero();
    expected(1) = kGammaW * g.S;
    expected(3) = expected(4) = -kGammaW * (h - c.y()) * g.S;
    const Vec6 F = water_block_load(level(h), v, c, 0.0);
    BOOST_TEST_MESSAGE("load " << F.transpose() << ", closed form " << expected.transpose());
    BOOST_TEST(rel(F, expected) < 1e-13);
  }
}

BOOST_AUTO_TEST_CASE(a_half_wet_vertical_edge_carries_the_hydrostatic_triangle_at_a_third_of_its_depth) {
  // Edge x = 1 from y = -1 up to y = 2 (interior to its left, outward normal +x),
  // level 0: the wet part -1 < y < 0 carries p = gamma_w (-y), resultant
  // fx = -gamma_w z^2 / 2 (z = 1) through y = -2/3 (a third above the bottom).
  // Load terms about c: u0 = fx, r0 = -(y_f - c_y) fx, ex = (1 - c_x) fx,
  // gxy = (y_f - c_y) fx / 2, v0 = ey = 0.
  const Vec2 a(1.0, -1.0), b(1.0, 2.0), c(0.3, 0.4);
  const double fx = -0.5 * kGammaW, yf = -2.0 / 3.0;
  Vec6 expected;
  expected << fx, 0.0, -(yf - c.y()) * fx, (1.0 - c.x()) * fx, 0.0, 0.5 * (yf - c.y()) * fx;
  const Vec6 F = water_edge_load(level(0.0), a, b, c, 0.0);
  BOOST_TEST_MESSAGE("load " << F.transpose() << ", closed form " << expected.transpose());
  BOOST_TEST(rel(F, expected) < 1e-13);
  // Reversed (the interior on the other side): the opposite load.
  BOOST_TEST(rel(-water_edge_load(level(0.0), b, a, c, 0.0), expected) < 1e-13);
  // A dry edge carries nothing.
  BOOST_TEST(water_edge_load(level(-1.0), a, b, c, 0.0).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(a_kinked_surface_across_an_inclined_edge_matches_a_fine_quadrature) {
  // A surface with two kinks above, across and below an inclined edge, at a
  // time between two samples (both surfaces' kinks split the edge): the exact
  // integral against a midpoint rule on 2e5 pieces (error ~ 1e-10 relative,
  // the kinks and the crossing cost O(1/n^2) each).
  Water w;
  w.unit_weight = kGammaW;
  w.history.push_back({0.0, {{-5, 1.0}, {0.7, 2.5}, {2.2, -0.5}, {5, 0.3}}});
  w.history.push_back({10.0, {{-5, 0.0}, {1.3, 1.5}, {6, 1.0}}});
  const Vec2 a(-1.0, -0.5), b(3.0, 1.8), c(0.2, 0.9);
  for (const double t : {-1.0, 0.0, 3.7, 10.0, 12.0}) {
    const Vec6 F = water_edge_load(w, a, b, c, t);
    const Vec6 ref = edge_load_quadrature(w, a, b, c, t, 200000);
    BOOST_TEST_MESSAGE("t " << t << ": load " << F.transpose() << ", quadrature " << ref.transpose());
    BOOST_TEST(rel(F, ref) < 1e-8);
  }
}

BOOST_AUTO_TEST_CASE(the_surface_is_linear_in_time_between_samples_and_held_beyond_them) {
  // A drawdown 10 -> 4 m over 0..6 and a refill to 8 m at 10: h(t) piecewise
  // linear, held before the first and after the last sample; a polyline's
  // height is linear in x between its points and held beyond its ends.
  Water w;
  w.unit_weight = kGammaW;
  w.history.push_back({0.0, {{0, 10}, {1, 10}}});
  w.history.push_back({6.0, {{0, 4}, {1, 4}}});
  w.history.push_back({10.0, {{0, 8}, {1, 8}}});
  BOOST_TEST(water_level_at(w, 0.5, -3.0) == 10.0);
  BOOST_TEST(water_level_at(w, 0.5, 3.0) == 7.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(water_level_at(w, 0.5, 8.0) == 6.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(water_level_at(w, 0.5, 20.0) == 8.0);
  BOOST_TEST(next_water_break(w, 0.0) == 6.0);
  BOOST_TEST(std::isinf(next_water_break(w, 10.0)));
  Water s;
  s.unit_weight = kGammaW;
  s.history.push_back({0.0, {{0, 1}, {2, 3}, {4, 0}}});
  BOOST_TEST(water_level_at(s, -1.0, 0.0) == 1.0);
  BOOST_TEST(water_level_at(s, 1.0, 0.0) == 2.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(water_level_at(s, 3.0, 0.0) == 1.5, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(water_level_at(s, 9.0, 0.0) == 0.0);
  BOOST_TEST(water_pressure(s, {1.0, 0.5}, 0.0) == kGammaW * 1.5, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(water_pressure(s, {1.0, 2.5}, 0.0) == 0.0);
}

BOOST_AUTO_TEST_CASE(a_submerged_block_fixed_at_its_centroid_sags_by_its_weight_less_the_buoyancy) {
  // As fixed_point/block_fixed_at_its_centroid_sags_weight_over_penalty, under
  // 5 m of water: p u = (rho g - gamma_w) A; and with the level lowered in time
  // past the block (a drawdown), the sag follows the wet part's uplift
  // gamma_w b (h - y_bottom), b = 2 m the block's width.
  Model m;
  m.settings.dt = 0.01;
  m.settings.dynamic_ratio = 0.0;
  m.blocks.push_back(block({{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
  m.fixed_points.push_back({.block = 0, .point = {1.0, 0.5}});
  m.water.unit_weight = kGammaW;
  m.water.history.push_back({0.0, {{-1, 6.0}, {3, 6.0}}});
  m.water.history.push_back({1.0, {{-1, 6.0}, {3, 6.0}}});
  m.water.history.push_back({2.0, {{-1, -1.0}, {3, -1.0}}});
  Engine e(m);
  const Material mat;
  const double p = 100.0 * mat.young_modulus;  // the automatic penalty [N/m]
  e.run(20);
  // The all-round pressure gamma_w (h - y0) shortens the block by eps =
  // -gamma_w (h - y0) (1 - nu) / E each way (plane stress), its area (hence its
  // weight rho g S and its buoyancy gamma_w S, both on the current area) by 2 eps.
  const double eps = -kGammaW * 5.5 * (1.0 - mat.poisson_ratio) / mat.young_modulus;
  const double sag = (mat.density * 9.81 - kGammaW) * 2.0 * (1.0 + 2.0 * eps) / p;
  BOOST_TEST_MESSAGE("submerged: sag " << -e.point_displacement(0, {1.0, 0.5}).y() << " m, closed form " << sag);
  BOOST_TEST(std::abs(e.point_displacement(0, {1.0, 0.5}).y() + sag) <= 1e-9 * sag);
  BOOST_TEST(std::abs(e.point_displacement(0, {1.0, 0.5}).x()) <= 1e-9 * sag);
  // Drawdown from 6 m at t = 1 to -1 m at t = 2: at t = 1.75 the level is 0.75 m.
  // A static step lags its load by the inertia share (2M/dt^2)/p = 1e-4 of the
  // step's change (0.07 m of level, 4 % of the sag): 4e-6 of the sag; the
  // pressure's strain of the area, as above, is below 1e-6 here.
  e.run_until(1.75);
  const double h = 0.75, sag_t = (mat.density * 9.81 * 2.0 - kGammaW * 2.0 * h) / p;
  BOOST_TEST_MESSAGE("t " << e.time() << ": sag " << -e.point_displacement(0, {1.0, 0.5}).y() << " m, closed form "
                          << sag_t);
  BOOST_TEST(std::abs(e.point_displacement(0, {1.0, 0.5}).y() + sag_t) <= 1e-5 * sag_t);
}

BOOST_AUTO_TEST_CASE(adaptive_steps_end_on_the_surface_sample_times_and_restart_from_dt_after_them) {
  // As on point-load sample times (docs/guide/choosing-step-controls.md): under step_tolerance
  // the steps grow while the level stands, end on each sample time where the
  // level changes its course (0.137, 0.5), and restart from dt after it.
  Model m;
  m.settings.dt = 0.01;
  m.settings.dynamic_ratio = 0.0;
  m.settings.step_tolerance = 1e-12;
  m.blocks.push_back(block({{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
  m.fixed_points.push_back({.block = 0, .point = {1.0, 0.5}});
  m.water.unit_weight = kGammaW;
  m.water.history.push_back({0.137, {{-1, 6.0}, {3, 6.0}}});
  m.water.history.push_back({0.5, {{-1, 0.5}, {3, 0.5}}});
  Engine e(m);
  e.run_until(0.8);
  const auto& reports = e.reports();
  for (const double t : {0.137, 0.5}) {
    BOOST_TEST_CONTEXT("sample time " << t) {
      const auto it = std::find_if(reports.begin(), reports.end(),
                                   [&](const StepReport& r) { return std::abs(r.time - t) < 1e-12; });
      BOOST_TEST_REQUIRE((it != reports.end()));
      BOOST_TEST_REQUIRE((it + 1 != reports.end()));
      BOOST_TEST((it + 1)->dt == m.settings.dt);
    }
  }
  BOOST_TEST(std::max_element(reports.begin(), reports.end(), [](const StepReport& a, const StepReport& b) {
               return a.dt < b.dt;
             })->dt > 2.0 * m.settings.dt);
}

BOOST_AUTO_TEST_CASE(bad_water_is_refused_with_its_key) {
  auto model = [](Water w) {
    Model m;
    m.blocks.push_back(block({{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
    m.water = std::move(w);
    return m;
  };
  auto refused = [&](Water w, const std::string& key) {
    try {
      Engine e(model(std::move(w)));
    } catch (const ModelError& err) {
      BOOST_TEST_MESSAGE(err.what());
      return err.key() == key;
    }
    return false;
  };
  Water w = level(3.0);
  w.unit_weight = -9810.0;
  BOOST_TEST(refused(w, "water.unit_weight"));
  w = level(3.0);
  w.history.clear();
  BOOST_TEST(refused(w, "water.history"));
  w = level(3.0);
  w.history.push_back({0.0, {{-1e3, 2.0}, {1e3, 2.0}}});  // same time as the first
  BOOST_TEST(refused(w, "water.history[1].time"));
  w = level(3.0);
  w.history[0].points = {{0.5, 3.0}, {1e3, 3.0}};  // starts inside the block's x-range
  BOOST_TEST(refused(w, "water.history[0].points"));
  w = level(3.0);
  w.history[0].points = {{-1.0, 3.0}, {1.0, 3.0}, {1.0, 2.0}, {3.0, 2.0}};  // x not increasing
  BOOST_TEST(refused(w, "water.history[0].points"));
  BOOST_CHECK_NO_THROW({ Engine e(model(level(3.0))); });
}

BOOST_AUTO_TEST_SUITE_END()
