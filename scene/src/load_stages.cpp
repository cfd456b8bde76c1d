// The `stages:` section of a scene file (docs/reference/stages.md; stages.hpp). Every
// check that does not need the run is made here, with file:line:col: stage
// names, times increasing within (0, duration), a settling stage to wait for,
// blocks, fixed points, loads and joint sets that exist when the stage comes,
// and a model that keeps a fixed point. What only the run knows (where a
// block stands when a point is added to it) is checked by the engine at the
// stage (run_stages.cpp reports it with the stage's file:line:col).
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <set>
#include <string>
#include <tuple>

#include "rheodda/scene/geometry.hpp"
#include "read_keys.hpp"
#include "scene_readers.hpp"

namespace rheodda::scene::detail {

namespace {

/// Area centroid of a simple polygon (the shoelace moments: c = sum (p_k + p_k+1)
/// (p_k x p_k+1) / (3 sum p_k x p_k+1)) [length].
Point polygon_centroid(const std::vector<Point>& v) {
  double a = 0.0, cx = 0.0, cy = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Point& p = v[k];
    const Point& q = v[(k + 1) % v.size()];
    const double w = p[0] * q[1] - q[0] * p[1];
    a += w;
    cx += w * (p[0] + q[0]);
    cy += w * (p[1] + q[1]);
  }
  return {cx / (3.0 * a), cy / (3.0 * a)};
}

/// A list of names (`[a, b]`), each a non-empty word.
std::vector<std::pair<std::string, YAML::Node>> name_list(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence() || n.size() == 0) ctx.fail(n, key, "expected a non-empty list of names, e.g. [a, b]");
  std::vector<std::pair<std::string, YAML::Node>> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string k = fmt::format("{}[{}]", key, i);
    std::string name = text(ctx, n[i], k);
    for (const auto& [other, node] : out)
      if (other == name) ctx.fail(n[i], k, fmt::format("'{}' is given twice", name));
    out.emplace_back(std::move(name), n[i]);
  }
  return out;
}

/// `remove_blocks: {names, region, rock_mass_inside}` into st.remove_blocks: the union of
/// the blocks they give, in increasing order.
void read_removed_blocks(const Ctx& ctx, const YAML::Node& n, const std::string& path, const SceneDescription& s,
                         StageDescription& st) {
  const MapReader m = declared_reader(ctx, n, path, stage_remove_blocks_keys(), "stages.remove_blocks");
  read_declared(ctx, m, stage_remove_blocks_keys(), st);  // names, region, ...: below
  if (m.entries().empty())
    ctx.fail(n, path,
             "give the blocks to remove: names: [...], region: [[x, y], ...] or rock_mass_inside: [[x, y], ...]");
  std::set<int> out;
  if (YAML::Node v = m.find(key::removed_blocks::names); v.IsDefined())
    for (const auto& [name, node] : name_list(ctx, v, m.child(key::removed_blocks::names)))
      out.insert(resolve(ctx, node, m.child(key::removed_blocks::names), s.blocks, "block"));
  // Blocks whose initial centroid lies inside the polygon (of all blocks, or
  // of the rock mass's generated blocks only).
  auto inside = [&](KeyName k, std::size_t first, std::size_t count) {
    YAML::Node v = m.find(k);
    if (!v.IsDefined()) return;
    const std::vector<Point> poly = polygon_points(ctx, v, m.child(k));
    int hits = 0;
    for (std::size_t b = first; b < first + count; ++b)
      if (contains(poly, polygon_centroid(s.blocks[b].polygon), 0.0)) out.insert(static_cast<int>(b)), ++hits;
    if (hits == 0) ctx.fail(v, m.child(k), "the polygon holds the centroid of no block: it would remove nothing");
  };
  inside(key::removed_blocks::region, 0, s.blocks.size());
  if (YAML::Node v = m.find(key::removed_blocks::rock_mass_inside); v.IsDefined() && !s.rock_mass)
    ctx.fail(v, m.child(key::removed_blocks::rock_mass_inside), "the scene has no rock_mass: whose blocks?");
  if (s.rock_mass) inside(key::removed_blocks::rock_mass_inside, s.rock_mass->first_block, s.rock_mass->block_count);
  st.remove_blocks.assign(out.begin(), out.end());
}

