// The `blocks:` section of a scene file: polygons, rectangles, grids and their edges' joint sets.
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
#include "rheodda/scene/memory.hpp"

namespace rheodda::scene::detail {

std::vector<int> edge_sets(const Ctx& ctx, const MapReader& m, const SceneDescription& s,
                           std::size_t edges, const char* order) {
  YAML::Node all = m.find(key::block::joint_set);
  YAML::Node each = m.find(key::block::edge_joint_sets);
  if (all.IsDefined() && each.IsDefined())
    ctx.fail(each, m.child(key::block::edge_joint_sets), "give either joint_set (every edge) or edge_joint_sets, not both");
  if (each.IsDefined()) {
    if (!each.IsSequence() || each.size() != edges)
      ctx.fail(each, m.child(key::block::edge_joint_sets),
               fmt::format("expected a list of {} joint set names, one per edge ({})", edges, order));
    std::vector<int> out;
    for (std::size_t k = 0; k < edges; ++k)
      out.push_back(resolve(ctx, each[k], fmt::format("{}[{}]", m.child(key::block::edge_joint_sets), k),
                            s.joint_sets, "joint set"));
    return out;
  }
  int js = 0;
  if (all.IsDefined())
    js = resolve(ctx, all, m.child(key::block::joint_set), s.joint_sets, "joint set");
  else if (s.joint_sets.size() != 1)
    ctx.fail(m.node(), m.child(key::block::joint_set),
             "missing key 'joint_set' (or edge_joint_sets): the scene has several joint sets");
  return std::vector<int>(edges, js);
}

void read_blocks(const Ctx& ctx, const YAML::Node& n, SceneDescription& s, std::vector<RawBlock>& raw) {
  if (!n.IsSequence() || n.size() == 0)
    ctx.fail(n, "blocks", "expected a list of blocks, e.g. `- {rectangle: {x: 0, y: 0, width: 1, height: 1}}`");
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string path = fmt::format("blocks[{}]", i);
    const MapReader m = declared_reader(ctx, n[i], path, block_keys(), "blocks");
    BlockDescription b;
    b.where = m.where();
    read_declared(ctx, m, block_keys(), b);  // name, fixed, initial_stress, initial_velocity (keys_blocks.cpp)
    if (YAML::Node v = m.find(key::block::material); v.IsDefined())
      b.material = resolve(ctx, v, m.child(key::block::material), s.materials, "material");
    else if (s.materials.size() != 1)
      ctx.fail(m.node(), m.child(key::block::material), "missing key 'material': the scene has several materials");
    if (YAML::Node v = m.find(key::block::initial_velocity); v.IsDefined() &&
        s.analysis.type == AnalysisType::static_analysis && b.initial_velocity != std::array<double, 3>{0.0, 0.0, 0.0})
      ctx.fail(v, m.child(key::block::initial_velocity),
               "a static analysis carries no velocity; initial_velocity needs `analysis: {type: dynamic}`");
    const std::string name = b.name;

    const int shapes =
        int(m.has(key::block::polygon)) + int(m.has(key::block::rectangle)) + int(m.has(key::block::grid));
    if (shapes != 1)
      ctx.fail(m.node(), path, shapes == 0 ? "missing the shape: give one of polygon, rectangle, grid"
                                           : "give only one of polygon, rectangle, grid");
    if (YAML::Node v = m.find(key::block::polygon); v.IsDefined()) {
      if (!v.IsSequence())
        ctx.fail(v, m.child(key::block::polygon), fmt::format("expected a list of [x, y] vertices, got {}", type_word(v)));
      if (v.size() > kMaxVertices)
        ctx.fail(v, m.child(key::block::polygon), fmt::format("more than {} vertices", kMaxVertices));
      for (std::size_t k = 0; k < v.size(); ++k)
        b.polygon.push_back(point(ctx, v[k], fmt::format("{}[{}]", m.child(key::block::polygon), k)));
      if (b.polygon.size() < 3)
        ctx.fail(v, m.child(key::block::polygon),
                 fmt::format("has {} vertices; a polygon needs at least 3", b.polygon.size()));
      b.edge_joint_set = edge_sets(ctx, m, s, b.polygon.size(), "edge k runs from vertex k to k+1");
      b.name = name;
      raw.push_back({b, path, n[i], v});
      continue;
    }
    const bool grid = m.has(key::block::grid);
    const KeyName shape_key = grid ? key::block::grid : key::block::rectangle;
    YAML::Node g = m.find(shape_key);
    const auto& shape_keys = grid ? grid_keys() : rectangle_keys();
    const MapReader r =
        declared_reader(ctx, g, m.child(shape_key), shape_keys, grid ? "blocks.grid" : "blocks.rectangle");
    BlockShape shape;
    read_declared(ctx, r, shape_keys, shape);  // keys_blocks.cpp
    const double x = shape.x, y = shape.y, w = shape.width, h = shape.height;
    const double angle = shape.angle;  // counter-clockwise rotation about (x, y) [deg]
    const double ca = std::cos(angle * std::numbers::pi / 180.0), sa = std::sin(angle * std::numbers::pi / 180.0);
    auto place = [&](double ls, double lt) -> Point { return {x + ca * ls - sa * lt, y + sa * ls + ca * lt}; };
    const int cols = shape.columns, rows = shape.rows;  // 1 and 1 for a rectangle
    if (grid && std::size_t(cols) * std::size_t(rows) + raw.size() > kMaxBlocks)
      ctx.fail(g, m.child(shape_key), fmt::format("more than {} blocks in the scene", kMaxBlocks));
    b.edge_joint_set = edge_sets(ctx, m, s, 4, "bottom, right, top, left");
    for (int row = 0; row < rows; ++row)
      for (int col = 0; col < cols; ++col) {
        BlockDescription c = b;
        const double s0 = col * w, t0 = row * h;
        c.polygon = {place(s0, t0), place(s0 + w, t0), place(s0 + w, t0 + h), place(s0, t0 + h)};
        c.name = grid ? fmt::format("{}.r{}.c{}", name.empty() ? fmt::format("grid{}", i + 1) : name,
                                    row + 1, col + 1)
                      : name;
        raw.push_back({c, path, n[i], g});
      }
  }
}

}  // namespace rheodda::scene::detail
