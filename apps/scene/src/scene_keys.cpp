// The valid keys of every map of a scene file and the schema that publishes them.
#include "scene_keys.hpp"

#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

namespace rheodda::scene {
namespace detail {

// The valid keys of the maps not yet declared with their types (keys.hpp), each list
// defined once: the MapReader of that map reads it through the list, and
// scene_schema() publishes the same lists, so what the loader accepts and what the
// schema (and the test of docs/reference/scene-format.md against it) says cannot
// diverge. Order: that of the docs.
namespace keys {
const std::vector<std::string> top{"title", "units", "analysis", "materials", "joint_sets",
                                   "blocks", "rock_mass", "fixed_points", "loads", "measurement_points",
                                   "water", "bolts", "stages"};
const std::vector<std::string> units{"length", "force", "time"};
const std::vector<std::string> stage{"name", "at", "after", "remove_fixed_points", "remove_loads", "remove_blocks",
                                     "add_fixed_points", "add_loads", "add_bolts", "joint_sets", "analysis", "settle",
                                     "water"};
const std::vector<std::string> stage_remove_blocks{"names", "region", "rock_mass_inside"};
const std::vector<std::string> stage_fixed_point{"name", "point", "block"};
const std::vector<std::string> stage_load{"name", "point", "block", "force", "history"};
const std::vector<std::string> stage_joint_set{"friction_angle", "cohesion", "tensile_strength",
                                               "residual_friction_angle", "residual_cohesion", "law"};
const std::vector<std::string> stage_analysis{"type", "dynamic_ratio"};
}  // namespace keys

}  // namespace detail

std::vector<SceneMapKeys> scene_schema() {
  // Built at each call: a key declared at run time (keys.hpp) is in it.
  std::vector<SceneMapKeys> schema{{"", detail::keys::top}, {"units", detail::keys::units}};
  for (const DeclaredMap& m : declared_maps())
    for (const std::string& path : m.schema_paths)
      schema.push_back({path, declared_key_names(m.name)});
  const std::vector<SceneMapKeys> stages{
      {"stages[*]", detail::keys::stage},
      {"stages[*].remove_blocks", detail::keys::stage_remove_blocks},
      {"stages[*].add_fixed_points[*]", detail::keys::stage_fixed_point},
      {"stages[*].add_loads[*]", detail::keys::stage_load},
      {"stages[*].joint_sets.*", detail::keys::stage_joint_set},
      {"stages[*].analysis", detail::keys::stage_analysis},
  };
  schema.insert(schema.end(), stages.begin(), stages.end());
  return schema;
}

}  // namespace rheodda::scene