/// `{name, point, block}` of a point a stage adds (`block:` required: the
/// point is where the block stands at the stage, which the loader cannot know);
/// `block`: the key `block` of its map.
StagePoint read_stage_point(const Ctx& ctx, const MapReader& m, const std::vector<EntryKey<StagePoint>>& keys,
                            KeyName block, const SceneDescription& s) {
  StagePoint p;
  p.where = m.where();
  read_declared(ctx, m, keys, p);  // name, point (and a load's force): keys_stages.cpp
  p.block = resolve(ctx, required_key(m, keys, block), m.child(block), s.blocks, "block");
  return p;
}

}  // namespace

/// A stage's `joint_sets: {NAME: {...}}`.
std::vector<StageJointSet> read_stage_joint_sets(const Ctx& ctx, const YAML::Node& n, const std::string& path,
                                                 const SceneDescription& s) {
  if (!n.IsMap() || n.size() == 0)
    ctx.fail(n, path, "expected a map of the joint sets to change, e.g. `bedding: {friction_angle: 20}`");
  std::vector<std::string> names;
  for (const auto& js : s.joint_sets) names.push_back(js.name);
  const MapReader all(ctx, n, path, "", names);
  std::vector<StageJointSet> out;
  for (const auto& e : all.entries()) {
    StageJointSet c;
    c.joint_set = resolve(ctx, e.key_node, path, s.joint_sets, "joint set");
    c.where = location(e.key_node);
    const JointSetDescription& js = s.joint_sets[static_cast<std::size_t>(c.joint_set)];
    const MapReader m =
        declared_reader(ctx, e.value, all.child_named(e.key), stage_joint_set_keys(), "stages.joint_sets");
    if (m.entries().empty()) ctx.fail(e.value, all.child_named(e.key), "changes nothing: give the values to change");
    read_declared(ctx, m, stage_joint_set_keys(), c);  // the strengths (keys_stages.cpp)
    if (YAML::Node v = m.find(key::stage_joint_set::law); v.IsDefined()) {
      const LawChoice law =
          read_law(ctx, v, m.child(key::stage_joint_set::law),
                   "a stage changes the law's parameters only: give it on the joint set's law");
      if (!js.law || js.law->name != law.name)
        ctx.fail(v, m.child(key::stage_joint_set::law),
                 fmt::format("joint set '{}' has {}: a stage can change a law's parameters, not add or replace a law",
                             js.name, js.law ? fmt::format("law '{}'", js.law->name) : std::string("no law")));
      c.law_name = law.name;
      c.law_parameters = law.parameters;
    }
    out.push_back(std::move(c));
  }
  return out;
}

namespace {

/// What exists as the stages come, in order: the blocks removed (and by which stage),
/// the fixed points and loads by name and block, so that each stage's references are
/// checked against the model as it will be then.
struct StageWorld {
  struct Named {
    std::string name;
    int block;
  };
  explicit StageWorld(const SceneDescription& s) : removed(s.blocks.size(), 0), removed_by(s.blocks.size()) {
    for (std::size_t b = 0; b < s.blocks.size(); ++b)
      if (s.blocks[b].fixed)  // `fixed: true` vertices, unnamed
        for (std::size_t k = 0; k < s.blocks[b].polygon.size(); ++k) fixed.push_back({"", static_cast<int>(b)});
    for (const auto& f : s.fixed_points) fixed.push_back({f.name, f.block});
    for (const auto& l : s.loads) loads.push_back({l.at.name, l.at.block});
  }
  static int find(const std::vector<Named>& list, const std::string& name) {
    for (std::size_t k = 0; k < list.size(); ++k)
      if (!name.empty() && list[k].name == name) return static_cast<int>(k);
    return -1;
  }
  /// "block 'b' is removed by then (stage 's')" when block `b` is removed.
  std::string removed_text(const SceneDescription& s, int b) const {
    return fmt::format("block '{}' is removed by then (stage '{}')", s.blocks[static_cast<std::size_t>(b)].name,
                       removed_by[static_cast<std::size_t>(b)]);
  }
  bool is_removed(int b) const { return removed[static_cast<std::size_t>(b)] != 0; }

