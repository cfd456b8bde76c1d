// Validation of a Model before a run (docs/reference/engine.md, "Parameters"): every
// refusal names the offending entry (ModelError::key) so that a scene reader
// can point at its file and line.
#include <algorithm>
#include <cmath>
#include <string>

#include "engine_impl.hpp"
#include "rheodda/core/property_specs.hpp"
#include "rheodda/core/settings.hpp"

namespace rheodda::core {

namespace {

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }


}  // namespace

bool inside_or_near(std::span<const Vec2> v, const Vec2& p, double tol) {
  bool inside = false;
  const std::size_t n = v.size();
  for (std::size_t k = 0, j = n - 1; k < n; j = k++) {
    const Vec2& a = v[k];
    const Vec2& b = v[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
    const Vec2 e = b - a;
    const double s = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    if ((a + s * e - p).norm() <= tol) return true;
  }
  return inside;
}

void Engine::Impl::validate() {
  const Model& m = model;
  if (m.materials.empty()) throw ModelError("materials", "at least one material is required");
  for (std::size_t k = 0; k < m.materials.size(); ++k) {
    const Material& mat = m.materials[k];
    check_declared(material_specs(), mat, ModelEntry{"materials", k});  // property_specs.hpp
    if (mat.damping_ratio > 0.0 && !m.settings.has_dynamic_steps())
      throw ModelError(ModelEntry{"materials", k}, "damping_ratio",
                       "damps velocities; a static analysis (dynamic_ratio 0) without a dynamic "
                       "settling stage has none");
  }
  if (m.blocks.empty()) throw ModelError("blocks", "at least one block is required");
  const Settings& s = m.settings;
  for (std::size_t k = 0; k < m.blocks.size(); ++k) {
    const BlockDef& b = m.blocks[k];
    const ModelEntry key{"blocks", k};
    if (b.vertices.size() < 3)
      throw ModelError(key, "vertices", "a block needs at least 3 vertices");
    for (const auto& v : b.vertices)
      if (!finite(v)) throw ModelError(key, "vertices", "vertex coordinates must be finite");
    if (!is_simple_polygon(b.vertices))
      throw ModelError(key, "vertices",
                       "not a simple polygon (edges cross, touch or have zero length)");
    if (polygon_integrals(b.vertices).S == 0.0)
      throw ModelError(key, "vertices", "the polygon has zero area");
    if (!b.edge_joint_set.empty() && b.edge_joint_set.size() != b.vertices.size())
      throw ModelError(key, "edge_joint_set",
                       "needs one joint set per edge (" + std::to_string(b.vertices.size()) +
                           "), or none");
    for (int j : b.edge_joint_set)
      if (j < 0) throw ModelError(key, "edge_joint_set", "joint set indices must be >= 0");
    if (b.material < 0 || b.material >= static_cast<int>(m.materials.size()))
      throw ModelError(key, "material", "no material with index " + std::to_string(b.material));
    if (!b.initial_stress.allFinite())
      throw ModelError(key, "initial_stress", "must be finite");
    if (!finite(b.initial_velocity) || !std::isfinite(b.initial_angular_velocity))
      throw ModelError(key, "initial_velocity", "must be finite");
    if (s.dynamic_ratio == 0.0 &&
        (b.initial_velocity != Vec2::Zero() || b.initial_angular_velocity != 0.0))
      throw ModelError(key, "initial_velocity",
                       "a static analysis (settings.dynamic_ratio = 0) carries no velocities");
  }
  auto check_point = [&](const ModelEntry& key, int block, const Vec2& p) {
    if (block < 0 || block >= static_cast<int>(m.blocks.size()))
      throw ModelError(key, "block", "no block with index " + std::to_string(block));
    if (!finite(p)) throw ModelError(key, "point", "must be finite");
    const auto& v = m.blocks[block].vertices;
    Eigen::AlignedBox2d box;
    for (const auto& q : v) box.extend(q);
    if (!inside_or_near(v, p, 1e-9 * box.diagonal().norm()))
      throw ModelError(key, "point", "lies outside block " + std::to_string(block));
  };
  for (std::size_t k = 0; k < m.point_loads.size(); ++k) {
    const PointLoad& l = m.point_loads[k];
    const ModelEntry key{"point_loads", k};
    check_point(key, l.block, l.point);
    if (l.history.empty()) throw ModelError(key, "history", "needs at least one sample");
    for (std::size_t i = 0; i < l.history.size(); ++i) {
      if (!std::isfinite(l.history[i].time) || !finite(l.history[i].force))
        throw ModelError(key, "history", "time and force must be finite");
      if (i > 0 && !(l.history[i].time > l.history[i - 1].time))
        throw ModelError(key, "history", "times must increase strictly");
    }
  }
  if (m.water.active() || m.water.unit_weight != 0.0) {  // water.hpp: the surfaces span the blocks at the start
    Eigen::AlignedBox2d box;
    for (const BlockDef& b : m.blocks)
      for (const Vec2& v : b.vertices) box.extend(v);
    validate_water(m.water, box.min().x(), box.max().x());
  }
  for (std::size_t k = 0; k < m.fixed_points.size(); ++k) {
    check_point(ModelEntry{"fixed_points", k}, m.fixed_points[k].block, m.fixed_points[k].point);
    const FixedPoint& fp = m.fixed_points[k];
    if (!fp.hold_x && !fp.hold_y && !fp.hold_rotation)
      throw ModelError(ModelEntry{"fixed_points", k}, "hold", "holds nothing (neither x, y nor the rotation)");
    if (fp.held_rotation && !std::isfinite(*fp.held_rotation))
      throw ModelError(ModelEntry{"fixed_points", k}, "held_rotation", "must be finite (rad)");
  }
  for (std::size_t k = 0; k < m.measurement_points.size(); ++k)
    check_point(ModelEntry{"measurement_points", k}, m.measurement_points[k].block,
                m.measurement_points[k].point);

  // Each declared setting within its range (settings.cpp); the checks that tie settings
  // together follow.
  check_setting_ranges(s);
  if (s.creep_tolerance > 0.0 && s.dt_max > 0.0 && s.dt_max < s.dt)
    throw ModelError("settings.dt_max", "must be >= dt (the first step) under creep_tolerance");
  if (s.step_tolerance > 0.0 && s.creep_tolerance > 0.0)
    throw ModelError("settings.step_tolerance",
                     "give step_tolerance or creep_tolerance, not both (two step controls)");
  if (s.step_tolerance > 0.0 && s.dt_max > 0.0 && s.dt_max < s.dt)
    throw ModelError("settings.dt_max", "must be >= dt (the first step) under step_tolerance");
  // The settling stage's numbers one by one (settle_specs, settings.hpp: a 0 is the mark
  // of "none"), then what ties them together.
  check_declared(settle_specs(), s.settle, std::string("settings.settle"));
  if (s.settle.until > 0.0 && !(s.settle.dt > 0.0))
    throw ModelError("settings.settle.dt", "must be > 0 (time) with a settling stage");
  if (s.settle.until > 0.0 && !(s.settle.max_displacement_ratio > 0.0))
    throw ModelError("settings.settle.max_displacement_ratio", "must be > 0 with a settling stage");
  if (s.settle.rest_tolerance > 0.0 && !(s.settle.until > 0.0 && s.settle.dynamic))
    throw ModelError("settings.settle.rest_tolerance",
                     "ends dynamic stages at rest; the analysis has no dynamic settling stage");
  if (s.settle.force_ratio > 0.0 && !(s.settle.rest_tolerance > 0.0))
    throw ModelError("settings.settle.force_ratio", "decides when a stage that ends at rest is at rest: "
                                                     "give settle.rest_tolerance too");
  if (s.settle.collapse_dt > 0.0) {
    if (!(s.settle.until > 0.0 && s.settle.dynamic && s.dynamic_ratio == 0.0))
      throw ModelError("settings.settle.collapse_dt",
                       "collapse stages are for a static analysis with a dynamic settling stage (their model)");
    if (!(s.settle.collapse_dt < s.dt)) throw ModelError("settings.settle.collapse_dt", "must be < dt");
    if (s.step_tolerance > 0.0)
      throw ModelError("settings.settle.collapse_dt", "not with step_tolerance (step doubling takes no collapse stage)");
  }
  if (s.threads < 0) throw ModelError("settings.threads", "must be >= 0 (0: OpenMP's default)");
  if (const IntegratorEntry& in = integrator_entry(s.integrator); !in.dynamic_trial)
    throw ModelError("settings.integrator",
                     std::string(in.word) + " chooses between the integrators before the engine runs "
                     "(scene/integrator_choice.hpp: the one estimated cheaper on the scene's initial state); "
                     "give the engine the integrator chosen");
  if (s.static_force_ratio > 0.0) {
    if (!integrator_entry(s.integrator).static_trial)
      throw ModelError("settings.static_force_ratio", "static steps by cycles are the explicit step's: give "
                                                       "integrator explicit_step");
    if (s.dynamic_ratio != 0.0)
      throw ModelError("settings.static_force_ratio", "a dynamic analysis has no static steps (dynamic_ratio 0 "
                                                       "is a static analysis)");
  }
  if (s.integrator == Integrator::explicit_step) {
    if (!s.has_dynamic_steps() && s.static_force_ratio == 0.0)
      throw ModelError("settings.integrator",
                       "the explicit step integrates dynamic steps, and static ones with static_force_ratio; a "
                       "static analysis without a dynamic settling stage or static_force_ratio has none");
    if (s.step_tolerance > 0.0)
      throw ModelError("settings.integrator",
                       "step doubling (step_tolerance) estimates the implicit step's error; the explicit "
                       "step's cycles are set by its stability");
    if (s.time_integration == TimeIntegration::trapezoidal)
      throw ModelError("settings.integrator",
                       "time_integration chooses the implicit step's scheme; the explicit step is central "
                       "difference");
  }
  if (!finite(s.gravity)) throw ModelError("settings.gravity", "must be finite");
  if (s.settle.gravity_ramp > 0.0 && !(s.settle.gravity_ramp <= s.settle.until))
    throw ModelError("settings.settle.gravity_ramp",
                     "must end within the settling stage (<= settle.until), so that the creep starts under full gravity");
  if (s.time_integration == TimeIntegration::trapezoidal && s.dynamic_ratio == 0.0)
    throw ModelError("settings.time_integration",
                     "the trapezoidal rule needs a dynamic analysis (settings.dynamic_ratio > 0)");
  validate_bolts(m);  // bolt_checks.cpp
}

}  // namespace rheodda::core
