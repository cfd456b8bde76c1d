// Model edits between two steps (Engine::edit; docs/reference/stages.md): fixed points
// and point loads removed and added, blocks removed (excavation), joint sets
// given new values, the analysis switched between static and dynamic, a
// settling stage opened. An edit is checked whole before anything changes.
//
// Velocities: a moving block that fixed points begin to hold stops in the
// directions they hold (a held rotation: it stops turning), one they stop holding
// starts from rest in those directions (held_velocity.hpp), and ModelEdit::set_velocities gives blocks a
// velocity; the kinetic energy each takes or gives is booked as
// EnergyFlows::dissipation_edits, so the balance stays closed across the edit.
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
#include "block_terms.hpp"
#include "bolts.hpp"
#include "held_velocity.hpp"
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

/// The rows of fixed point fp where its material point stands now, on a block of central
/// integrals g (held_velocity.hpp).
void add_rows(HeldRows& J, const BlockState& b, const PolygonIntegrals& g, const FixedPoint& fp) {
  add_fixed_point_rows(J, b.centroid, b.map_A * fp.material() + b.map_b, g, fp);
}

}  // namespace

EditReport Engine::edit(const ModelEdit& e) {
  Impl& m = *impl_;
  const std::size_t nb = m.st.blocks.size();
  // Check everything first: an invalid edit changes nothing (model_edit_checks.cpp).
  const std::vector<char> gone = m.check_edit(e);
  const Settings& s = m.model.settings;

  EditReport report;
  report.replay = e;
  report.replay.material_points = true;
  // 1. Fixed points and point loads removed by index (largest first, so the
  //    other indices keep their meaning while erasing).
  auto erase = [](auto& list, std::vector<int> which) {
    std::sort(which.rbegin(), which.rend());
    for (int i : which) list.erase(list.begin() + i);
  };
  // Per block, the rows its velocity must leave at rest after the edit: those of
  // the fixed points removed from it (their spring's vibration is dropped) and,
  // below, of every fixed point on a block that gains one (held_velocity.hpp).
  std::vector<HeldRows> rows(nb);
  for (int i : e.remove_fixed_points) {
    const FixedPoint& fp = m.model.fixed_points[static_cast<std::size_t>(i)];
    const auto k = static_cast<std::size_t>(fp.block);
    add_rows(rows[k], m.st.blocks[k], m.moments[k], fp);
  }
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
    const auto b = static_cast<std::size_t>(fp.block);
    if (!e.material_points) fp.material_point = material_point(m.st.blocks[b], fp.point);
    // A rotation held from the one the block has now (unless given: a replay's).
    if (fp.hold_rotation && !fp.held_rotation)
      fp.held_rotation = mean_rotation(central_integrals(m.model.blocks[b].vertices), m.st.blocks[b].map_A);
    report.replay.add_fixed_points[k] = fp;
    m.model.fixed_points.push_back(fp);
  }
  std::vector<char> gains(nb, 0);
  for (const FixedPoint& fp : e.add_fixed_points) gains[static_cast<std::size_t>(fp.block)] = 1;
  for (const FixedPoint& fp : m.model.fixed_points)
    if (const auto k = static_cast<std::size_t>(fp.block); gains[k])
      add_rows(rows[k], m.st.blocks[k], m.moments[k], fp);
  // 3a. Velocities: the held directions at rest, then the velocities given.
  auto mass = [&](std::size_t k) -> Mat6 {
    const BlockState& b = m.st.blocks[k];  // s M in a density-scaled stage (BlockState::mass_scale)
    return b.mass_scale * m.model.materials[static_cast<std::size_t>(b.material)].density * unit_mass_matrix(m.moments[k]);
  };
  auto kinetic = [](const Mat6& M, const Vec6& v) { return 0.5 * v.dot(M * v); };
  double taken = 0.0;
  for (std::size_t k = 0; k < nb; ++k) {
    if (rows[k].rows() == 0 || m.is_removed(k)) continue;
    BlockState& b = m.st.blocks[k];
    const Mat6 M = mass(k);
    const double size = std::sqrt(std::abs(m.moments[k].S));
    const Vec6 v = held_velocity(M, rows[k], b.velocity, size);
    taken += kinetic(M, b.velocity) - kinetic(M, v);
    b.velocity = v;
    b.acceleration = held_velocity(M, rows[k], b.acceleration, size);
  }
  for (const auto& [block, v] : e.set_velocities) {
    const std::size_t k = static_cast<std::size_t>(block);
    BlockState& b = m.st.blocks[k];
    const Mat6 M = mass(k);
    taken -= kinetic(M, v) - kinetic(M, b.velocity);
    b.velocity = v;
  }
  report.kinetic_energy_taken = taken;
  m.st.energy.total.dissipation_edits += taken;
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
      const double reach = s.settle.max_displacement_ratio * m.w0;  // the stage's step limit [length]
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
    m.start_stage(StageKind::settling, s.settle.until);
    m.st.next_dt = std::min(s.dt, s.settle.dt);
  }
  m.count_held();
  m.refresh_geometry();
  m.search_disp = std::min(m.max_displacement_ratio_now() * m.w0, std::max(m.search_disp, m.search_floor));
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