  std::vector<char> removed;
  std::vector<std::string> removed_by;
  std::vector<Named> fixed;  ///< fixed points (name, block)
  std::vector<Named> loads;
};

/// `remove_fixed_points:`, `remove_loads:` and `remove_blocks:` of a stage; the fixed
/// points and loads on removed blocks go with them.
void read_stage_removals(const Ctx& ctx, const MapReader& m, const SceneDescription& s, StageWorld& w,
                         StageDescription& st) {
  auto remove_named = [&](KeyName key, std::vector<StageWorld::Named>& list, const char* what,
                          std::vector<std::string>& into, SourceLocation& where) {
    YAML::Node v = m.find(key);
    if (!v.IsDefined()) return;
    where = location(v);
    for (const auto& [name, node] : name_list(ctx, v, m.child(key))) {
      const int k = StageWorld::find(list, name);
      if (k < 0) ctx.fail(node, m.child(key), fmt::format("no {} named '{}' is in the model at this stage", what, name));
      list.erase(list.begin() + k);
      into.push_back(name);
    }
  };
  remove_named(key::stage::remove_fixed_points, w.fixed, "fixed point", st.remove_fixed_points, st.remove_fixed_points_where);
  remove_named(key::stage::remove_loads, w.loads, "load", st.remove_loads, st.remove_loads_where);
  if (YAML::Node v = m.find(key::stage::remove_blocks); v.IsDefined()) {
    st.remove_blocks_where = location(v);
    read_removed_blocks(ctx, v, m.child(key::stage::remove_blocks), s, st);
    for (int b : st.remove_blocks) {
      if (w.is_removed(b))
        ctx.fail(v, m.child(key::stage::remove_blocks),
                 fmt::format("block '{}' was removed by stage '{}' before", s.blocks[static_cast<std::size_t>(b)].name,
                             w.removed_by[static_cast<std::size_t>(b)]));
      w.removed[static_cast<std::size_t>(b)] = 1;
      w.removed_by[static_cast<std::size_t>(b)] = st.name;
    }
    if (std::all_of(w.removed.begin(), w.removed.end(), [](char c) { return c != 0; }))
      ctx.fail(v, m.child(key::stage::remove_blocks), "would remove every block of the model");
    std::erase_if(w.fixed, [&](const StageWorld::Named& f) { return w.is_removed(f.block); });
    std::erase_if(w.loads, [&](const StageWorld::Named& l) { return w.is_removed(l.block); });
  }
}

/// `add_fixed_points:` (load false) or `add_loads:` (load true) of a stage.
void read_stage_points(const Ctx& ctx, const MapReader& m, const SceneDescription& s, bool load, StageWorld& w,
                       std::vector<StagePoint>& into, SourceLocation& where) {
  const KeyName added = load ? key::stage::add_loads : key::stage::add_fixed_points;
  YAML::Node v = m.find(added);
  if (!v.IsDefined()) return;
  where = location(v);
  if (!v.IsSequence() || v.size() == 0) ctx.fail(v, m.child(added), "expected a non-empty list");
  const auto& point_keys = load ? stage_load_keys() : stage_fixed_point_keys();
  const std::string point_map = load ? "stages.add_loads" : "stages.add_fixed_points";
  const KeyName name = load ? key::stage_load::name : key::stage_fixed_point::name;
  const KeyName block = load ? key::stage_load::block : key::stage_fixed_point::block;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const MapReader pm = declared_reader(ctx, v[k], fmt::format("{}[{}]", m.child(added), k), point_keys, point_map);
    StagePoint p = read_stage_point(ctx, pm, point_keys, block, s);
    if (w.is_removed(p.block)) ctx.fail(pm.find(block), pm.child(block), w.removed_text(s, p.block));
    std::vector<StageWorld::Named>& list = load ? w.loads : w.fixed;
    if (!p.name.empty() && StageWorld::find(list, p.name) >= 0)
      ctx.fail(pm.find(name), pm.child(name),
               fmt::format("a {} named '{}' is already in the model", load ? "load" : "fixed point", p.name));
    if (load)  // read_points.cpp
      read_force_or_history(ctx, pm, force_or_history<key::stage_load>, p.history, " (t from the stage's start)");
    list.push_back({p.name, p.block});
    into.push_back(std::move(p));
  }
}

