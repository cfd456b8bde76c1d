// The `rock_mass:` section of a scene file: joint sets generated and cut into blocks (docs/guide/rockmass.md).
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

/// `rock_mass:` (docs/guide/rockmass.md): reads the region, the joint sets' statistics and the
/// explicit traces, generates and cuts (rockmass::generate_traces, cut_blocks) and
/// appends the blocks to `raw`; they are checked with the hand-written ones.
void read_rock_mass(const Ctx& ctx, const YAML::Node& n, SceneDescription& s, std::vector<RawBlock>& raw) {
  const MapReader m = declared_reader(ctx, n, "rock_mass", rock_mass_keys(), "rock_mass");
  RockMassDescription rm;
  rm.where = m.where();
  read_declared(ctx, m, rock_mass_keys(), rm);  // name, seed, sliver_area (keys_blocks.cpp)
  if (YAML::Node v = m.find(key::rock_mass::material); v.IsDefined())
    rm.material = resolve(ctx, v, m.child(key::rock_mass::material), s.materials, "material");
  else if (s.materials.size() != 1)
    ctx.fail(m.node(), m.child(key::rock_mass::material), "missing key 'material': the scene has several materials");
  const YAML::Node region = required_key(m, rock_mass_keys(), key::rock_mass::region);
  rm.region.outer = polygon_points(ctx, region, m.child(key::rock_mass::region));
  if (auto defect = coordinate_defect(rm.region.outer))
    ctx.fail(region, m.child(key::rock_mass::region), "the region " + *defect);
  rockmass::Box box{rm.region.outer[0][0], rm.region.outer[0][1], rm.region.outer[0][0], rm.region.outer[0][1]};
  for (const Point& p : rm.region.outer)
    box = {std::min(box.x0, p[0]), std::min(box.y0, p[1]), std::max(box.x1, p[0]), std::max(box.y1, p[1])};
  const double tol = std::max(1e-9 * std::hypot(box.x1 - box.x0, box.y1 - box.y0), std::numeric_limits<double>::min());
  if (auto defect = polygon_defect(rm.region.outer, tol))
    ctx.fail(region, m.child(key::rock_mass::region), "the region " + *defect);
  if (YAML::Node h = m.find(key::rock_mass::holes); h.IsDefined()) {
    if (!h.IsSequence())
      ctx.fail(h, m.child(key::rock_mass::holes), fmt::format("expected a list of polygons, got {}", type_word(h)));
    for (std::size_t k = 0; k < h.size(); ++k) {
      const std::string key = fmt::format("{}[{}]", m.child(key::rock_mass::holes), k);
      auto hole = polygon_points(ctx, h[k], key);
      if (auto defect = polygon_defect(hole, tol)) ctx.fail(h[k], key, "the hole " + *defect);
      for (const Point& p : hole)
        if (!contains(rm.region.outer, p, tol) || boundary_distance(rm.region.outer, p) <= tol)
          ctx.fail(h[k], key, fmt::format("vertex ({:g}, {:g}) of the hole is not strictly inside the region", p[0], p[1]));
      for (const Point& p : rm.region.outer)
        if (contains(hole, p, tol))
          ctx.fail(h[k], key, fmt::format("the hole covers the region's vertex ({:g}, {:g})", p[0], p[1]));
      for (std::size_t j = 0; j < rm.region.holes.size(); ++j) {
        bool touch = interiors_overlap(hole, rm.region.holes[j], tol);
        for (const Point& p : hole) touch = touch || contains(rm.region.holes[j], p, tol);
        for (const Point& p : rm.region.holes[j]) touch = touch || contains(hole, p, tol);
        if (touch) ctx.fail(h[k], key, fmt::format("holes {} and {} overlap or touch", j, k));
      }
      rm.region.holes.push_back(std::move(hole));
    }
  }
  if (YAML::Node v = m.find(key::rock_mass::boundary_joint_set); v.IsDefined())
    rm.boundary_joint_set = resolve(ctx, v, m.child(key::rock_mass::boundary_joint_set), s.joint_sets, "joint set");
  else if (s.joint_sets.size() != 1)
    ctx.fail(m.node(), m.child(key::rock_mass::boundary_joint_set),
             "missing key 'boundary_joint_set' (the joint set of the edges on the region's boundary): the scene "
             "has several joint sets");
  auto list = [&](KeyName k) {
    YAML::Node v = m.find(k);
    if (v.IsDefined() && !v.IsSequence())
      ctx.fail(v, m.child(k), fmt::format("expected a list of maps, got {}", type_word(v)));
    return v;
  };
  std::vector<rockmass::Trace> traces;
  std::vector<std::pair<std::size_t, std::size_t>> set_traces;  // per joint set: its range in `traces`
  if (YAML::Node sets = list(key::rock_mass::joint_sets); sets.IsDefined())
    for (std::size_t i = 0; i < sets.size(); ++i) {
      const MapReader j = declared_reader(ctx, sets[i], fmt::format("{}[{}]", m.child(key::rock_mass::joint_sets), i),
                                          rock_mass_joint_set_keys(), "rock_mass.joint_sets");
      rockmass::JointSetGeneration g;
      read_declared(ctx, j, rock_mass_joint_set_keys(), g);  // keys_blocks.cpp
      g.tag = resolve(ctx, required_key(j, rock_mass_joint_set_keys(), key::rock_mass_joint_set::joint_set),
                      j.child(key::rock_mass_joint_set::joint_set), s.joint_sets, "joint set");
      const bool deviation = g.spacing_distribution == rockmass::SpacingDistribution::normal ||
                             g.spacing_distribution == rockmass::SpacingDistribution::log_normal;
      if (YAML::Node v = j.find(key::rock_mass_joint_set::spacing_deviation); v.IsDefined() && !deviation)
        ctx.fail(v, j.child(key::rock_mass_joint_set::spacing_deviation),
                 fmt::format("a {} spacing has no deviation; spacing_deviation applies to spacing_distribution "
                             "normal or log-normal",
                             rockmass::spacing_distribution_name(g.spacing_distribution)));
      else if (!v.IsDefined() && deviation)
        ctx.fail(j.node(), j.child(key::rock_mass_joint_set::spacing_deviation),
                 fmt::format("missing key 'spacing_deviation' (standard deviation of a {} spacing [length])",
                             rockmass::spacing_distribution_name(g.spacing_distribution)));
      YAML::Node length = j.find(key::rock_mass_joint_set::trace_length), gap = j.find(key::rock_mass_joint_set::gap);
      if (length.IsDefined() != gap.IsDefined())
        ctx.fail(length.IsDefined() ? length : gap,
                 j.child(length.IsDefined() ? key::rock_mass_joint_set::gap : key::rock_mass_joint_set::trace_length),
                 "give trace_length and gap together (non-persistent joints), or neither (persistent joints)");
      // Lines across the region: its box's diagonal over the smallest likely spacing.
      const double lines = std::hypot(box.x1 - box.x0, box.y1 - box.y0) / g.spacing;
      if (lines > 1e6)
        ctx.fail(j.find(key::rock_mass_joint_set::spacing), j.child(key::rock_mass_joint_set::spacing),
                 fmt::format("spacing {:g} gives about {:.3g} joints across the region (more than 1e6)", g.spacing, lines));
      std::vector<rockmass::Trace> t;
      try {
        t = rockmass::generate_traces(g, {box.x0, box.y0, box.x1, box.y1}, rm.seed, static_cast<int>(i));
      } catch (const std::invalid_argument& e) {
        ctx.fail(j.node(), j.child(key::rock_mass_joint_set::spacing), e.what());
      }
      if (traces.size() + t.size() > rockmass::kMaxTraces)
        ctx.fail(j.node(), j.child(key::rock_mass_joint_set::spacing),
                 "the joint sets give more than 2e6 traces: larger spacing or fewer sets");
      set_traces.push_back({traces.size(), traces.size() + t.size()});
      traces.insert(traces.end(), t.begin(), t.end());
      rm.joint_sets.push_back(g);
    }
  if (YAML::Node list_t = list(key::rock_mass::traces); list_t.IsDefined())
    for (std::size_t i = 0; i < list_t.size(); ++i) {
      const MapReader j = declared_reader(ctx, list_t[i], fmt::format("{}[{}]", m.child(key::rock_mass::traces), i),
                                          rock_mass_trace_keys(), "rock_mass.traces");
      rockmass::Trace t;
      read_declared(ctx, j, rock_mass_trace_keys(), t);  // from, to (keys_blocks.cpp)
      t.tag = resolve(ctx, required_key(j, rock_mass_trace_keys(), key::trace::joint_set),
                      j.child(key::trace::joint_set), s.joint_sets, "joint set");
      if (t.a == t.b) ctx.fail(j.find(key::trace::to), j.child(key::trace::to), "the trace ends where it starts");
      rm.traces.push_back(t);
      traces.push_back(t);
    }
  // What the cut will cost, before cutting: a spacing of millimetres over a slope
  // would ask for 1e9 blocks and more memory than the machine has.
  {
    const rockmass::CutEstimate e = rm.estimate = rockmass::estimate_cut(rm.region, traces);
    // Located at the joint set that draws the most traces (or the explicit traces).
    YAML::Node at = m.find(key::rock_mass::traces);
    std::string key = m.child(key::rock_mass::traces);
    std::size_t most = 0;
    for (std::size_t i = 0; i < set_traces.size(); ++i)
      if (const std::size_t k = set_traces[i].second - set_traces[i].first; k >= most) {
        most = k;
        at = list(key::rock_mass::joint_sets)[i]["spacing"];
        key = fmt::format("{}[{}].spacing", m.child(key::rock_mass::joint_sets), i);
      }
    if (!at.IsDefined()) at = n, key = "rock_mass";
    const std::string what =
        fmt::format("the traces ({} of them) cross about {:.3g} times and would cut the region into up to {:.3g} "
                    "blocks",
                    traces.size(), e.crossings, e.pieces);
    if (e.pieces > 10.0 * static_cast<double>(kMaxBlocks))
      ctx.fail(at, key, fmt::format("{}; a scene holds at most {} blocks: a larger spacing, shorter traces or a "
                                    "smaller region",
                                    what, kMaxBlocks));
    if (const auto available = available_memory(); available && e.bytes > *available)
      ctx.fail(at, key, fmt::format("{}; the cut would need about {} of memory, {} is available: a larger spacing, "
                                    "shorter traces or a smaller region",
                                    what, format_bytes(e.bytes), format_bytes(*available)));
  }
  rockmass::CutResult cut;
  try {
    cut = rockmass::cut_blocks(rm.region, traces, {rm.sliver_area});
  } catch (const rockmass::CutError& e) {
    ctx.fail(region, m.child(key::rock_mass::region), e.what());
  }
  for (const auto& [first, last] : set_traces)
    rm.traces_generated.push_back(static_cast<std::size_t>(
        std::count(cut.trace_in_region.begin() + static_cast<long>(first),
                   cut.trace_in_region.begin() + static_cast<long>(last), 1)));
  if (cut.blocks.size() + raw.size() > kMaxBlocks)
    ctx.fail(n, "rock_mass", fmt::format("the cut gives {} blocks; more than {} blocks in the scene",
                                         cut.blocks.size(), kMaxBlocks));
  rm.first_block = raw.size();
  rm.block_count = cut.blocks.size();
  rm.joint_length = cut.joint_length;
  rm.merged_slivers = cut.merged_slivers;
  rm.dangling_removed = cut.dangling_removed;
  rm.extended_traces = cut.extended_traces;
  rm.added_traces = cut.added_traces;
  rm.collapsed_blocks = cut.collapsed_blocks;
  rm.area_error = cut.area_error;
  for (std::size_t k = 0; k < cut.blocks.size(); ++k) {
    rockmass::Block& c = cut.blocks[k];
    BlockDescription b;
    b.name = fmt::format("{}.{}", rm.name, k + 1);
    b.material = rm.material;
    b.where = rm.where;
    std::vector<bool> on_boundary;
    for (std::size_t e = 0; e < c.polygon.size(); ++e) {
      b.polygon.push_back({c.polygon[e][0], c.polygon[e][1]});
      on_boundary.push_back(c.edge_tag[e] == rockmass::kBoundaryTag);
      b.edge_joint_set.push_back(on_boundary.back() ? rm.boundary_joint_set : c.edge_tag[e]);
    }
    rm.edge_on_boundary.push_back(std::move(on_boundary));
    raw.push_back({std::move(b), "rock_mass", n, region});
  }
  s.rock_mass = std::move(rm);
}

}  // namespace rheodda::scene::detail
