// A scene's `water:` into the engine's model, `rheodda check` and contacts.csv
// (water.hpp; docs/reference/water.md); summary.json's "water" is scene_json.cpp's.
#include "rheodda/scene/water.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

namespace {

const char* form_name(WaterDescription::Form f) {
  switch (f) {
    case WaterDescription::Form::level: return "level";
    case WaterDescription::Form::surface: return "surface";
    case WaterDescription::Form::level_history: return "level_history";
    case WaterDescription::Form::surface_history: return "surface_history";
  }
  return "?";
}

bool is_level(WaterDescription::Form f) {
  return f == WaterDescription::Form::level || f == WaterDescription::Form::level_history;
}

}  // namespace

core::Water build_water(const WaterDescription& water, const SceneDescription& scene) {
  core::Water w;
  static_cast<core::WaterProperties&>(w) = water;  // the declared properties (core/property_specs.hpp), whole
  // A level: a horizontal line over the blocks' x-range widened by that range on
  // each side (the engine holds it level beyond its ends anyway), so that it still
  // spans the blocks where they have moved when a stage brings it in.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& b : scene.blocks)
    for (const auto& p : b.polygon) lo = std::min(lo, p[0]), hi = std::max(hi, p[0]);
  const double margin = std::max(hi - lo, 1.0);
  lo -= margin;
  hi += margin;
  for (const auto& smp : water.history) {
    core::WaterSurface s;
    s.time = smp.time;
    if (is_level(water.form)) {
      s.points = {{lo, smp.level}, {hi, smp.level}};
    } else {
      for (const auto& p : smp.surface) s.points.emplace_back(p[0], p[1]);
    }
    w.history.push_back(std::move(s));
  }
  return w;
}

std::string describe_water(const WaterDescription& water, const Units& u) {
  // The declared keys (keys_water.cpp) but the surface's, described below by its form.
  std::string out = fmt::format(
      "water: {}, {}",
      key_values_text(keys_except(water_keys(), {"level", "surface", "level_history", "surface_history"}), "water",
                      water, u),
      form_name(water.form));
  const auto& h = water.history;
  switch (water.form) {
    case WaterDescription::Form::level:
      out += fmt::format(" {:g} {}\n", h[0].level, u.length);
      break;
    case WaterDescription::Form::surface:
      out += fmt::format(" of {} points, x = {:g} .. {:g} {}\n", h[0].surface.size(), h[0].surface.front()[0],
                         h[0].surface.back()[0], u.length);
      break;
    case WaterDescription::Form::level_history:
      out += fmt::format(" of {} samples, t = {:g} .. {:g} {}, level {:g} .. {:g} {}\n", h.size(), h.front().time,
                         h.back().time, u.time, h.front().level, h.back().level, u.length);
      break;
    case WaterDescription::Form::surface_history:
      out += fmt::format(" of {} surfaces, t = {:g} .. {:g} {}\n", h.size(), h.front().time, h.back().time, u.time);
      break;
  }
  out += "  pressure gamma_w (h - y) on every block edge below the surface; contacts carry the effective normal force "
         "(docs/reference/water.md)\n";
  return out;
}

std::string water_pressure_cell(const core::Water& water, const core::Vec2& p, double t) {
  return fmt::format(",{:.10g}", core::water_pressure(water, p, t));
}

bool scene_has_water(const SceneDescription& scene) {
  if (scene.water) return true;
  for (const StageDescription& st : scene.stages)
    if (st.water) return true;
  return false;
}

}  // namespace rheodda::scene