/// `add_bolts:` of a stage (docs/reference/stages.md, "Bolts"): the keys of `bolts:`,
/// their ends on blocks that stay.
void read_stage_bolts(const Ctx& ctx, const MapReader& m, const SceneDescription& s, const StageWorld& w,
                      StageDescription& st) {
  YAML::Node v = m.find(key::stage::add_bolts);
  if (!v.IsDefined()) return;
  st.add_bolts_where = location(v);
  if (!v.IsSequence() || v.size() == 0) ctx.fail(v, m.child(key::stage::add_bolts), "expected a non-empty list of bolts");
  std::vector<std::string> taken = bolt_names(s);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string bp = fmt::format("{}[{}]", m.child(key::stage::add_bolts), k);
    BoltDescription b = read_bolt(ctx, v[k], bp, s, taken, true);
    for (const auto& [end, side, block] : {std::tuple<const BlockPoint*, KeyName, KeyName>{&b.from, key::bolt::from, key::bolt_from::block},
                                           {&b.to, key::bolt::to, key::bolt_to::block}})
      if (end->block >= 0 && w.is_removed(end->block))
        ctx.fail(v[k][std::string(side.word())][std::string(block.word())],
                 fmt::format("{}.{}.{}", bp, side.word(), block.word()), w.removed_text(s, end->block));
    taken.push_back(b.name);
    st.add_bolts.push_back(std::move(b));
  }
  // What the engine refuses for every bolt, refused here at the stage's line (bolt_checks.cpp).
  const Analysis& a = s.analysis;
  if (a.contact_solver == core::ContactSolver::newton)
    ctx.fail(v, m.child(key::stage::add_bolts),
             "the newton contact solve's residual does not hold the bolts' forces: give analysis.contact_solver: "
             "open_close (docs/reference/bolts.md, \"Limits\")");
}

}  // namespace

