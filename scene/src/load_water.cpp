// The `water:` section of a scene file (docs/reference/scene-format.md, "water";
// docs/reference/water.md): the water's unit weight and the phreatic surface, one of
//   level: h                                    a horizontal surface [length]
//   surface: [[x, y], ...]                      a polyline, x strictly increasing [length]
//   level_history: [[t, h], ...]                a level piecewise linear in time
//   surface_history: [{time: t, surface: [[x, y], ...]}, ...]
// Every surface spans the blocks' x-range at the start (else it would leave part
// of the model without a defined water table); times increase strictly.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <limits>

#include "read_keys.hpp"
#include "scene_readers.hpp"

namespace rheodda::scene::detail {

namespace {

/// The blocks' x-range at the start [length].
std::pair<double, double> x_range(const SceneDescription& s) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& b : s.blocks)
    for (const Point& p : b.polygon) lo = std::min(lo, p[0]), hi = std::max(hi, p[0]);
  return {lo, hi};
}

/// `[[x, y], ...]`: >= 2 points, x strictly increasing, spanning the blocks' x-range.
std::vector<Point> read_surface(const Ctx& ctx, const YAML::Node& n, const std::string& key,
                                const SceneDescription& s) {
  if (!n.IsSequence() || n.size() < 2 || n.size() > kMaxVertices)
    ctx.fail(n, key,
             fmt::format("expected a list of 2 to {} points [[x, y], ...] [length], got {}", kMaxVertices,
                         n.IsSequence() ? fmt::format("{} items", n.size()) : std::string(type_word(n))));
  std::vector<Point> out;
  for (std::size_t k = 0; k < n.size(); ++k) {
    const std::string item = fmt::format("{}[{}]", key, k);
    const Point p = point(ctx, n[k], item);
    if (!out.empty() && !(p[0] > out.back()[0]))
      ctx.fail(n[k], item,
               fmt::format("x must increase strictly along the surface: {:g} after {:g} (the water table is a "
                           "height over x)",
                           p[0], out.back()[0]));
    out.push_back(p);
  }
  const auto [lo, hi] = x_range(s);
  if (out.front()[0] > lo || out.back()[0] < hi)
    ctx.fail(n, key,
             fmt::format("the surface spans x = {:g} .. {:g} {}, not the whole model (its blocks span x = {:g} .. "
                         "{:g}): extend it across the model",
                         out.front()[0], out.back()[0], s.units.length, lo, hi));
  return out;
}

/// The time t of the next sample of a history (at `n`, named `key`): >= 0 and
/// after the previous sample's.
double sample_time(const Ctx& ctx, const YAML::Node& n, const std::string& key, double t,
                   const WaterDescription& w) {
  if (t < 0.0) ctx.fail(n, key, fmt::format("time {:g} is negative", t));
  if (!w.history.empty() && !(t > w.history.back().time))
    ctx.fail(n, key, fmt::format("times must increase strictly: {:g} after {:g}", t, w.history.back().time));
  return t;
}

}  // namespace

WaterDescription read_water(const Ctx& ctx, const YAML::Node& n, const SceneDescription& s, const std::string& path) {
  const MapReader m = declared_reader(ctx, n, path, water_keys(), "water");
  WaterDescription w;
  w.where = m.where();
  read_declared(ctx, m, water_keys(), w);  // unit_weight, level (keys_water.cpp)
  int given = 0;
  for (const KeyName f :
       {key::water::level, key::water::surface, key::water::level_history, key::water::surface_history})
    given += m.has(f) ? 1 : 0;
  if (given != 1)
    ctx.fail(m.node(), path,
             given == 0 ? "missing the phreatic surface: give one of level, surface, level_history, surface_history"
                        : "give only one of level, surface, level_history, surface_history");
  if (const YAML::Node level = m.find(key::water::level); level.IsDefined()) {
    w.history.front().where = location(level);  // the one sample, read with the declared keys
  } else if (const YAML::Node surface = m.find(key::water::surface); surface.IsDefined()) {
    w.form = WaterDescription::Form::surface;
    WaterDescription::Sample smp;
    smp.surface = read_surface(ctx, surface, m.child(key::water::surface), s);
    smp.where = location(surface);
    w.history.push_back(smp);
  } else if (YAML::Node v = m.find(key::water::level_history); v.IsDefined()) {
    w.form = WaterDescription::Form::level_history;
    if (!v.IsSequence() || v.size() == 0 || v.size() > kMaxSamples)
      ctx.fail(v, m.child(key::water::level_history), "expected a list of [t, level] samples [time, length]");
    for (std::size_t k = 0; k < v.size(); ++k) {
      const std::string key = fmt::format("{}[{}]", m.child(key::water::level_history), k);
      const auto x = numbers(ctx, v[k], key, 2, any("time, length"));
      WaterDescription::Sample smp;
      smp.time = sample_time(ctx, v[k], key, x[0], w);
      smp.level = x[1];
      smp.where = location(v[k]);
      w.history.push_back(smp);
    }
  } else {
    const YAML::Node h = m.find(key::water::surface_history);
    w.form = WaterDescription::Form::surface_history;
    if (!h.IsSequence() || h.size() == 0 || h.size() > kMaxSamples)
      ctx.fail(h, m.child(key::water::surface_history), "expected a list of {time, surface} samples");
    for (std::size_t k = 0; k < h.size(); ++k) {
      const MapReader sm = declared_reader(ctx, h[k], fmt::format("{}[{}]", m.child(key::water::surface_history), k),
                                           water_sample_keys(), "water.surface_history");
      WaterDescription::Sample smp;
      read_declared(ctx, sm, water_sample_keys(), smp);  // time
      smp.time = sample_time(ctx, sm.find(key::surface_sample::time), sm.child(key::surface_sample::time), smp.time, w);
      smp.surface = read_surface(ctx, required_key(sm, water_sample_keys(), key::surface_sample::surface),
                                 sm.child(key::surface_sample::surface), s);
      smp.where = sm.where();
      w.history.push_back(smp);
    }
  }
  return w;
}

}  // namespace rheodda::scene::detail
