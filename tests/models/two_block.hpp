// The seed's two-block shear creep scene (its Section 4; as
// tests/contact/engine/creep_scene.hpp): block A (w x w) on a fixed block B,
// the joint along A's base, for the tests and benches that run it through the
// engine (tests/accuracy/staged_two_block.hpp, bench/shear_creep_table1.cpp,
// bench/stability_map.cpp). Units: mm, N, h, MPa.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/model.hpp"

namespace rheodda::models {

inline std::vector<core::Vec2> rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

/// B = block 0 (3w x w, fixed by three fixed points), A = block 1 (w x w) on
/// it; static analysis without gravity at a fixed step dt [h]; no loads.
inline core::Model two_block_model(double w, double dt) {
  core::Model m;
  m.materials[0].young_modulus = 1e7;  // blocks 1e6 x stiffer than the joint [MPa]
  m.materials[0].density = 1e-12;      // no inertia at creep time scales [MPa h^2/mm^2]
  m.settings.dt = dt;
  m.settings.dynamic_ratio = 0.0;      // static analysis
  m.settings.gravity = {0.0, 0.0};
  core::BlockDef b, a;
  b.vertices = rect(-w, -w, 2 * w, 0.0);
  a.vertices = rect(0.0, 0.0, w, w);
  m.blocks = {b, a};
  for (int i = 0; i < 3; ++i) m.fixed_points.push_back({0, b.vertices[i]});
  return m;
}

/// The seed's joint between A and B: friction 60 deg (tan 60 = 1.73 exceeds tau/sigma of
/// every Table 1 row, so it never slides), normal stiffness 1e4 MPa/mm, the given law
/// (its E1 the shear spring).
inline contact::JointSet seed_joint(std::shared_ptr<const laws::ContactRheology> law) {
  contact::JointSet j;
  j.name = "joint";
  j.friction_angle = 60.0;    // [deg]
  j.normal_stiffness = 1e4;   // [MPa/mm]
  j.law = std::move(law);
  return j;
}

/// The engine on a two-block model with the seed's joint and `law`, each step's creep
/// integrated by `scheme` (unset: the law's automatic choice).
struct SeedJointRun {
  contact::ContactSystem contacts;
  core::ContactAdapter adapter;
  core::Engine engine;
  SeedJointRun(const core::Model& m, std::shared_ptr<const laws::ContactRheology> law,
               std::optional<laws::Scheme> scheme)
      : contacts({seed_joint(std::move(law))}, settings(m, scheme)), adapter(contacts), engine(m, adapter) {}
  static contact::ContactSettings settings(const core::Model& m, std::optional<laws::Scheme> scheme) {
    contact::ContactSettings s = core::contact_settings_for(m);
    s.scheme = scheme;
    return s;
  }
};

/// The joint's relative shear displacement along +x: mean over A's base contacts [mm].
inline double joint_shear(const contact::ContactSystem& cs) {
  double sum = 0.0;
  int n = 0;
  for (const auto& c : cs.contacts())
    if (c.key.vblock == 1) sum -= c.shear_displacement, ++n;
  return n ? sum / n : 0.0;
}

/// The joint's forces after a step, over A's base contacts.
struct JointForces {
  double largest_stress = 0.0;  ///< largest |shear force| / contact length [MPa]
  double shear_force = 0.0;     ///< summed shear force along +x (B's top edge runs in -x) [N/mm]
  double length = 0.0;          ///< summed contact length [mm]
};
inline JointForces joint_forces(const contact::ContactSystem& cs) {
  JointForces f;
  for (const contact::Contact& c : cs.contacts())
    if (c.key.vblock == 1) {
      f.largest_stress = std::max(f.largest_stress, std::abs(c.shear_force) / c.length);
      f.shear_force -= c.shear_force;
      f.length += c.length;
    }
  return f;
}

/// The growth of a creep scheme in the DDA step (the stability map, docs/notes/step-controls.md,
/// "Stability map"): the largest joint stress of step n relative to `scale`, watched over
/// `steps` steps; diverged once it exceeds `stop` x scale.
struct GrowthWatch {
  double growth = 0.0;         ///< largest stress / scale over the second half of the run, or at divergence [-]
  int diverged_at = 0;         ///< step at which it exceeded stop x scale, 0 if never [-]
  double amplification = 0.0;  ///< diverged: |joint shear force| of the last step / the one before [-]
  double previous = 0.0;       ///< joint shear force of the previous step [N/mm]
  /// Records step n of `steps`; true when the run has diverged (then stop stepping).
  bool diverged(int n, int steps, const JointForces& f, double scale, double stop) {
    if (f.largest_stress > stop * scale) {
      growth = f.largest_stress / scale;
      diverged_at = n;
      amplification = std::abs(f.shear_force / previous);
      return true;
    }
    previous = f.shear_force;
    if (n > steps / 2) growth = std::max(growth, f.largest_stress / scale);
    return false;
  }
};

}  // namespace rheodda::models
