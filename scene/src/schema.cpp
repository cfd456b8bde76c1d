// The schema of a scene file: the valid keys of every map, as the loader accepts them.
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

namespace rheodda::scene {

std::vector<SceneMapKeys> scene_schema() {
  // Built at each call from the declarations (keys.hpp): a key declared at run time is in it.
  std::vector<SceneMapKeys> schema;
  for (const DeclaredMap& m : declared_maps())
    for (const std::string& path : m.schema_paths) schema.push_back({path, declared_key_names(m.name)});
  return schema;
}

}  // namespace rheodda::scene
