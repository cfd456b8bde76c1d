// `rheodda check`'s lines on a rock mass (describe_parts.hpp): what the cut gave
// (docs/guide/rockmass.md): block count, size distribution, joint sets, joint lengths.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "describe_parts.hpp"
#include "rheodda/scene/geometry.hpp"
#include "rheodda/scene/memory.hpp"

namespace rheodda::scene::detail {

std::string describe_rock_mass(const SceneDescription& s, const RockMassDescription& r) {
  const Units& u = s.units;
  std::string out;
  auto line = [&out](const std::string& t) { out += t + '\n'; };
  double region = std::abs(signed_area(r.region.outer));
  for (const auto& h : r.region.holes) region -= std::abs(signed_area(h));
  line(fmt::format("rock mass '{}': {} blocks ({} .. {}) cut from a region of {:g} {}^2 ({} vertices, {} holes), "
                   "material {}, seed {}",
                   r.name, r.block_count, r.block_count ? s.blocks[r.first_block].name : "-",
                   r.block_count ? s.blocks[r.first_block + r.block_count - 1].name : "-", region, u.length,
                   r.region.outer.size(), r.region.holes.size(), s.materials[r.material].name, r.seed));
  std::vector<double> areas;
  for (std::size_t i = r.first_block; i < r.first_block + r.block_count; ++i)
    areas.push_back(signed_area(s.blocks[i].polygon));
  std::sort(areas.begin(), areas.end());
  if (!areas.empty()) {
    auto q = [&](double f) { return areas[static_cast<std::size_t>(f * double(areas.size() - 1) + 0.5)]; };
    double sum = 0.0;
    for (double x : areas) sum += x;
    line(fmt::format("  block area [{}^2]: min {:.4g}, 10% {:.4g}, median {:.4g}, mean {:.4g}, 90% {:.4g}, max {:.4g}; "
                     "sum - region area: {:.2g} relative",
                     u.length, areas.front(), q(0.1), q(0.5), sum / double(areas.size()), q(0.9), areas.back(),
                     r.area_error));
  }
  line(fmt::format("  estimated before cutting: {:.3g} trace crossings, up to {:.3g} blocks, {} of memory",
                   r.estimate.crossings, r.estimate.pieces, format_bytes(r.estimate.bytes)));
  line(fmt::format("  slivers merged (sliver_area {:g} {}^2): {}; dead-end trace segments removed: {}",
                   r.sliver_area, u.length, r.merged_slivers, r.dangling_removed));
  if (r.extended_traces > 0)
    line(fmt::format("  traces extended so that every block is a simple polygon: {} ({} of them parallel to a "
                     "block's joints, from a hole no trace reached)",
                     r.extended_traces, r.added_traces));
  if (r.collapsed_blocks > 0)
    line(fmt::format("  blocks of rounding size dropped (vertices closer than 1e-9 of the region welded): {}",
                     r.collapsed_blocks));
  for (std::size_t k = 0; k < r.joint_sets.size(); ++k) {
    const auto& g = r.joint_sets[k];
    line(fmt::format("  joint set {}: dip {:g} deg to the {}, spacing {:g} {} ({}{}), {}{}; {} traces drawn",
                     s.joint_sets[g.tag].name, g.dip, g.dips_right ? "right" : "left", g.spacing, u.length,
                     rockmass::spacing_distribution_name(g.spacing_distribution),
                     g.spacing_deviation > 0.0 ? fmt::format(", deviation {:g}", g.spacing_deviation) : "",
                     g.trace_length ? fmt::format("trace_length {:g} {}, gap {:g} {} (persistence {:.3g})",
                                                  *g.trace_length, u.length, g.gap, u.length,
                                                  *g.trace_length / (*g.trace_length + g.gap))
                                    : std::string("persistent"),
                     g.dip_spread > 0.0 ? fmt::format(", dip_spread {:g} deg", g.dip_spread) : "",
                     r.traces_generated[k]));
  }
  if (!r.traces.empty()) line(fmt::format("  explicit traces: {}", r.traces.size()));
  for (const auto& [tag, length] : r.joint_length)
    line(fmt::format("  joint length in the blocks, {}: {:g} {}",
                     tag < 0 ? fmt::format("region boundary (joint set {})", s.joint_sets[r.boundary_joint_set].name)
                             : s.joint_sets[tag].name,
                     length, u.length));
  return out;
}

}  // namespace rheodda::scene::detail
