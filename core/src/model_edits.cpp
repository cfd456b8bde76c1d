// Model edits between two steps (Engine::edit; docs/reference/stages.md): fixed points
// and point loads removed and added, blocks removed (excavation), joint sets
// given new values, the analysis switched between static and dynamic, a
// settling stage opened. An edit is checked whole before anything changes.
//
// A removed block stays in the model (indices keep their meaning for outputs,
// measurement points and checkpoints) but takes no part: its contacts are
// dropped and never detected again (ContactModel::remove_blocks), it carries
// no gravity, velocity or stress, and its six unknowns solve to zero
// (block_assembly.cpp) and are set to zero when a step is accepted (engine.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine_impl.hpp"
#include "bolts.hpp"
#include "rheodda/core/contact_adapter.hpp"

namespace rheodda::core {

int ContactModel::remove_blocks(std::span<const char>) {
  throw std::logic_error("this contact model cannot remove blocks (ContactModel::remove_blocks)");
}

void ContactModel::set_joint_set(int, const contact::JointSet&) {
  throw std::logic_error("this contact model cannot change joint sets (ContactModel::set_joint_set)");
}

int ContactAdapter::remove_blocks(std::span<const char> removed) {
  const std::size_t before = system_.contacts().size();
  system_.remove_blocks(removed);
  return static_cast<int>(before - system_.contacts().size());
}

void ContactAdapter::set_joint_set(int index, const contact::JointSet& joint_set) {
  system_.set_joint_set(index, joint_set);
}

namespace {


/// The initial position of the material point of block b that stands at p now:
/// x = A x0 + b inverted (BlockState::map_A, map_b) [length].
Vec2 material_point(const BlockState& b, const Vec2& p) { return b.map_A.inverse() * (p - b.map_b); }

}  // namespace

EditReport Engine::edit(const ModelEdit& e) {
  Impl& m = *impl_;
  const std::size_t nb = m.st.blocks.size();
  const int n_blocks = static_cast<int>(nb);
  // Check everything first: an invalid edit changes nothing.
  auto check_indices = [](const std::vector<int>& list, std::size_t size, const char* key, const char* what) {
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (list[k] < 0 || list[k] >= static_cast<int>(size))
        throw ModelError(ModelEntry{key, k}, std::string("no ") + what + " with index " + std::to_string(list[k]));
      for (std::size_t j = 0; j < k; ++j)
        if (list[j] == list[k])
          throw ModelError(ModelEntry{key, k}, std::string(what) + " " + std::to_string(list[k]) + " given twice");
    }
  };
  check_indices(e.remove_fixed_points, m.model.fixed_points.size(), "remove_fixed_points", "fixed point");
  check_indices(e.remove_point_loads, m.model.point_loads.size(), "remove_point_loads", "point load");
  check_indices(e.remove_blocks, nb, "remove_blocks", "block");
  std::vector<char> gone = m.removed.empty() ? std::vector<char>(nb, 0) : m.removed;
  for (std::size_t k = 0; k < e.remove_blocks.size(); ++k) {
    if (gone[static_cast<std::size_t>(e.remove_blocks[k])])
      throw ModelError(ModelEntry{"remove_blocks", k}, "block " + std::to_string(e.remove_blocks[k]) + " was removed before");
    gone[static_cast<std::size_t>(e.remove_blocks[k])] = 1;
  }
  if (std::count(gone.begin(), gone.end(), 1) == n_blocks)
    throw ModelError("remove_blocks", "would remove every block of the model");
  auto check_point = [&](const ModelEntry& key, int block, const Vec2& p) {
    if (block < 0 || block >= n_blocks)
      throw ModelError(key, "block", "no block with index " + std::to_string(block));
    if (gone[static_cast<std::size_t>(block)])
      throw ModelError(key, "block", "block " + std::to_string(block) + " is removed");
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) throw ModelError(key, "point", "must be finite");
    const auto& v = m.st.blocks[static_cast<std::size_t>(block)].vertices;
    Eigen::AlignedBox2d box;
    for (const auto& q : v) box.extend(q);
    if (!inside_or_near(v, p, 1e-9 * box.diagonal().norm()))
      throw ModelError(key, "point", "lies outside block " + std::to_string(block) + " where it stands now");
  };
  for (std::size_t k = 0; k < e.add_fixed_points.size(); ++k) {
    const FixedPoint& fp = e.add_fixed_points[k];
    if (!e.material_points)
      check_point(ModelEntry{"add_fixed_points", k}, fp.block, fp.point);
    else if (fp.block < 0 || fp.block >= n_blocks || gone[static_cast<std::size_t>(fp.block)] || !fp.material_point)
      throw ModelError(ModelEntry{"add_fixed_points", k},
                       "a replayed fixed point needs a block that stays and its material point");
  }
  for (std::size_t k = 0; k < e.add_point_loads.size(); ++k) {
    const PointLoad& l = e.add_point_loads[k];
    const ModelEntry key{"add_point_loads", k};
    if (!e.material_points)
      check_point(key, l.block, l.point);
    else if (l.block < 0 || l.block >= n_blocks || gone[static_cast<std::size_t>(l.block)])
      throw ModelError(key, "block", "a replayed point load needs a block that stays");
    if (l.history.empty()) throw ModelError(key, "history", "needs at least one sample");
    for (std::size_t i = 0; i < l.history.size(); ++i) {
      if (!std::isfinite(l.history[i].time) || !std::isfinite(l.history[i].force.x()) ||
          !std::isfinite(l.history[i].force.y()))
        throw ModelError(key, "history", "time and force must be finite");
      if (i > 0 && !(l.history[i].time > l.history[i - 1].time))
        throw ModelError(key, "history", "times must increase strictly");
    }
  }
  for (std::size_t k = 0; k < e.add_bolts.size(); ++k) {
    const Bolt& b = e.add_bolts[k];
    const ModelEntry key{"add_bolts", k};
    if (!e.material_points) {
      check_point(key.within("a"), b.block_a, b.point_a);
      if (b.block_b >= 0) check_point(key.within("b"), b.block_b, b.point_b);
      if (!std::isfinite(b.point_b.x()) || !std::isfinite(b.point_b.y())) throw ModelError(key, "b.point", "must be finite");
    } else if (b.block_a < 0 || b.block_a >= n_blocks || gone[static_cast<std::size_t>(b.block_a)] ||
               b.block_b >= n_blocks || (b.block_b >= 0 && gone[static_cast<std::size_t>(b.block_b)]) ||
               !(b.installed_length > 0.0)) {
      throw ModelError(key, "a replayed bolt needs blocks that stay and its installed length");
    }
    validate_bolt_values(b, key);  // bolt_checks.cpp
  }
  if (!e.add_bolts.empty()) validate_bolt_settings(m.model.settings);
  // Support: a model held by fixed points must keep one on a block that stays.
  {
    std::vector<char> dropped(m.model.fixed_points.size(), 0);
    for (int i : e.remove_fixed_points) dropped[static_cast<std::size_t>(i)] = 1;
    std::size_t left = e.add_fixed_points.size();
    for (std::size_t k = 0; k < m.model.fixed_points.size(); ++k)
      if (!dropped[k] && !gone[static_cast<std::size_t>(m.model.fixed_points[k].block)]) ++left;
    if (!m.model.fixed_points.empty() && left == 0)
      throw ModelError(e.remove_blocks.empty() ? "remove_fixed_points" : "remove_blocks",
                       "would leave no fixed point: the model is held by " +
                           std::to_string(m.model.fixed_points.size()) +
                           " fixed points, and none would remain on a block that stays");
  }
  for (std::size_t k = 0; k < e.joint_sets.size(); ++k)
    if (e.joint_sets[k].first < 0) throw ModelError(ModelEntry{"joint_sets", k}, "no joint set with a negative index");
  if (e.dynamic_ratio && !(*e.dynamic_ratio >= 0.0 && *e.dynamic_ratio <= 1.0))
    throw ModelError("dynamic_ratio", "must be in [0, 1]");
  if (e.water && (e.water->active() || e.water->unit_weight != 0.0)) {
    // The new surfaces span the blocks that stay, where they stand now (water.hpp).
    double x_min = std::numeric_limits<double>::max(), x_max = std::numeric_limits<double>::lowest();
    for (std::size_t b = 0; b < m.st.blocks.size(); ++b)
      if (!gone[b])
        for (const Vec2& v : m.st.blocks[b].vertices) x_min = std::min(x_min, v.x()), x_max = std::max(x_max, v.x());
    validate_water(*e.water, x_min, x_max);  // keys water.*
  }
  const Settings& s = m.model.settings;
  if (e.settle && !(s.settle_until > 0.0 && s.settle_dt > 0.0 && s.settle_g2 > 0.0))
    throw ModelError("settle", "a settling stage needs settings.settle_until, settle_dt and settle_g2");

  EditReport report;
  report.replay = e;
  report.replay.material_points = true;
  // 1. Fixed points and point loads removed by index (largest first, so the
  //    other indices keep their meaning while erasing).
  auto erase = [](auto& list, std::vector<int> which) {
    std::sort(which.rbegin(), which.rend());
    for (int i : which) list.erase(list.begin() + i);
  };
  erase(m.model.fixed_points, e.remove_fixed_points);
  erase(m.model.point_loads, e.remove_point_loads);
  // 2. Blocks removed, and the fixed points and loads on them.
  if (!e.remove_blocks.empty()) {
    for (std::size_t k = 0; k < m.model.fixed_points.size(); ++k)
      if (gone[static_cast<std::size_t>(m.model.fixed_points[k].block)])
        report.fixed_points_removed.push_back(static_cast<int>(k));
    for (std::size_t k = 0; k < m.model.point_loads.size(); ++k)
      if (gone[static_cast<std::size_t>(m.model.point_loads[k].block)])
        report.point_loads_removed.push_back(static_cast<int>(k));
    erase(m.model.fixed_points, report.fixed_points_removed);
    erase(m.model.point_loads, report.point_loads_removed);
    m.removed = gone;
    for (int b : e.remove_blocks) {
      BlockState& st = m.st.blocks[static_cast<std::size_t>(b)];
      st.velocity.setZero();
      st.acceleration.setZero();
      st.stress.setZero();
    }
    report.contacts_dropped = m.contacts->remove_blocks(m.removed);
    // A bolt with an end on a removed block goes with it (docs/reference/stages.md).
    for (std::size_t k = 0; k < m.model.bolts.size(); ++k) {
      const Bolt& b = m.model.bolts[k];
      BoltState& bs = m.st.bolts[k];
      const bool on_removed = gone[static_cast<std::size_t>(b.block_a)] ||
                              (b.block_b >= 0 && gone[static_cast<std::size_t>(b.block_b)]);
      if (!on_removed || bs.state == BoltMode::ruptured) continue;
      bs.state = BoltMode::ruptured;
      bs.force = 0.0;
      bs.rupture_time = m.st.time;
      report.bolts_removed.push_back(static_cast<int>(k));
    }
  }
  // 3. Fixed points and loads added where their material points stand now.
  for (std::size_t k = 0; k < e.add_fixed_points.size(); ++k) {
    FixedPoint fp = e.add_fixed_points[k];
    if (!e.material_points)
      fp.material_point = material_point(m.st.blocks[static_cast<std::size_t>(fp.block)], fp.point);
    report.replay.add_fixed_points[k] = fp;
    m.model.fixed_points.push_back(fp);
  }
  for (std::size_t k = 0; k < e.add_point_loads.size(); ++k) {
    PointLoad l = e.add_point_loads[k];
    if (!e.material_points) l.point = material_point(m.st.blocks[static_cast<std::size_t>(l.block)], l.point);
    report.replay.add_point_loads[k] = l;
    m.model.point_loads.push_back(std::move(l));
  }
  // 3b. Bolts installed where their ends stand now: material points, and the
  //     length now as the length they are installed at (bolt.hpp).
  for (std::size_t k = 0; k < e.add_bolts.size(); ++k) {
    Bolt b = e.add_bolts[k];
    if (!e.material_points) {
      const Vec2 a_now = b.point_a, b_now = b.point_b;
      b.installed_length = (b_now - a_now).norm();
      b.point_a = material_point(m.st.blocks[static_cast<std::size_t>(b.block_a)], a_now);
      if (b.block_b >= 0) b.point_b = material_point(m.st.blocks[static_cast<std::size_t>(b.block_b)], b_now);
    }
    report.replay.add_bolts[k] = b;
    m.st.bolts.push_back(BoltSet::installed_state(b));
    m.model.bolts.push_back(std::move(b));
  }
  // 4. Joint sets (the contact model checks them and keeps its records).
  for (const auto& [index, js] : e.joint_sets) m.contacts->set_joint_set(index, js);
  // 5. Static or dynamic from now on: a static step starts at rest (accept()).
  if (e.dynamic_ratio) m.model.settings.dynamic_ratio = *e.dynamic_ratio;
  // 5b. The water from now on (the next step's loads and step ends follow it).
  if (e.water) m.model.water = *e.water;
  // 6. A settling stage from now; one in progress ends here (its event recorded).
  if (e.settle) {
    StageState& g = m.st.stage;
    if (g.open) {  // ends now, not at rest: its event as update_stage records one
      StageEvent& ev = g.event;
      ev.end_time = m.st.time;
      const double reach = s.settle_g2 * m.w0;  // the stage's step limit [length]
      for (std::size_t k = 0; k < nb && k < g.start_vertices.size(); ++k) {
        double moved = 0.0;
        const auto& v = m.st.blocks[k].vertices;
        const auto& v0 = g.start_vertices[k];
        for (std::size_t i = 0; i < v.size() && i < v0.size(); ++i) moved = std::max(moved, (v[i] - v0[i]).norm());
        ev.largest_displacement = std::max(ev.largest_displacement, moved);
        if (moved > reach) ++ev.blocks_involved;
      }
      m.st.events.push_back(ev);
      g.open = false;
    }
    m.start_stage(StageKind::settling, s.settle_until);
    m.stage_opened_by_edit = true;
    m.st.next_dt = std::min(s.dt, s.settle_dt);
  }
  m.count_held();
  m.refresh_geometry();
  m.search_disp = std::min(m.g2_now() * m.w0, std::max(m.search_disp, m.search_floor));
  // Stored energies of the edited model: what was removed leaves the balance
  // here, outside the flows of any step (docs/reference/stages.md, "Energy").
  const StoredEnergy blocks = EnergyAccount::stored_in_blocks(m.energy_inputs());
  const ContactEnergy c = m.contacts->energy();
  StoredEnergy& now = m.st.energy.stored;
  now.kinetic = blocks.kinetic;
  now.strain = blocks.strain;
  now.fixed = blocks.fixed;
  if (!report.bolts_removed.empty() || !e.add_bolts.empty()) now.bolt = BoltSet::stored_energy(m.model, m.st.bolts);
  if (report.contacts_dropped > 0) {
    now.contact_normal = c.normal;
    now.contact_shear = c.shear;
  }
  return report;
}

bool Engine::removed(int b) const { return impl_->is_removed(static_cast<std::size_t>(b)); }

std::span<const char> Engine::removed_blocks() const { return impl_->removed; }

}  // namespace rheodda::core
