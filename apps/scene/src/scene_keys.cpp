// The valid keys of every map of a scene file and the schema that publishes them.
#include "scene_keys.hpp"

#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

namespace rheodda::scene {
namespace detail {

// The valid keys of the top level and of `units:`, the maps not declared with their
// types (keys.hpp), each list defined once: the MapReader of that map reads it
// through the list, and scene_schema() publishes the same lists with the declared
// maps', so what the loader accepts and what the schema (and the test of
// docs/reference/scene-format.md against it) says cannot diverge. Order: that of the docs.
namespace keys {
const std::vector<std::string> top{"title", "units", "analysis", "materials", "joint_sets",
                                   "blocks", "rock_mass", "fixed_points", "loads", "measurement_points",
                                   "water", "bolts", "stages"};
const std::vector<std::string> units{"length", "force", "time"};
}  // namespace keys

}  // namespace detail

std::vector<SceneMapKeys> scene_schema() {
  // Built at each call: a key declared at run time (keys.hpp) is in it.
  std::vector<SceneMapKeys> schema{{"", detail::keys::top}, {"units", detail::keys::units}};
  for (const DeclaredMap& m : declared_maps())
    for (const std::string& path : m.schema_paths)
      schema.push_back({path, declared_key_names(m.name)});
  return schema;
}

}  // namespace rheodda::scene
