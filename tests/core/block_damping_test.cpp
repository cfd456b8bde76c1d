// Block damping (Material::damping_ratio; docs/reference/engine.md, "Block damping"): a
// free square block released from a hydrostatic initial stress vibrates in its
// symmetric strain mode; the Kelvin-Voigt damping tau = 2 zeta / omega_1 gives
// that mode the damping ratio zeta_s = tau omega_s / 2, and its successive
// stress peaks fall by the damped oscillator's closed form
// exp(-2 pi zeta_s / sqrt(1 - zeta_s^2)). The trapezoidal rule keeps the
// energy of linear vibrations, so what decays is the damping alone, and the
// energy balance names it (dissipation_block_damping).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

/// Successive maxima of sigma_x of a free 1 m square released from sigma0 = (s, s, 0).
struct Release {
  std::vector<double> peaks;  ///< [stress]
  double omega_1 = 0.0;       ///< lowest strain mode [rad/time]
  double omega_s = 0.0;       ///< symmetric (excited) strain mode [rad/time]
  EnergyBalance energy;
};

Release release(double zeta, double dt, int steps) {
  Model m;
  m.settings.dt = dt;
  m.settings.gravity = Vec2::Zero();
  m.settings.time_integration = TimeIntegration::trapezoidal;
  Material& mat = m.materials[0];  // plane stress, E 1e10, nu 0.25, rho 2600
  mat.damping_ratio = zeta;
  BlockDef b = block({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  b.initial_stress = Vec3(1e6, 1e6, 0.0);
  m.blocks.push_back(b);
  // Plane stress, unit square (S = 1, int dx^2 = int dy^2 = 1/12): the symmetric
  // mode ex = ey has omega_s^2 = S E / ((1 - nu) rho / 12); the antisymmetric and
  // shear modes share the lowest, omega_1^2 = S E / ((1 + nu) rho / 12).
  Release r;
  r.omega_s = std::sqrt(mat.young_modulus / ((1.0 - mat.poisson_ratio) * mat.density / 12.0));
  r.omega_1 = std::sqrt(mat.young_modulus / ((1.0 + mat.poisson_ratio) * mat.density / 12.0));
  Engine e(m);
  double prev2 = 0.0, prev1 = 1e6;
  for (int k = 0; k < steps; ++k) {
    e.step();
    const double s = e.stress(0).x();
    if (k >= 1 && prev1 > prev2 && prev1 >= s && prev1 > 0.0) r.peaks.push_back(prev1);
    prev2 = prev1;
    prev1 = s;
  }
  r.energy = e.energy();
  return r;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(block_damping)

BOOST_AUTO_TEST_CASE(strain_vibration_decays_at_the_closed_form_rate_of_the_damping_ratio) {
  const double zeta = 0.05, dt = 2e-6;
  const Release r = release(zeta, dt, 20000);
  BOOST_TEST_REQUIRE(r.peaks.size() >= 8u);
  const double zeta_s = zeta * r.omega_s / r.omega_1;  // stiffness-proportional damping
  const double expected = std::exp(-2.0 * std::numbers::pi * zeta_s / std::sqrt(1.0 - zeta_s * zeta_s));
  // Peaks are sampled at the steps (omega dt = 0.016): the ratio over several
  // periods, to sampling error.
  const double measured = std::pow(r.peaks[6] / r.peaks[1], 1.0 / 5.0);
  BOOST_TEST_MESSAGE("block damping: peak ratio per period " << measured << ", closed form " << expected
                     << " (zeta_s " << zeta_s << ")");
  BOOST_TEST(measured == expected, boost::test_tools::tolerance(2e-3));
  // The balance: the strain energy released went to the damping term.
  const EnergyBalance& b = r.energy;
  BOOST_TEST(b.total.dissipation_block_damping > 0.9 * (b.initial.total() - b.stored.total()));
  BOOST_TEST(b.max_relative_residual < 1e-3);
}

BOOST_AUTO_TEST_CASE(without_damping_the_trapezoidal_rule_keeps_the_vibration) {
  const Release r = release(0.0, 2e-6, 20000);
  BOOST_TEST_REQUIRE(r.peaks.size() >= 8u);
  BOOST_TEST(r.peaks[6] == r.peaks[1], boost::test_tools::tolerance(1e-3));
  BOOST_TEST(r.energy.total.dissipation_block_damping == 0.0);
}

BOOST_AUTO_TEST_CASE(damping_ratio_is_refused_outside_zero_one_and_in_static_analysis) {
  Model m;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  m.materials[0].damping_ratio = 1.5;
  BOOST_CHECK_THROW(Engine{m}, ModelError);
  m.materials[0].damping_ratio = 0.1;
  m.settings.dynamic_ratio = 0.0;
  BOOST_CHECK_THROW(Engine{m}, ModelError);
}

BOOST_AUTO_TEST_SUITE_END()