void read_stages(const Ctx& ctx, const YAML::Node& n, SceneDescription& s) {
  if (!n.IsSequence() || n.size() == 0) ctx.fail(n, "stages", "expected a non-empty list of stages");
  const Analysis& a = s.analysis;
  StageWorld w(s);
  // The settling stage a stage `after: settled` waits for: the analysis's at first.
  bool settling_to_wait_for = a.has_settle() && a.settle.rest_tolerance > 0.0;
  double last_at = 0.0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string path = fmt::format("stages[{}]", i);
    const MapReader m = declared_reader(ctx, n[i], path, stage_keys(), "stages");
    StageDescription st;
    st.where = m.where();
    read_declared(ctx, m, stage_keys(), st);  // name, at, after, settle (keys_stages.cpp)
    for (const auto& other : s.stages)
      if (other.name == st.name)
        ctx.fail(m.find(key::stage::name), m.child(key::stage::name),
                 fmt::format("stage '{}' is defined twice", st.name));
    YAML::Node at = m.find(key::stage::at), after = m.find(key::stage::after);
    if (at.IsDefined() == after.IsDefined())
      ctx.fail(m.node(), m.child(key::stage::at), "give exactly one of at: <time> or after: settled");
    if (at.IsDefined()) {
      if (!(st.at < a.duration))
        ctx.fail(at, m.child(key::stage::at),
                 fmt::format("{:g} is not before the end of the run (duration {:g})", st.at, a.duration));
      if (!(st.at > last_at))
        ctx.fail(at, m.child(key::stage::at),
                 fmt::format("{:g} is not after the stage before ({:g}): stage times must increase", st.at, last_at));
      last_at = st.at;
    } else {
      if (!settling_to_wait_for)
        ctx.fail(after, m.child(key::stage::after),
                 i == 0 ? std::string("no settling stage ends at rest before this stage: give analysis.settle a "
                                      "rest_tolerance (a dynamic settling stage), or use at: <time>")
                        : std::string("the stage before opens no settling stage: give it settle: true (with "
                                      "analysis.settle's rest_tolerance), or use at: <time>"));
    }
    read_stage_removals(ctx, m, s, w, st);
    read_stage_points(ctx, m, s, false, w, st.add_fixed_points, st.add_fixed_points_where);
    read_stage_points(ctx, m, s, true, w, st.add_loads, st.add_loads_where);
    read_stage_bolts(ctx, m, s, w, st);
    // Support: a model held by fixed points keeps one (Engine::edit checks it again).
    const bool had_support = !s.fixed_points.empty() || std::any_of(s.blocks.begin(), s.blocks.end(),
                                                                    [](const BlockDescription& b) { return b.fixed; });
    if (had_support && w.fixed.empty()) {
      YAML::Node at_key = m.find(key::stage::remove_blocks).IsDefined() ? m.find(key::stage::remove_blocks)
                                                                         : m.find(key::stage::remove_fixed_points);
      ctx.fail(
          at_key.IsDefined() ? at_key : m.node(),
          m.child(m.find(key::stage::remove_blocks).IsDefined() ? key::stage::remove_blocks
                                                                 : key::stage::remove_fixed_points),
          "would leave no fixed point in the model: nothing would hold it (keep a fixed block, or add_fixed_points)");
    }
    if (YAML::Node v = m.find(key::stage::joint_sets); v.IsDefined()) {
      st.joint_sets_where = location(v);
      st.joint_sets = read_stage_joint_sets(ctx, v, m.child(key::stage::joint_sets), s);
    }
    if (YAML::Node v = m.find(key::stage::analysis); v.IsDefined()) {
      const MapReader am =
          declared_reader(ctx, v, m.child(key::stage::analysis), stage_analysis_keys(), "stages.analysis");
      read_declared(ctx, am, stage_analysis_keys(), st);  // type, dynamic_ratio (keys_stages.cpp)
      if (YAML::Node r = am.find(key::stage_analysis::dynamic_ratio);
          r.IsDefined() && am.find(key::stage_analysis::type).Scalar() == "static")
        ctx.fail(r, am.child(key::stage_analysis::dynamic_ratio), "a static analysis carries no velocity (dynamic_ratio 0)");
      if (a.time_integration == TimeIntegration::trapezoidal && *st.dynamic_ratio == 0.0)
        ctx.fail(v, am.child(key::stage_analysis::type), "time_integration: trapezoidal needs a dynamic analysis");
    }
    if (YAML::Node v = m.find(key::stage::settle); v.IsDefined()) {
      st.settle_where = location(v);
      if (st.settle && !a.has_settle())
        ctx.fail(v, m.child(key::stage::settle), "a settling stage takes analysis.settle's values: give analysis.settle");
    }
    if (YAML::Node v = m.find(key::stage::water); v.IsDefined()) {  // docs/reference/water.md
      st.water_where = location(v);
      st.water = read_water(ctx, v, s, m.child(key::stage::water));
    }
    if (m.entries().size() == 2 + (m.has(key::stage::settle) && !st.settle ? 1 : 0))
      ctx.fail(m.node(), path, "changes nothing: give what the stage does (remove_blocks, joint_sets, ...)");
    settling_to_wait_for = st.settle && a.has_settle() && a.settle.rest_tolerance > 0.0;
    s.stages.push_back(std::move(st));
  }
}

}  // namespace rheodda::scene::detail
