// The running-bond brick wall: the performance benchmark's scene (bench/contact_bench.cpp,
// docs/notes/performance.md) and the tests that run it (tests/contact/engine). nx x ny bricks
// 0.2 m x 0.1 m, every other course offset by half a brick with half bricks at its
// ends, on a fixed base (block 0, held at three vertices); E = 5 GPa, density
// 2600 kg/m^3, a dynamic analysis at dt = 1e-3 s. Units: m, N, s, Pa.
#pragma once

#include <vector>

#include "rheodda/core/defaults.hpp"
#include "rheodda/core/model.hpp"

namespace rheodda::models {

inline constexpr double kBrickWidth = 0.2;   ///< [m]
inline constexpr double kBrickHeight = 0.1;  ///< [m]

/// Counter-clockwise rectangle [x0, x1] x [y0, y1] [m].
inline std::vector<core::Vec2> rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

/// The wall; the allowed displacement per step max_displacement_ratio w0 is 1 mm (1 % of a brick's height)
/// at every size, so that the contact search distance 2.5 max_displacement_ratio w0 stays below the brick
/// size (Shi's g2 = 0.01 of a 10 m wall would search 0.26 m around 0.1 m bricks).
inline core::Model running_bond_wall(int nx, int ny, double poisson_ratio = 0.2) {
  core::Model m;
  core::Material rock;
  rock.density = 2600.0;     // [kg/m^3]
  rock.young_modulus = 5e9;  // [Pa]
  rock.poisson_ratio = poisson_ratio;
  m.materials = {rock};
  m.settings.dt = 1e-3;  // [s]
  m.settings.dynamic_ratio = 1.0;
  const double width = nx * kBrickWidth;
  m.settings.max_displacement_ratio = 1e-3 / core::half_model_size(width + 1.0, ny * kBrickHeight + 0.5);
  auto add = [&m](std::vector<core::Vec2> v) {
    core::BlockDef b;
    b.vertices = std::move(v);
    m.blocks.push_back(std::move(b));
  };
  add(rectangle(-0.5, -0.5, width + 0.5, 0.0));
  for (int k = 0; k < 3; ++k) m.fixed_points.push_back({0, m.blocks[0].vertices[k]});
  for (int j = 0; j < ny; ++j) {
    const double y0 = j * kBrickHeight, y1 = y0 + kBrickHeight;
    if (j % 2 == 0) {
      for (int i = 0; i < nx; ++i) add(rectangle(i * kBrickWidth, y0, (i + 1) * kBrickWidth, y1));
    } else {
      add(rectangle(0.0, y0, 0.5 * kBrickWidth, y1));
      for (int i = 0; i + 1 < nx; ++i) add(rectangle((i + 0.5) * kBrickWidth, y0, (i + 1.5) * kBrickWidth, y1));
      add(rectangle(width - 0.5 * kBrickWidth, y0, width, y1));
    }
  }
  return m;
}

}  // namespace rheodda::models
