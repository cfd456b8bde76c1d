// The scene as summary.json's "inputs" (docs/outputs.md, "summary.json"): every
// key the run used, defaults filled in.
#include <nlohmann/json.hpp>

#include "rheodda/scene/describe.hpp"
#include "bolts_text.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {
namespace {

using json = nlohmann::ordered_json;

json scene_json(const SceneDescription& s) {
  json j;
  j["file"] = s.file;
  j["title"] = s.title;
  j["units"] = {{"length", s.units.length}, {"force", s.units.force}, {"time", s.units.time},
                {"stress", s.units.stress()}};
  const Analysis& a = s.analysis;
  j["analysis"] = {{"type", analysis_type_name(a.type)},
                   {"duration", a.duration},
                   {"dt", a.dt},
                   {"dt_growth", a.dt_growth},
                   {"dt_cut", a.dt_cut},
                   {"max_cuts", a.max_cuts},
                   {"creep_tolerance", a.creep_tolerance},
                   {"step_tolerance", a.step_tolerance},
                   {"step_extrapolation", a.step_extrapolation},
                   {"dt_max", a.dt_max},
                   {"creep_restart_on_contact_change", a.creep_restart_on_contact_change},
                   {"max_displacement_ratio", a.max_displacement_ratio},
                   {"settle", a.settle ? json{{"until", a.settle->until},
                                              {"dt", a.settle->dt},
                                              {"max_displacement_ratio", a.settle->max_displacement_ratio},
                                              {"type", a.settle->dynamic ? "dynamic" : "static"},
                                              {"collapse_dt", a.settle->collapse_dt},
                                              {"gravity_ramp", a.settle->gravity_ramp},
                                              {"rest_tolerance", a.settle->rest_tolerance},
                                              {"open_close_limit", a.settle->open_close_limit}}
                                       : json(nullptr)},
                   {"dynamic_ratio", a.dynamic_ratio},
                   {"time_integration", time_integration_name(a.time_integration)},
                   {"scheme", scheme_text(a)},
                   {"penalty", a.penalty},
                   {"shear_normal_ratio", a.shear_normal_ratio},
                   {"search_factor", a.search_factor},
                   {"angle_tolerance", a.angle_tolerance},
                   {"penetration_ratio", a.penetration_ratio},
                   {"stick_keeps_force", a.stick_keeps_force},
                   {"friction_tolerance", a.friction_tolerance},
                   {"force_resolution", a.force_resolution},
                   {"max_flips", a.max_flips},
                   {"max_refinements", a.max_refinements},
                   {"penalty_raise", a.penalty_raise},
                   {"penalty_max_factor", a.penalty_max_factor},
                   {"open_close_limit", a.open_close_limit},
                   {"fixed_point_stiffness", a.fixed_point_stiffness},
                   {"solver", solver_name(a.solver)},
                   {"solver_tolerance", a.solver_tolerance},
                   {"solver_max_iterations", a.solver_max_iterations},
                   {"solver_iterate_tolerance", a.solver_iterate_tolerance},
                   {"contact_solver", a.contact_solver == ContactSolverKind::newton ? "newton" : "open-close"},
                   {"contact_residual_tolerance", a.contact_residual_tolerance},
                   {"output_interval", a.output_interval},
                   {"max_travel_ratio", a.max_travel_ratio},
                   {"max_output_size", a.max_output_size},
                   {"gravity", a.gravity}};
  for (const auto& m : s.materials)
    j["materials"][m.name] = {{"density", m.density},
                              {"young_modulus", m.young_modulus},
                              {"poisson_ratio", m.poisson_ratio},
                              {"plane", plane_name(m.plane)}};
  for (const auto& js : s.joint_sets) {
    json o = {{"friction_angle", js.friction_angle},
              {"cohesion", js.cohesion},
              {"tensile_strength", js.tensile_strength},
              {"residual_friction_angle", js.residual_friction_angle.value_or(js.friction_angle)},
              {"residual_cohesion", js.residual_cohesion}};
    o["normal_stiffness"] = js.normal_stiffness ? json(*js.normal_stiffness) : json(nullptr);
    o["shear_stiffness"] = js.shear_stiffness ? json(*js.shear_stiffness) : json(nullptr);
    if (js.law) {
      json law = {{"name", js.law->name}};
      for (const auto& [k, v] : js.law->parameters) law[k] = v;
      o["law"] = law;
    } else {
      o["law"] = nullptr;
    }
    o["record"] = js.record;
    j["joint_sets"][js.name] = o;
  }
  j["blocks"] = json::array();
  for (const auto& b : s.blocks) {
    json e = {{"name", b.name}, {"material", s.materials[b.material].name}, {"polygon", b.polygon}};
    json sets = json::array();
    for (int k : b.edge_joint_set) sets.push_back(s.joint_sets[k].name);
    e["edge_joint_sets"] = sets;
    e["fixed"] = b.fixed;
    e["initial_stress"] = b.initial_stress;
    e["initial_velocity"] = b.initial_velocity;
    j["blocks"].push_back(e);
  }
  j["fixed_points"] = json::array();
  for (const auto& f : s.fixed_points) j["fixed_points"].push_back({{"point", f.point}, {"block", s.blocks[f.block].name}});
  j["loads"] = json::array();
  for (const auto& l : s.loads)
    j["loads"].push_back({{"point", l.at.point}, {"block", s.blocks[l.at.block].name}, {"history", l.history}});
  j["measurement_points"] = json::array();
  for (const auto& m : s.measurement_points)
    j["measurement_points"].push_back({{"name", m.name}, {"point", m.at.point}, {"block", s.blocks[m.at.block].name}});
  add_bolts_json(s, j);  // bolts_text.cpp
  return j;
}

}  // namespace

std::string scene_json_text(const SceneDescription& s) { return scene_json(s).dump(); }

}  // namespace rheodda::scene
