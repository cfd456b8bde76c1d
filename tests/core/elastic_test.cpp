// A block squeezed by two opposite point loads P at mid-height of its ends
// carries sigma_x = -P/H and shows the strain sigma/E in plane stress and
// (1 - nu^2) sigma/E in plane strain (with the matching lateral strains
// -nu sigma/E and -nu (1 + nu) sigma/E).
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

constexpr double L = 2.0, H = 1.0;  // block length and height [m]
constexpr double E = 1.0e10, nu = 0.25;

Model squeezed_block(PlaneMode plane, std::vector<LoadSample> history_right) {
  Model m;
  m.materials[0].young_modulus = E;
  m.materials[0].poisson_ratio = nu;
  m.materials[0].plane = plane;
  m.settings.dt = 1.0;  // static: inertia 2 rho S/dt^2 is ~1e-7 of the elastic stiffness
  m.settings.dynamic_ratio = 0.0;
  m.settings.gravity = Vec2::Zero();
  m.blocks.push_back(block({{-L / 2, -H / 2}, {L / 2, -H / 2}, {L / 2, H / 2}, {-L / 2, H / 2}}));
  std::vector<LoadSample> history_left = history_right;
  for (auto& s : history_left) s.force = -s.force;
  m.point_loads.push_back({.block = 0, .point = {L / 2, 0.0}, .history = history_right});
  m.point_loads.push_back({.block = 0, .point = {-L / 2, 0.0}, .history = history_left});
  m.measurement_points.push_back({.block = 0, .point = {L / 2, 0.0}});
  m.measurement_points.push_back({.block = 0, .point = {-L / 2, 0.0}});
  m.measurement_points.push_back({.block = 0, .point = {0.0, H / 2}});
  m.measurement_points.push_back({.block = 0, .point = {0.0, -H / 2}});
  return m;
}

struct Strains {
  double x, y;
};

Strains measured_strains(const Engine& e) {
  const auto& s = e.measurements();
  const double dx = s[0].back().displacement.x() - s[1].back().displacement.x();
  const double dy = s[2].back().displacement.y() - s[3].back().displacement.y();
  return {dx / L, dy / H};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(elastic)

BOOST_AUTO_TEST_CASE(plane_stress_strain_is_sigma_over_E) {
  const double P = 1.0e4;  // [N per m thickness]
  Engine e(squeezed_block(PlaneMode::plane_stress, {{0.0, {-P, 0.0}}}));
  e.run(10);
  const double sigma = -P / H;
  BOOST_TEST(std::abs(e.stress(0).x() - sigma) <= 1e-5 * std::abs(sigma));
  BOOST_TEST(std::abs(e.stress(0).y()) <= 1e-5 * std::abs(sigma));
  BOOST_TEST(std::abs(e.stress(0).z()) <= 1e-5 * std::abs(sigma));
  const Strains s = measured_strains(e);
  BOOST_TEST(std::abs(s.x - sigma / E) <= 1e-4 * std::abs(sigma / E));
  BOOST_TEST(std::abs(s.y + nu * sigma / E) <= 1e-4 * std::abs(nu * sigma / E));
}

BOOST_AUTO_TEST_CASE(plane_strain_strain_is_one_minus_nu_squared_sigma_over_E) {
  const double P = 1.0e4;
  Engine e(squeezed_block(PlaneMode::plane_strain, {{0.0, {-P, 0.0}}}));
  e.run(10);
  const double sigma = -P / H;
  BOOST_TEST(std::abs(e.stress(0).x() - sigma) <= 1e-5 * std::abs(sigma));
  BOOST_TEST(std::abs(e.stress(0).y()) <= 1e-5 * std::abs(sigma));
  const Strains s = measured_strains(e);
  const double ex = (1.0 - nu * nu) * sigma / E, ey = -nu * (1.0 + nu) * sigma / E;
  BOOST_TEST(std::abs(s.x - ex) <= 1e-4 * std::abs(ex));
  BOOST_TEST(std::abs(s.y - ey) <= 1e-4 * std::abs(ey));
}

BOOST_AUTO_TEST_CASE(point_load_history_is_piecewise_linear_in_time) {
  // Ramp 0 -> P over [0, 1], down to P/2 at t = 2, held after. The static
  // block follows the load: sigma_x(t) = -P(t)/H at each step's end time.
  const double P = 1.0e4;
  Model m = squeezed_block(PlaneMode::plane_stress, {{0.0, {0.0, 0.0}}, {1.0, {-P, 0.0}}, {2.0, {-P / 2, 0.0}}});
  m.settings.dt = 0.25;  // inertia still ~1e-6 of the elastic stiffness
  Engine e(m);
  auto load = [&](double t) {
    if (t <= 1.0) return P * t;
    if (t <= 2.0) return P * (1.0 - 0.5 * (t - 1.0));
    return P / 2;
  };
  for (int k = 0; k < 12; ++k) {
    e.step();
    const double sigma = -load(e.time()) / H;
    BOOST_TEST(std::abs(e.stress(0).x() - sigma) <= 1e-4 * P / H);
  }
}

BOOST_AUTO_TEST_CASE(initial_stress_balanced_by_loads_stays_put) {
  // A block carrying sigma_x = -P/H from the start, squeezed by P: already in
  // equilibrium, nothing moves.
  const double P = 1.0e4;
  Model m = squeezed_block(PlaneMode::plane_stress, {{0.0, {-P, 0.0}}});
  m.blocks[0].initial_stress = {-P / H, 0.0, 0.0};
  Engine e(m);
  e.run(5);
  BOOST_TEST(std::abs(e.stress(0).x() + P / H) <= 1e-9 * P / H);
  BOOST_TEST(e.point_displacement(0, {L / 2, 0.0}).norm() <= 1e-15);
}

BOOST_AUTO_TEST_SUITE_END()
