// The `bolts:` section of a scene file (docs/reference/scene-format.md, "bolts";
// docs/reference/bolts.md), and the bolts a stage installs (`add_bolts:`,
// docs/reference/stages.md): each bolt's ends, stiffness, pretension, yield force,
// rupture elongation and optional creep law, checked here so that the engine
// never sees a bad one (where a stage's ends stand is checked at the stage).
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "bolts_text.hpp"
#include "read_keys.hpp"
#include "scene_readers.hpp"

namespace rheodda::scene::detail {

namespace {

/// An end on a block of a bolt a stage installs: `{point, block}`; the point is
/// where the end stands at the stage, which the loader cannot know: the engine
/// checks it there, and a `block` left out (-1) is the block standing there then
/// (run_stages.cpp). `keys`: the end's map's.
BlockPoint read_stage_end(const Ctx& ctx, const MapReader& m, const PointOnBlock& keys, const SceneDescription& s) {
  BlockPoint bp;
  bp.where = m.where();
  bp.point =
      point(ctx, m.required(keys.point, "[x, y] where the end stands at the stage [length]"), m.child(keys.point));
  bp.block = -1;
  if (const YAML::Node b = m.find(keys.block); b.IsDefined())
    bp.block = resolve(ctx, b, m.child(keys.block), s.blocks, "block");
  return bp;
}

}  // namespace

std::vector<std::string> bolt_names(const SceneDescription& s) {
  std::vector<std::string> out;
  for (const BoltDescription* b : all_bolts(s)) out.push_back(b->name);  // bolts_text.cpp
  return out;
}

BoltDescription read_bolt(const Ctx& ctx, const YAML::Node& n, const std::string& path, const SceneDescription& s,
                          const std::vector<std::string>& taken, bool at_stage) {
  const double tol = geometry_tolerance(s.blocks);
  const MapReader m = declared_reader(ctx, n, path, bolt_keys(), "bolts");
  BoltDescription b;
  b.where = m.where();
  // name, axial_stiffness, pretension, yield_force, rupture_elongation (keys_bolts.cpp).
  read_declared(ctx, m, bolt_keys(), b);
  if (std::find(taken.begin(), taken.end(), b.name) != taken.end())
    ctx.fail(m.find(key::bolt::name), m.child(key::bolt::name), fmt::format("bolt '{}' is defined twice", b.name));
  auto read_end = [&](const MapReader& e, const PointOnBlock& keys) {
    return at_stage ? read_stage_end(ctx, e, keys, s) : read_block_point(ctx, e, keys, s, tol);
  };
  const char* installed = at_stage ? "at the stage" : "at t = 0";

  const MapReader from = declared_reader(ctx, required_key(m, bolt_keys(), key::bolt::from), m.child(key::bolt::from),
                                         bolt_end_keys(), "bolts.from");
  b.from = read_end(from, point_on_block<key::bolt_from>);
  read_declared(ctx, from, bolt_end_keys(), b.from);  // point and block are read_end's

  const MapReader to = declared_reader(ctx, required_key(m, bolt_keys(), key::bolt::to), m.child(key::bolt::to),
                                       bolt_to_keys(), "bolts.to");
  if (const YAML::Node fixed = to.find(key::bolt_to::fixed); fixed.IsDefined()) {
    if (to.has(key::bolt_to::point) || to.has(key::bolt_to::block))
      ctx.fail(to.node(), to.child(key::bolt_to::fixed),
               "give either {fixed: [x, y]} (an anchor fixed in space) or {point: [x, y], block: NAME}, not both");
    b.to_fixed = true;
    b.to.point = point(ctx, fixed, to.child(key::bolt_to::fixed));
    b.to.block = -1;
    b.to.where = location(fixed);
  } else {
    b.to = read_end(to, point_on_block<key::bolt_to>);
    if (b.to.block >= 0 && b.to.block == b.from.block)
      ctx.fail(to.node(), to.child(key::bolt_to::block),
               fmt::format("both ends are on block '{}': a bolt joins two blocks, or a block and a fixed point",
                           s.blocks[b.to.block].name));
  }
  read_declared(ctx, to, bolt_to_keys(), b.to);  // fixed, point and block are read above
  if (std::hypot(b.to.point[0] - b.from.point[0], b.to.point[1] - b.from.point[1]) <= tol)
    ctx.fail(to.node(), to.child(b.to_fixed ? key::bolt_to::fixed : key::bolt_to::point),
             "the two ends coincide: a bolt needs a length");

  if (const YAML::Node law = m.find(key::bolt::law); law.IsDefined()) {
    b.law = read_law(ctx, law, m.child(key::bolt::law),
                     "a bolt's law does not take it (its force is axial, not a joint's shear stress)");
    const auto built = laws::LawRegistry::builtin().create(b.law->name, b.law->parameters);
    if (built->failure_time(1.0))
      ctx.fail(law, m.child(key::bolt::law),
               fmt::format("law '{}' fails by damage, which a bolt does not model: give rupture_elongation "
                           "instead (docs/reference/bolts.md)", b.law->name));
  }
  // The spring: axial_stiffness, or the law's instantaneous stiffness E1 (one spring, one value).
  std::optional<double> e1;
  if (b.law)
    if (const auto it = b.law->parameters.find("E1"); it != b.law->parameters.end()) e1 = it->second;
  if (const YAML::Node k = m.find(key::bolt::axial_stiffness); k.IsDefined()) {
    if (e1 && std::abs(*e1 - b.axial_stiffness) > 1e-12 * b.axial_stiffness)
      ctx.fail(k, m.child(key::bolt::axial_stiffness),
               fmt::format("{:g} differs from the law's instantaneous stiffness E1 = {:g}, which is the bolt's "
                           "spring: give one of them", b.axial_stiffness, *e1));
  } else if (e1) {
    b.axial_stiffness = *e1;
  } else {
    m.required(key::bolt::axial_stiffness, "axial force per unit elongation [force/length]");
  }
  if (const YAML::Node v = m.find(key::bolt::pretension); v.IsDefined()) {
    if (std::abs(b.pretension) > b.yield_force)  // never, without a yield_force (infinite)
      ctx.fail(v, m.child(key::bolt::pretension),
               fmt::format("{:g} exceeds the yield force {:g}", b.pretension, b.yield_force));
    if (b.pretension / b.axial_stiffness >= b.rupture_elongation)
      ctx.fail(v, m.child(key::bolt::pretension),
               fmt::format("stretches the bolt by {:g} {}, not below its rupture_elongation {:g}",
                           b.pretension / b.axial_stiffness, installed, b.rupture_elongation));
  }
  return b;
}

void read_bolts(const Ctx& ctx, const MapReader& top, SceneDescription& s) {
  const YAML::Node n = top.find(key::top::bolts);
  if (!n.IsDefined() || n.IsNull()) return;
  if (!n.IsSequence()) ctx.fail(n, "bolts", fmt::format("expected a list of bolts, got {}", type_word(n)));
  for (std::size_t i = 0; i < n.size(); ++i)
    s.bolts.push_back(read_bolt(ctx, n[i], fmt::format("bolts[{}]", i), s, bolt_names(s), false));
}

}  // namespace rheodda::scene::detail
