// A run with stages (docs/reference/stages.md): the steps land on each stage's time (or
// the stage waits for the settling stage before it to end at rest); at each
// stage its changes go to the engine (Engine::edit), then a frame and a
// checkpoint are written and the stage is recorded (history.csv's `stage`
// column, summary.json's `stages`). A scene without stages never comes here.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rheodda/scene/build.hpp"
#include "rheodda/scene/edits.hpp"
#include "rheodda/scene/geometry.hpp"
#include "rheodda/scene/water.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {

namespace {

/// Where in the scene file what the engine refused of stage `st`'s edit was given: the
/// entry the error names (core::ModelError::entry), else the list or setting its key is.
SourceLocation where_of(const StageDescription& st, const core::ModelError& err) {
  const std::string list = err.entry() ? err.entry()->list : err.key();
  const std::size_t k = err.entry() ? err.entry()->index : 0;
  auto starts = [&](const char* prefix) { return list.rfind(prefix, 0) == 0; };
  auto entry_of = [&](const auto& entries, SourceLocation whole) {
    return err.entry() && k < entries.size() ? entries[k].where : whole;
  };
  if (starts("remove_blocks")) return st.remove_blocks_where;
  if (starts("remove_fixed_points")) return st.remove_fixed_points_where;
  if (starts("remove_point_loads")) return st.remove_loads_where;
  if (starts("add_fixed_points")) return entry_of(st.add_fixed_points, st.add_fixed_points_where);
  if (starts("add_point_loads")) return entry_of(st.add_loads, st.add_loads_where);
  if (starts("add_bolts")) return entry_of(st.add_bolts, st.add_bolts_where);
  if (starts("joint_sets")) return st.joint_sets_where;
  if (starts("settle")) return st.settle_where;
  if (starts("water")) return st.water_where;
  return st.where;
}

/// The block on which the point `p` of a stage's bolt end stands now (its `block:`
/// left out): the one block that stays whose polygon holds it, to a billionth of
/// the model; none or several stop the run at the end's line.
int block_standing_at(const Run& run, const BlockPoint& p, const std::string& key) {
  const core::Engine& e = run.engine;
  std::vector<std::vector<Point>> now(static_cast<std::size_t>(e.block_count()));
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (int b = 0; b < e.block_count(); ++b)
    for (const core::Vec2& v : e.vertices(b)) {
      now[static_cast<std::size_t>(b)].push_back({v.x(), v.y()});
      lo = std::min({lo, v.x(), v.y()});
      hi = std::max({hi, v.x(), v.y()});
    }
  const double tol = 1e-9 * (hi - lo);
  std::vector<std::string> hits;
  int found = -1;
  for (int b = 0; b < e.block_count(); ++b)
    if (!e.removed(b) && contains(now[static_cast<std::size_t>(b)], p.point, tol)) {
      found = b;
      hits.push_back(run.s.blocks[static_cast<std::size_t>(b)].name);
    }
  const std::string stage = run.s.stages[run.stage_run.next].name;
  if (hits.empty())
    throw SceneError(run.s.file, p.where, key,
                     fmt::format("stage '{}' at t = {:g} {}: ({:g}, {:g}) lies on no block where the blocks stand now",
                                 stage, e.time(), run.s.units.time, p.point[0], p.point[1]));
  if (hits.size() > 1)
    throw SceneError(run.s.file, p.where, key,
                     fmt::format("stage '{}' at t = {:g} {}: ({:g}, {:g}) lies on the boundary of several blocks "
                                 "({}); say which with `block:`",
                                 stage, e.time(), run.s.units.time, p.point[0], p.point[1], fmt::join(hits, ", ")));
  return found;
}

/// Applies stage run.stage_run.next to the engine and records it.
void apply_stage(Run& run) {
  StageRun& g = run.stage_run;
  const std::size_t index = g.next;
  const StageDescription& st = run.s.stages[index];
  core::Engine& engine = run.engine;
  core::ModelEdit e;
  std::vector<std::string> actions;
  auto index_of = [](const std::vector<std::string>& names, const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  for (const auto& name : st.remove_fixed_points) e.remove_fixed_points.push_back(index_of(g.fixed_names, name));
  for (const auto& name : st.remove_loads) e.remove_point_loads.push_back(index_of(g.load_names, name));
  e.remove_blocks = st.remove_blocks;
  for (const StagePoint& p : st.add_fixed_points)  // `hold: both | x | y | rotation` (docs/reference/stages.md)
    e.add_fixed_points.push_back(build_fixed_point(p.block, p.point[0], p.point[1], p.hold));
  for (const StagePoint& p : st.add_loads) {
    core::PointLoad l;
    l.block = p.block;
    l.point = {p.point[0], p.point[1]};
    // Load history times count from the stage's start.
    for (const auto& h : p.history) l.history.push_back({engine.time() + h[0], {h[1], h[2]}});
    e.add_point_loads.push_back(std::move(l));
  }
  for (std::size_t k = 0; k < st.add_bolts.size(); ++k) {  // build.hpp
    BoltDescription b = st.add_bolts[k];
    const std::string key = fmt::format("stages[{}].add_bolts[{}]", index, k);
    if (b.from.block < 0) b.from.block = block_standing_at(run, b.from, key + ".from.point");
    if (!b.to_fixed && b.to.block < 0) b.to.block = block_standing_at(run, b.to, key + ".to.point");
    if (b.from.block == b.to.block)
      throw SceneError(run.s.file, b.to.where, key + ".to",
                       fmt::format("stage '{}': both ends are on block '{}' where they stand now: a bolt joins two "
                                   "blocks, or a block and a fixed point",
                                   st.name, run.s.blocks[static_cast<std::size_t>(b.to.block)].name));
    e.add_bolts.push_back(build_bolt(b));
  }
  for (const StageJointSet& c : st.joint_sets)
    e.joint_sets.emplace_back(c.joint_set,
                              changed_joint_set(run.contacts.joint_sets()[static_cast<std::size_t>(c.joint_set)], c));
  e.dynamic_ratio = st.dynamic_ratio;
  e.settle = st.settle;
  if (st.water) {  // its times count from the stage's start (docs/reference/stages.md)
    e.water = build_water(*st.water, run.s);
    for (core::WaterSurface& h : e.water->history) h.time += engine.time();
  }
  const std::string path = fmt::format("stages[{}]", index);
  core::EditReport rep;
  try {
    rep = engine.edit(e);
  } catch (const core::ModelError& err) {
    throw SceneError(run.s.file, where_of(st, err), path + "." + edit_key(err),  // edits.hpp
                     fmt::format("stage '{}' at t = {:g} {}: {}", st.name, engine.time(), run.s.units.time,
                                 err.message()));
  } catch (const std::invalid_argument& err) {  // a joint set the contact layer refuses
    throw SceneError(run.s.file, st.joint_sets_where, path + ".joint_sets",
                     fmt::format("stage '{}': {}", st.name, err.what()));
  }
  // The names follow the engine's lists: explicit removals, then those on
  // removed blocks (indices after the explicit ones), then the added points.
  auto erase = [](std::vector<std::string>& names, std::vector<int> which) {
    std::sort(which.rbegin(), which.rend());
    for (int i : which) names.erase(names.begin() + i);
  };
  erase(g.fixed_names, e.remove_fixed_points);
  erase(g.load_names, e.remove_point_loads);
  erase(g.fixed_names, rep.fixed_points_removed);
  erase(g.load_names, rep.point_loads_removed);
  for (const StagePoint& p : st.add_fixed_points) g.fixed_names.push_back(p.name);
  for (const StagePoint& p : st.add_loads) g.load_names.push_back(p.name);

  auto names = [&](const std::vector<int>& blocks) {
    std::vector<std::string> out;
    for (int b : blocks) out.push_back(run.s.blocks[static_cast<std::size_t>(b)].name);
    return out;
  };
  if (!st.remove_fixed_points.empty())
    actions.push_back(fmt::format("removed fixed points {}", fmt::join(st.remove_fixed_points, ", ")));
  if (!st.remove_loads.empty()) actions.push_back(fmt::format("removed loads {}", fmt::join(st.remove_loads, ", ")));
  if (!st.remove_blocks.empty())
    actions.push_back(fmt::format("removed {} blocks ({}) with {} contacts, {} fixed points and {} loads on them",
                                  st.remove_blocks.size(), fmt::join(names(st.remove_blocks), ", "),
                                  rep.contacts_dropped, rep.fixed_points_removed.size(),
                                  rep.point_loads_removed.size()));
  if (!rep.bolts_removed.empty())
    actions.push_back(fmt::format("removed {} bolts on the removed blocks", rep.bolts_removed.size()));
  if (!st.add_fixed_points.empty()) actions.push_back(fmt::format("added {} fixed points", st.add_fixed_points.size()));
  if (!st.add_loads.empty()) actions.push_back(fmt::format("added {} loads", st.add_loads.size()));
  if (!st.add_bolts.empty()) {
    std::vector<std::string> bolts;
    for (const BoltDescription& b : st.add_bolts) bolts.push_back(b.name);
    actions.push_back(fmt::format("installed {} bolts ({})", bolts.size(), fmt::join(bolts, ", ")));
  }
  for (const StageJointSet& c : st.joint_sets)
    actions.push_back(
        fmt::format("changed joint set {}", run.s.joint_sets[static_cast<std::size_t>(c.joint_set)].name));
  if (st.dynamic_ratio)
    actions.push_back(*st.dynamic_ratio > 0.0 ? fmt::format("dynamic analysis (dynamic_ratio {:g})", *st.dynamic_ratio)
                                              : std::string("static analysis"));
  if (st.settle) actions.push_back("opened a settling stage");
  if (st.water) actions.push_back("changed the water");
  g.applied.push_back({st.name, engine.time(), engine.step_count(), std::move(actions)});
  g.current = st.name;
  g.watch_events = engine.events().size();
  ++g.next;
}

/// The stage comes: applied, its frame and its checkpoint.
void begin_stage(Run& run) {
  apply_stage(run);
  write_frame(run);
  write_checkpoint(run);
}

}  // namespace

void start_stages(Run& run) {
  StageRun& g = run.stage_run;
  // The engine's fixed points: every vertex of a `fixed: true` block (unnamed),
  // then fixed_points:, as build_scene lists them.
  for (const auto& b : run.s.blocks)
    if (b.fixed) g.fixed_names.insert(g.fixed_names.end(), b.polygon.size(), std::string());
  for (const auto& f : run.s.fixed_points) g.fixed_names.push_back(f.name);
  for (const auto& l : run.s.loads) g.load_names.push_back(l.at.name);
}

void watch_settling(Run& run, const core::Engine& e) {
  StageRun& g = run.stage_run;
  if (g.next >= run.s.stages.size() || run.s.stages[g.next].start != StageStart::settled) return;
  const auto& events = e.events();
  for (std::size_t k = g.watch_events; k < events.size(); ++k) {
    if (events[k].kind != core::StageKind::settling) continue;
    if (!events[k].at_rest)
      throw std::runtime_error(fmt::format(
          "stage '{}' (after: settled) waits for the settling stage from t = {:g} {} to end at rest, but it ended at "
          "its longest at t = {:g} {} (analysis.settle.until; raise it or rest_tolerance)",
          run.s.stages[g.next].name, events[k].start_time, run.s.units.time, events[k].end_time, run.s.units.time));
    g.due = true;
    throw StageDue{};
  }
}

void run_staged_to_end(Run& run) {
  StageRun& g = run.stage_run;
  core::Engine& engine = run.engine;
  if (run.frames_done == 0) write_frame(run);
  for (std::size_t k = run.next_output(run.pvd.back().first); k < run.frame_times.size();
       k = run.next_output(run.pvd.back().first)) {
    const StageDescription* st = g.next < run.s.stages.size() ? &run.s.stages[g.next] : nullptr;
    if (st && st->start == StageStart::at) {
      // Its time is after the time the stage before began: stages after one
      // that waited for the settling may find the run past their time.
      if (st->at < engine.time() - 1e-12 * std::max(1.0, std::abs(st->at)))
        throw SceneError(run.s.file, st->where, fmt::format("stages[{}].at", g.next),
                         fmt::format("stage '{}' at {:g} {} comes after the run has passed it (t = {:g} {}, the stage "
                                     "before began later)",
                                     st->name, st->at, run.s.units.time, engine.time(), run.s.units.time));
      if (run.frame_times[k] < st->at - 1e-12 * std::max(1.0, std::abs(st->at))) {
        engine.run_until(run.frame_times[k]);  // an output time before the stage's: the steps end on it
        write_frame(run);
        continue;
      }
      engine.run_until(st->at);  // the last step lands on it
      begin_stage(run);
      continue;
    }
    try {
      engine.run_until(run.frame_times[k]);
      write_frame(run);
    } catch (const StageDue&) {
      g.due = false;
      begin_stage(run);
    }
  }
  for (std::size_t i = g.next; i < run.s.stages.size(); ++i)
    run.result.warnings.push_back(fmt::format("stage '{}' did not begin before the end of the run (t = {:g} {})",
                                              run.s.stages[i].name, engine.time(), run.s.units.time));
}

}  // namespace rheodda::scene
