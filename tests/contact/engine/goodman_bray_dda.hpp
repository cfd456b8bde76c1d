// The Goodman & Bray toppling slope (goodman_bray.hpp) as a DDA model: shared by
// tests/contact/engine/toppling_test.cpp and bench/toppling_probe.cpp, so that the
// measurements of docs/notes/explicit-step.md ("Toppling") are those of the test.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "goodman_bray.hpp"
#include "sim.hpp"

namespace rheodda::testing::goodman_bray {

/// The DDA model's controls; the defaults are the test's.
struct DdaOptions {
  double phi_deg = 40.0;  ///< friction angle of base and sides [deg]
  core::ContactSolver solver = core::ContactSolver::open_close;
  core::Integrator integrator = core::Integrator::implicit;
  double dt = 5e-3;             ///< step [s]
  double young_modulus = 1e10;  ///< of the blocks [Pa]
  double penalty_factor = 40.0;  ///< contact penalty / E (Sim's default)
  double explicit_safety = -1.0;   ///< < 0: the model's default
  double explicit_damping = -1.0;  ///< < 0: the model's default
  /// The contacts' stick rule (contact::ContactSettings::stick_keeps_force): false is Shi's (a
  /// contact that stops sliding locks with its shear spring unstretched), the default.
  bool stick_keeps_force = false;
};

/// Largest block displacement [m] at each of the `times` [s] (ascending) of dynamic DDA from
/// rest under sudden gravity. The model is built in the frame of the base steps (x' up the
/// steps, y' normal to them) with gravity tilted by the step dip: the same mechanics as the
/// rotated slope, with axis-aligned blocks. Density 2 500 kg/m^3.
inline std::vector<double> largest_displacements(const Slope& s, const DdaOptions& o, const std::vector<double>& times) {
  core::Model m;
  m.settings.dt = o.dt;
  m.settings.contact_solver = o.solver;
  m.settings.integrator = o.integrator;
  if (o.explicit_safety > 0.0) m.settings.explicit_safety = o.explicit_safety;
  if (o.explicit_damping >= 0.0) m.settings.explicit_damping = o.explicit_damping;
  const double a = deg(s.alpha_deg);
  m.settings.gravity = Vec2(-9.81 * std::sin(a), -9.81 * std::cos(a));
  m.materials[0].density = 2500.0;  // [kg/m^3]
  m.materials[0].young_modulus = o.young_modulus;
  // Fixed stepped base: block n stands on the step at height (n - 1) b.
  std::vector<Vec2> base{{0.0, -20.0}, {s.blocks * s.dx, -20.0}};
  for (int n = s.blocks; n >= 1; --n) {
    base.emplace_back(n * s.dx, (n - 1) * s.b);
    base.emplace_back((n - 1) * s.dx, (n - 1) * s.b);
  }
  add_fixed(m, base);
  for (int n = 1; n <= s.blocks; ++n)
    m.blocks.push_back(block(rect((n - 1) * s.dx, (n - 1) * s.b, n * s.dx, (n - 1) * s.b + s.height(n))));
  contact::ContactSettings settings = core::contact_settings_for(m, o.penalty_factor);
  settings.stick_keeps_force = o.stick_keeps_force;
  Sim sim(std::move(m), {joint(o.phi_deg)}, settings);
  std::vector<Vec2> c0;
  for (int b = 0; b <= s.blocks; ++b) c0.push_back(sim.engine.centroid(b));
  std::vector<double> out;
  for (const double t : times) {
    sim.engine.run_until(t);
    double largest = 0.0;
    for (int b = 1; b <= s.blocks; ++b) largest = std::max(largest, sim.engine.point_displacement(b, c0[b]).norm());
    out.push_back(largest);
  }
  return out;
}

}  // namespace rheodda::testing::goodman_bray
