// Model edits are checked whole before anything changes (Engine::edit,
// model_edits.cpp; docs/reference/stages.md): indices, points on blocks that stay
// (where they stand now, or as material points when replayed), bolts, the support
// the model keeps, values. Each refusal is a ModelError naming the edit's entry
// (ModelEntry) in the engine's words.
#include <algorithm>
#include <limits>
#include <string>

#include "block_terms.hpp"
#include "bolts.hpp"
#include "engine_impl.hpp"
#include "held_velocity.hpp"

namespace rheodda::core {

std::vector<char> Engine::Impl::check_edit(const ModelEdit& e) const {
  const Impl& m = *this;
  const std::size_t nb = m.st.blocks.size();
  const int n_blocks = static_cast<int>(nb);
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
    if (!fp.hold_x && !fp.hold_y && !fp.hold_rotation)
      throw ModelError(ModelEntry{"add_fixed_points", k}, "hold", "holds nothing (neither x, y nor the rotation)");
    if (fp.held_rotation && !std::isfinite(*fp.held_rotation))
      throw ModelError(ModelEntry{"add_fixed_points", k}, "held_rotation", "must be finite (rad)");
    if (!e.material_points)
      check_point(ModelEntry{"add_fixed_points", k}, fp.block, fp.point);
    else if (fp.block < 0 || fp.block >= n_blocks || gone[static_cast<std::size_t>(fp.block)] || !fp.material_point ||
             (fp.hold_rotation && !fp.held_rotation))
      throw ModelError(ModelEntry{"add_fixed_points", k},
                       "a replayed fixed point needs a block that stays, its material point and, holding the "
                       "rotation, the rotation held");
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
  // Velocities given: finite, on a block that stays, in a dynamic analysis, and
  // leaving the block's fixed points after the edit at rest (held_velocity.hpp).
  {
    const bool dynamic_after = (e.dynamic_ratio ? *e.dynamic_ratio > 0.0 : m.dynamic_now()) ||
                               (e.settle && m.model.settings.settle.dynamic);
    std::vector<char> dropped(m.model.fixed_points.size(), 0);
    for (int i : e.remove_fixed_points) dropped[static_cast<std::size_t>(i)] = 1;
    for (std::size_t k = 0; k < e.set_velocities.size(); ++k) {
      const auto& [block, v] = e.set_velocities[k];
      const ModelEntry key{"set_velocities", k};
      if (block < 0 || block >= n_blocks) throw ModelError(key, "block", "no block with index " + std::to_string(block));
      const std::size_t b = static_cast<std::size_t>(block);
      if (gone[b]) throw ModelError(key, "block", "block " + std::to_string(block) + " is removed");
      for (std::size_t j = 0; j < k; ++j)
        if (e.set_velocities[j].first == block)
          throw ModelError(key, "block", "block " + std::to_string(block) + " given twice");
      if (!v.allFinite()) throw ModelError(key, "velocity", "must be finite");
      if (!dynamic_after)
        throw ModelError(key, "velocity", "a static analysis carries no velocity (its steps start at rest)");
      const BlockState& bs = m.st.blocks[b];
      HeldRows J(0, 6);
      for (std::size_t i = 0; i < m.model.fixed_points.size(); ++i) {
        const FixedPoint& fp = m.model.fixed_points[i];
        if (fp.block == block && !dropped[i])
          add_fixed_point_rows(J, bs.centroid, bs.map_A * fp.material() + bs.map_b, m.moments[b], fp);
      }
      for (const FixedPoint& fp : e.add_fixed_points)
        if (fp.block == block)
          add_fixed_point_rows(J, bs.centroid,
                               e.material_points ? Vec2(bs.map_A * fp.material() + bs.map_b) : fp.point, m.moments[b],
                               fp);
      const Mat6 M = m.model.materials[static_cast<std::size_t>(bs.material)].density * unit_mass_matrix(m.moments[b]);
      const Vec6 lost = v - held_velocity(M, J, v, std::sqrt(std::abs(m.moments[b].S)));
      if (lost.dot(M * lost) > 1e-12 * v.dot(M * v))
        throw ModelError(key, "velocity",
                         "moves block " + std::to_string(block) +
                             " where its fixed points hold it; free it first, or give a velocity that leaves them at rest");
    }
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
  if (e.settle && !(s.settle.until > 0.0 && s.settle.dt > 0.0 && s.settle.max_displacement_ratio > 0.0))
    throw ModelError("settle", "a settling stage needs settings.settle.until, settle.dt and settle.max_displacement_ratio");
  return gone;
}

}  // namespace rheodda::core
