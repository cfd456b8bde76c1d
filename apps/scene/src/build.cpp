#include "rheodda/scene/build.hpp"

#include <fmt/format.h>

#include "rheodda/laws/registry.hpp"

namespace rheodda::scene {

BuiltScene build_scene(const SceneDescription& s) {
  BuiltScene out;
  core::Model& m = out.model;
  const Analysis& a = s.analysis;

  m.materials.clear();
  for (const auto& mat : s.materials)
    m.materials.push_back({mat.density, mat.young_modulus, mat.poisson_ratio,
                           mat.plane == PlaneKind::strain ? core::PlaneMode::plane_strain
                                                          : core::PlaneMode::plane_stress});

  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    const BlockDescription& b = s.blocks[i];
    core::BlockDef def;
    for (const auto& p : b.polygon) def.vertices.emplace_back(p[0], p[1]);
    def.edge_joint_set = b.edge_joint_set;
    def.material = b.material;
    def.initial_stress = {b.initial_stress[0], b.initial_stress[1], b.initial_stress[2]};
    def.initial_velocity = {b.initial_velocity[0], b.initial_velocity[1]};
    def.initial_angular_velocity = b.initial_velocity[2];
    m.blocks.push_back(std::move(def));
    if (b.fixed)
      for (const auto& p : b.polygon) m.fixed_points.push_back({static_cast<int>(i), {p[0], p[1]}});
  }
  for (const auto& f : s.fixed_points) m.fixed_points.push_back({f.block, {f.point[0], f.point[1]}});
  for (const auto& l : s.loads) {
    core::PointLoad load;
    load.block = l.at.block;
    load.point = {l.at.point[0], l.at.point[1]};
    for (const auto& h : l.history) load.history.push_back({h[0], {h[1], h[2]}});
    m.point_loads.push_back(std::move(load));
  }
  for (const auto& mp : s.measurement_points)
    m.measurement_points.push_back({mp.at.block, {mp.at.point[0], mp.at.point[1]}});

  core::Settings& st = m.settings;
  st.dt = a.dt;
  st.dt_growth = a.dt_growth;
  st.dt_cut = a.dt_cut;
  st.max_cuts = a.max_cuts;
  st.creep_tolerance = a.creep_tolerance;
  st.dt_max = a.dt_max;
  st.step_tolerance = a.step_tolerance;
  st.step_extrapolation = a.step_extrapolation;
  st.creep_restart_on_contact_change = a.creep_restart_on_contact_change;
  st.g2 = a.max_displacement_ratio;
  st.dynamic_ratio = a.dynamic_ratio;
  st.time_integration = a.time_integration == TimeIntegration::trapezoidal ? core::TimeIntegration::trapezoidal
                                                                          : core::TimeIntegration::shi;
  st.gravity = {a.gravity[0], a.gravity[1]};
  st.fixed_point_stiffness = a.fixed_point_stiffness;
  st.max_open_close = a.open_close_limit;
  switch (a.solver) {
    case SolverKind::automatic: st.solver = core::SolverKind::automatic; break;
    case SolverKind::cholmod: st.solver = core::SolverKind::cholmod; break;
    case SolverKind::pcg: st.solver = core::SolverKind::pcg; break;
    case SolverKind::amg: st.solver = core::SolverKind::amg; break;
  }
  st.pcg_tolerance = a.solver_tolerance;
  st.pcg_max_iterations = a.solver_max_iterations;

  contact::ContactSettings& cs = out.contact_settings;
  cs.penalty = a.penalty;
  cs.shear_normal_ratio = a.shear_normal_ratio;
  cs.search_factor = a.search_factor;
  cs.angle_tolerance = a.angle_tolerance;
  cs.penetration_ratio = a.penetration_ratio;
  cs.stick_keeps_force = a.stick_keeps_force;
  cs.friction_tolerance = a.friction_tolerance;
  cs.force_resolution = a.force_resolution;
  cs.max_flips = a.max_flips;
  cs.max_refinements = a.max_refinements;
  cs.penalty_raise = a.penalty_raise;
  cs.penalty_max_factor = a.penalty_max_factor;
  cs.scheme = a.scheme;

  const auto& registry = laws::LawRegistry::builtin();
  for (const auto& js : s.joint_sets) {
    contact::JointSet j;
    j.name = js.name;
    j.friction_angle = js.friction_angle;
    j.cohesion = js.cohesion;
    j.tensile_strength = js.tensile_strength;
    j.normal_stiffness = js.normal_stiffness;
    j.shear_stiffness = js.shear_stiffness;
    if (js.law) j.law = registry.create(js.law->name, js.law->parameters);
    out.joint_sets.push_back(std::move(j));
  }
  return out;
}

}  // namespace rheodda::scene
