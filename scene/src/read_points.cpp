// The `fixed_points:`, `loads:` and `measurement_points:` sections of a scene file.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <unordered_set>

#include "read_keys.hpp"
#include "scene_readers.hpp"
#include "rheodda/scene/geometry.hpp"

namespace rheodda::scene::detail {

/// Tolerance for "same place": a billionth of the model size [length].
double geometry_tolerance(const std::vector<BlockDescription>& blocks) {
  return std::max(1e-9 * 2.0 * half_model_size(blocks), std::numeric_limits<double>::min());
}

void read_force_or_history(const Ctx& ctx, const MapReader& m, const ForceOrHistory& keys,
                           std::vector<std::array<double, 3>>& history, const std::string& times) {
  YAML::Node f = m.find(keys.force), h = m.find(keys.history);
  if (f.IsDefined() == h.IsDefined())
    ctx.fail(m.node(), m.child(keys.force),
             fmt::format("give exactly one of force: [fx, fy] or history: [[t, fx, fy], ...]{}", times));
  if (!h.IsDefined()) return;  // `force` gave the one sample (its declaration, keys_points.cpp)
  if (!h.IsSequence() || h.size() == 0 || h.size() > kMaxSamples)
    ctx.fail(h, m.child(keys.history), "expected a list of [t, fx, fy] samples");
  history.clear();
  for (std::size_t k = 0; k < h.size(); ++k) {
    const std::string key = fmt::format("{}[{}]", m.child(keys.history), k);
    const auto v = numbers(ctx, h[k], key, 3, any("time, force, force"));
    if (v[0] < 0.0) ctx.fail(h[k], key, fmt::format("time {:g} is negative", v[0]));
    if (!history.empty() && v[0] <= history.back()[0])
      ctx.fail(h[k], key, fmt::format("times must increase strictly: {:g} after {:g}", v[0], history.back()[0]));
    history.push_back({v[0], v[1], v[2]});
  }
}

BlockPoint read_block_point(const Ctx& ctx, const MapReader& m, const PointOnBlock& keys, const SceneDescription& s,
                            double tol) {
  BlockPoint bp;
  bp.where = m.where();
  YAML::Node p = m.required(keys.point, "[x, y] [length]");
  bp.point = point(ctx, p, m.child(keys.point));
  if (YAML::Node v = m.find(keys.block); v.IsDefined()) {
    bp.block = resolve(ctx, v, m.child(keys.block), s.blocks, "block");
    if (!contains(s.blocks[bp.block].polygon, bp.point, tol))
      ctx.fail(p, m.child(keys.point),
               fmt::format("({:g}, {:g}) is not on block '{}'", bp.point[0], bp.point[1], s.blocks[bp.block].name));
    return bp;
  }
  std::vector<int> hits;
  for (std::size_t i = 0; i < s.blocks.size(); ++i)
    if (contains(s.blocks[i].polygon, bp.point, tol)) hits.push_back(static_cast<int>(i));
  if (hits.empty())
    ctx.fail(p, m.child(keys.point), fmt::format("({:g}, {:g}) lies on no block", bp.point[0], bp.point[1]));
  if (hits.size() > 1) {
    std::vector<std::string> names;
    for (int h : hits) names.push_back(s.blocks[h].name);
    ctx.fail(p, m.child(keys.point),
             fmt::format("({:g}, {:g}) lies on the boundary of several blocks ({}); say which with `block:`",
                         bp.point[0], bp.point[1], join(names)));
  }
  bp.block = hits.front();
  return bp;
}

void read_points(const Ctx& ctx, const MapReader& top, SceneDescription& s) {
  const double tol = geometry_tolerance(s.blocks);
  auto list = [&](KeyName k) {
    YAML::Node n = top.find(k);
    if (n.IsDefined() && !n.IsSequence() && !n.IsNull())
      ctx.fail(n, std::string(k.word()), fmt::format("expected a list, got {}", type_word(n)));
    return n;
  };
  // The optional `name` of a fixed point or load: what a stage removes it by (docs/reference/stages.md).
  auto check_name = [&](const MapReader& m, KeyName key, const std::string& name, const auto& earlier, auto name_of,
                        const char* what) {
    for (const auto& e : earlier)
      if (!name.empty() && name_of(e) == name)
        ctx.fail(m.find(key), m.child(key), fmt::format("{} '{}' is defined twice", what, name));
  };
  // Each list's declared keys (keys_points.cpp) first, then the point on its block.
  if (YAML::Node n = list(key::top::fixed_points); n.IsSequence())
    for (std::size_t i = 0; i < n.size(); ++i) {
      const MapReader m =
          declared_reader(ctx, n[i], fmt::format("fixed_points[{}]", i), fixed_point_keys(), "fixed_points");
      BlockPoint declared;
      read_declared(ctx, m, fixed_point_keys(), declared);
      check_name(m, key::fixed_point::name, declared.name, s.fixed_points, [](const BlockPoint& p) { return p.name; },
                 "fixed point");
      s.fixed_points.push_back(read_block_point(ctx, m, point_on_block<key::fixed_point>, s, tol));
      s.fixed_points.back().name = declared.name;
      s.fixed_points.back().hold = declared.hold;
    }
  if (YAML::Node n = list(key::top::loads); n.IsSequence())
    for (std::size_t i = 0; i < n.size(); ++i) {
      const MapReader m = declared_reader(ctx, n[i], fmt::format("loads[{}]", i), load_keys(), "loads");
      LoadDescription load;
      read_declared(ctx, m, load_keys(), load);  // name, force
      const std::string name = load.at.name;
      check_name(m, key::load::name, name, s.loads, [](const LoadDescription& l) { return l.at.name; }, "load");
      load.at = read_block_point(ctx, m, point_on_block<key::load>, s, tol);
      load.at.name = name;
      read_force_or_history(ctx, m, force_or_history<key::load>, load.history, "");
      s.loads.push_back(std::move(load));
    }
  if (YAML::Node n = list(key::top::measurement_points); n.IsSequence())
    for (std::size_t i = 0; i < n.size(); ++i) {
      const MapReader m = declared_reader(ctx, n[i], fmt::format("measurement_points[{}]", i),
                                          measurement_point_keys(), "measurement_points");
      MeasurementPoint mp;
      read_declared(ctx, m, measurement_point_keys(), mp);  // name
      check_name(m, key::measurement_point::name, mp.name, s.measurement_points,
                 [](const MeasurementPoint& p) { return p.name; }, "measurement point");
      mp.at = read_block_point(ctx, m, point_on_block<key::measurement_point>, s, tol);
      s.measurement_points.push_back(std::move(mp));
    }
}

}  // namespace rheodda::scene::detail
