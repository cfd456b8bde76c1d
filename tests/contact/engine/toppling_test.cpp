// Goodman & Bray block toppling: DDA's critical friction angle of the textbook
// 16-block slope lies within 2 deg of the limit-equilibrium value; taken by the explicit
// step, between 0.5 deg below it and 0.75 deg above it.
#include <boost/test/unit_test.hpp>

#include <vector>

#include "goodman_bray.hpp"
#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// Largest block displacement [m] at each of the `times` [s] (ascending) of dynamic DDA at
/// friction phi. The model is built in the frame of the base steps (x' up the steps, y'
/// normal to them) with gravity tilted by the step dip: the same mechanics as
/// the rotated slope, with axis-aligned blocks.
/// `integrator`: the implicit step (with `solver`) or the explicit one.
std::vector<double> largest_displacements(const goodman_bray::Slope& s, double phi_deg, const std::vector<double>& times,
                                          core::ContactSolver solver = core::ContactSolver::open_close,
                                          core::Integrator integrator = core::Integrator::implicit) {
  core::Model m;
  m.settings.dt = 5e-3;  // [s]
  m.settings.contact_solver = solver;
  m.settings.integrator = integrator;
  const double a = deg(s.alpha_deg);
  m.settings.gravity = Vec2(-9.81 * std::sin(a), -9.81 * std::cos(a));
  m.materials[0].density = 2500.0;      // [kg/m^3]
  m.materials[0].young_modulus = 1e10;  // [Pa]
  // Fixed stepped base: block n stands on the step at height (n - 1) b.
  std::vector<Vec2> base{{0.0, -20.0}, {s.blocks * s.dx, -20.0}};
  for (int n = s.blocks; n >= 1; --n) {
    base.emplace_back(n * s.dx, (n - 1) * s.b);
    base.emplace_back((n - 1) * s.dx, (n - 1) * s.b);
  }
  add_fixed(m, base);
  for (int n = 1; n <= s.blocks; ++n)
    m.blocks.push_back(
        block(rect((n - 1) * s.dx, (n - 1) * s.b, n * s.dx, (n - 1) * s.b + s.height(n))));
  Sim sim(std::move(m), {joint(phi_deg)});
  std::vector<Vec2> c0;
  for (int b = 0; b <= s.blocks; ++b) c0.push_back(sim.engine.centroid(b));
  std::vector<double> out;
  for (const double t : times) {
    sim.engine.run_until(t);
    double largest = 0.0;
    for (int b = 1; b <= s.blocks; ++b)
      largest = std::max(largest, sim.engine.point_displacement(b, c0[b]).norm());
    out.push_back(largest);
  }
  return out;
}

/// Largest block displacement [m] after `seconds` (largest_displacements).
double largest_displacement(const goodman_bray::Slope& s, double phi_deg, double seconds,
                            core::ContactSolver solver = core::ContactSolver::open_close,
                            core::Integrator integrator = core::Integrator::implicit) {
  return largest_displacements(s, phi_deg, {seconds}, solver, integrator).front();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(toppling)

BOOST_AUTO_TEST_CASE(limit_equilibrium_analysis_reproduces_the_textbook_critical_angle) {
  // Hoek & Bray's worked example reaches limiting equilibrium at 38.15 deg
  // (their table rounds intermediate forces); the analysis here within 1 deg.
  const goodman_bray::Slope s;
  const double phi = goodman_bray::critical_friction_angle(s);
  BOOST_TEST_MESSAGE("limit equilibrium: phi = " << phi << " deg");
  BOOST_TEST(std::abs(phi - 38.15) < 1.0);
  BOOST_TEST(goodman_bray::toe_force(s, phi + 1.0) < 0.0);
  BOOST_TEST(goodman_bray::toe_force(s, phi - 1.0) > 0.0);
}

BOOST_AUTO_TEST_CASE(dda_critical_friction_angle_is_within_2_deg_of_limit_equilibrium) {
  const goodman_bray::Slope s;
  const double phi_le = goodman_bray::critical_friction_angle(s);
  // 3 s of motion: a failing slope moves metres, a stable one centimetres
  // (elastic and penalty settling of 40 m high blocks).
  // Either contact solve (docs/reference/contacts.md, "Contact solves").
  for (const auto solver : {core::ContactSolver::open_close, core::ContactSolver::newton}) {
    const double below = largest_displacement(s, phi_le - 2.0, 3.0, solver);
    const double above = largest_displacement(s, phi_le + 2.0, 3.0, solver);
    BOOST_TEST_MESSAGE((solver == core::ContactSolver::newton ? "newton" : "open-close")
                       << ": phi_LE - 2 deg: " << below << " m; phi_LE + 2 deg: " << above << " m");
    BOOST_TEST(below > 1.0);   // topples
    BOOST_TEST(above < 0.1);   // stands
  }
}

BOOST_AUTO_TEST_CASE(explicit_step_critical_friction_angle_is_within_three_quarters_of_a_degree_of_limit_equilibrium) {
  // The same slope taken by the explicit step (docs/reference/explicit-step.md): 0.5 deg below
  // the limit-equilibrium angle it topples (metres in 3 s), 0.75 deg above it it comes to rest
  // (no motion between 6 s and 10 s beyond a millimetre). Half a degree above it, it topples
  // as the implicit step's does (docs/notes/explicit-step.md, "Toppling"): neither step has
  // its critical angle within 0.5 deg of limit equilibrium on this slope.
  const goodman_bray::Slope s;
  const double phi_le = goodman_bray::critical_friction_angle(s);
  const auto expl = core::Integrator::explicit_step;
  const double below = largest_displacement(s, phi_le - 0.5, 3.0, core::ContactSolver::open_close, expl);
  const std::vector<double> above =
      largest_displacements(s, phi_le + 0.75, {6.0, 10.0}, core::ContactSolver::open_close, expl);
  BOOST_TEST_MESSAGE("explicit: phi_LE = " << phi_le << " deg; - 0.5 deg: " << below << " m at 3 s; + 0.75 deg: "
                                           << above[0] << " m at 6 s, " << above[1] << " m at 10 s");
  BOOST_TEST(below > 1.0);                          // topples
  BOOST_TEST(std::abs(above[1] - above[0]) < 1e-3);  // at rest
  BOOST_TEST(above[1] < 1.0);
}

BOOST_AUTO_TEST_SUITE_END()
