// The geometry checks of a scene's blocks, after they are read (simple polygons, no overlaps).
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <unordered_set>

#include "scene_readers.hpp"
#include "rheodda/scene/geometry.hpp"
#include "rheodda/scene/memory.hpp"

namespace rheodda::scene::detail {

void check_geometry(const Ctx& ctx, std::vector<RawBlock>& raw, SceneDescription& s) {
  std::vector<BlockDescription> blocks;
  for (const auto& r : raw) blocks.push_back(r.block);
  // A block with coordinates that overflow, or far from all others (a typo), is
  // named before its size sets the tolerance every other block is checked with.
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (auto defect = coordinate_defect(raw[i].block.polygon))
      ctx.fail(raw[i].geometry_node, raw[i].path + ".polygon",
               fmt::format("block '{}' {}", raw[i].block.name.empty() ? fmt::format("block{}", i + 1) : raw[i].block.name,
                           *defect));
  if (const auto stray = stray_block(blocks, 1e6)) {
    auto name = [&](std::size_t i) {
      return raw[i].block.name.empty() ? fmt::format("block{}", i + 1) : raw[i].block.name;
    };
    const auto& r = raw[stray->first];
    ctx.fail(r.geometry_node, r.path + ".polygon",
             raw.size() == 2
                 ? fmt::format("blocks '{}' and '{}' lie {:g} {} apart, more than 1e6 times the median block size: "
                               "are their coordinates right?",
                               name(0), name(1), stray->second, s.units.length)
                 : fmt::format("block '{}' lies {:g} {} from all the other blocks, more than 1e6 times the median "
                               "block size: are its coordinates right?",
                               name(stray->first), stray->second, s.units.length));
  }
  const double tol = geometry_tolerance(blocks);
  std::unordered_set<std::string> names;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    BlockDescription& b = raw[i].block;
    if (b.name.empty()) b.name = fmt::format("block{}", i + 1);
    if (!names.insert(b.name).second)
      ctx.fail(raw[i].node, raw[i].path + ".name", fmt::format("block name '{}' is used twice", b.name));
    if (auto defect = polygon_defect(b.polygon, tol)) {
      if (raw[i].path == "rock_mass") {
        // A generated block has no place in the file: say where it lies and why.
        double x = 0.0, y = 0.0;
        for (const Point& p : b.polygon) x += p[0], y += p[1];
        x /= static_cast<double>(b.polygon.size()), y /= static_cast<double>(b.polygon.size());
        ctx.fail(raw[i].geometry_node, "rock_mass.region",
                 fmt::format("the cut leaves a needle DDA cannot model at ({:g}, {:g}): the block there {}; two "
                             "traces cross at a grazing angle (below about 1e-7 rad) there: change the seed or the "
                             "joint sets (docs/guide/rockmass.md, \"Limits\")",
                             x, y, *defect));
      }
      ctx.fail(raw[i].geometry_node, raw[i].path + ".polygon", fmt::format("block '{}' {}", b.name, *defect));
    }
    if (signed_area(b.polygon) < 0.0) {
      // Clockwise input: reverse to counter-clockwise. New edge k (v'_k -> v'_k+1) is
      // old edge n-2-k (mod n), so the edge joint sets follow their edges.
      const std::size_t n = b.polygon.size();
      std::vector<Point> p(n);
      std::vector<int> e(n);
      for (std::size_t k = 0; k < n; ++k) {
        p[k] = b.polygon[n - 1 - k];
        e[k] = b.edge_joint_set[(2 * n - 2 - k) % n];
      }
      b.polygon = std::move(p);
      b.edge_joint_set = std::move(e);
    }
    blocks[i] = b;
  }
  const auto overlaps = overlapping_blocks(blocks, tol);
  if (!overlaps.empty()) {
    const auto [i, j] = overlaps.front();
    ctx.fail(raw[j].node, raw[j].path,
             fmt::format("blocks '{}' and '{}' overlap at the start (blocks may touch, not overlap)",
                         blocks[i].name, blocks[j].name));
  }
  s.blocks = std::move(blocks);
}

}  // namespace rheodda::scene::detail
