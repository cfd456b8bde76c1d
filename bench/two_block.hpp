// The seed's two-block shear creep scene (its Section 4; as
// tests/contact/engine/creep_scene.hpp): block A (w x w) on a fixed block B,
// the joint along A's base, for the benches that run it through the engine.
// Units: mm, N, h, MPa.
#pragma once

#include <vector>

#include "rheodda/core/model.hpp"

namespace rheodda::bench {

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

}  // namespace rheodda::bench
