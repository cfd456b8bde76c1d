// `water:` of a scene file (docs/reference/scene-format.md, "water"; docs/reference/water.md): the
// water in the joints, a phreatic surface - a level or a polyline - constant or
// piecewise linear in time, and the water's unit weight.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rheodda/core/water.hpp"
#include "rheodda/scene/error.hpp"

namespace rheodda::scene {

struct SceneDescription;
struct Units;

/// `water: {unit_weight, level | surface | level_history | surface_history}`.
/// Its properties are the engine's WaterProperties (unit_weight), declared in
/// core/property_specs.hpp (the key of the same name; build_water hands them on whole).
struct WaterDescription : core::WaterProperties {
  /// Which key gave the surface (echoed as given).
  enum class Form { level, surface, level_history, surface_history };
  /// One time sample of the phreatic surface.
  struct Sample {
    double time = 0.0;   ///< [time]; 0 for `level` and `surface`
    double level = 0.0;  ///< the surface's height [length] (forms level and level_history)
    std::vector<std::array<double, 2>> surface;  ///< polyline (x, y), x strictly increasing [length]
                                                 ///< (forms surface and surface_history)
    SourceLocation where{};
  };
  Form form = Form::level;
  std::vector<Sample> history;  ///< >= 1 sample, times strictly increasing
  SourceLocation where{};
};

/// The engine's water (core/water.hpp): a level becomes a horizontal surface
/// over the blocks' x-range (held level beyond it).
core::Water build_water(const WaterDescription& water, const SceneDescription& scene);

/// `rheodda check`'s lines on the water (each ending with a newline).
std::string describe_water(const WaterDescription& water, const Units& units);

/// The scene has water at some time: a `water:`, or a stage's (docs/reference/stages.md);
/// its contacts.csv and contact frames then carry water_pressure.
bool scene_has_water(const SceneDescription& scene);

/// contacts.csv's water_pressure cell at the point p at time t, with its leading comma [stress].
std::string water_pressure_cell(const core::Water& water, const core::Vec2& p, double t);

}  // namespace rheodda::scene
