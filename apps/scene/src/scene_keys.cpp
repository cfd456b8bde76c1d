// The valid keys of every map of a scene file and the schema that publishes them.
#include "scene_keys.hpp"

#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

namespace rheodda::scene {
namespace detail {

// The valid keys of every map of a scene file, each list defined once: the
// MapReader of that map reads it through the list, and scene_schema() publishes
// the same lists, so what the loader accepts and what the schema (and the test of
// docs/reference/scene-format.md against it) says cannot diverge. Order: that of the docs.
namespace keys {
const std::vector<std::string> top{"title", "units", "analysis", "materials", "joint_sets",
                                   "blocks", "rock_mass", "fixed_points", "loads", "measurement_points",
                                   "water", "bolts", "stages"};
const std::vector<std::string> units{"length", "force", "time"};
const std::vector<std::string> material{"density", "young_modulus", "poisson_ratio", "plane", "damping_ratio"};
const std::vector<std::string> joint_set{"friction_angle", "cohesion", "tensile_strength",
                                         "residual_friction_angle", "residual_cohesion", "normal_stiffness", "shear_stiffness", "restitution", "law", "record"};
/// And the parameters of the law named, which only the registry knows.
const std::vector<std::string> law{"name"};
const std::vector<std::string> block{"name", "material", "polygon", "rectangle", "grid",
                                     "joint_set", "edge_joint_sets", "fixed", "initial_stress",
                                     "initial_velocity"};
const std::vector<std::string> rectangle{"x", "y", "width", "height", "angle"};
const std::vector<std::string> grid{"x", "y", "width", "height", "columns", "rows", "angle"};
const std::vector<std::string> rock_mass{"name", "material", "region", "holes", "boundary_joint_set",
                                         "seed", "sliver_area", "joint_sets", "traces"};
const std::vector<std::string> rock_mass_joint_set{"joint_set", "dip", "dip_direction", "spacing",
                                                   "spacing_distribution", "spacing_deviation",
                                                   "trace_length", "gap", "dip_spread", "origin"};
const std::vector<std::string> rock_mass_trace{"joint_set", "from", "to"};
const std::vector<std::string> fixed_point{"name", "point", "block"};
const std::vector<std::string> load{"name", "point", "block", "force", "history"};
const std::vector<std::string> measurement_point{"name", "point", "block"};
const std::vector<std::string> water{"unit_weight", "level", "surface", "level_history", "surface_history"};
const std::vector<std::string> water_sample{"time", "surface"};
const std::vector<std::string> stage{"name", "at", "after", "remove_fixed_points", "remove_loads", "remove_blocks",
                                     "add_fixed_points", "add_loads", "add_bolts", "joint_sets", "analysis", "settle",
                                     "water"};
const std::vector<std::string> stage_remove_blocks{"names", "region", "rock_mass_inside"};
const std::vector<std::string> stage_fixed_point{"name", "point", "block"};
const std::vector<std::string> stage_load{"name", "point", "block", "force", "history"};
const std::vector<std::string> stage_joint_set{"friction_angle", "cohesion", "tensile_strength",
                                               "residual_friction_angle", "residual_cohesion", "law"};
const std::vector<std::string> stage_analysis{"type", "dynamic_ratio"};
const std::vector<std::string> bolt{"name", "from", "to", "axial_stiffness", "pretension", "yield_force",
                                    "rupture_elongation", "law"};
const std::vector<std::string> bolt_from{"point", "block"};
const std::vector<std::string> bolt_to{"point", "block", "fixed"};
}  // namespace keys

}  // namespace detail

std::vector<SceneMapKeys> scene_schema() {
  // Built at each call: a key declared at run time (keys.hpp) is in it.
  return {
      {"", detail::keys::top},
      {"units", detail::keys::units},
      {"analysis", declared_key_names("analysis")},
      {"analysis.settle", declared_key_names("analysis.settle")},
      {"materials.*", detail::keys::material},
      {"joint_sets.*", detail::keys::joint_set},
      {"joint_sets.*.law", detail::keys::law},
      {"blocks[*]", detail::keys::block},
      {"blocks[*].rectangle", detail::keys::rectangle},
      {"blocks[*].grid", detail::keys::grid},
      {"rock_mass", detail::keys::rock_mass},
      {"rock_mass.joint_sets[*]", detail::keys::rock_mass_joint_set},
      {"rock_mass.traces[*]", detail::keys::rock_mass_trace},
      {"fixed_points[*]", detail::keys::fixed_point},
      {"loads[*]", detail::keys::load},
      {"measurement_points[*]", detail::keys::measurement_point},
      {"water", detail::keys::water},
      {"water.surface_history[*]", detail::keys::water_sample},
      {"stages[*]", detail::keys::stage},
      {"stages[*].remove_blocks", detail::keys::stage_remove_blocks},
      {"stages[*].add_fixed_points[*]", detail::keys::stage_fixed_point},
      {"stages[*].add_loads[*]", detail::keys::stage_load},
      {"stages[*].joint_sets.*", detail::keys::stage_joint_set},
      {"stages[*].joint_sets.*.law", detail::keys::law},
      {"stages[*].analysis", detail::keys::stage_analysis},
      {"stages[*].add_bolts[*]", detail::keys::bolt},
      {"stages[*].add_bolts[*].from", detail::keys::bolt_from},
      {"stages[*].add_bolts[*].to", detail::keys::bolt_to},
      {"stages[*].add_bolts[*].law", detail::keys::law},
      {"bolts[*]", detail::keys::bolt},
      {"bolts[*].from", detail::keys::bolt_from},
      {"bolts[*].to", detail::keys::bolt_to},
      {"bolts[*].law", detail::keys::law},
  };
}

}  // namespace rheodda::scene
