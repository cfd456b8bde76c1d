#include "rheodda/scene/assemble.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "rheodda/scene/error.hpp"

namespace rheodda::scene {

AssembledScene assemble_scene(const SceneDescription& s, const BuiltScene& built) {
  AssembledScene a;
  try {
    a.contacts = std::make_unique<contact::ContactSystem>(built.joint_sets, built.contact_settings);
  } catch (const std::invalid_argument& e) {
    // The contact layer names the joint set by index ("joint set 2 ..."): point at it in the scene.
    SourceLocation where = s.analysis.where;
    std::string key = "analysis";
    int index = -1;
    if (std::sscanf(e.what(), "joint set %d", &index) == 1 && index >= 0 &&
        index < static_cast<int>(s.joint_sets.size())) {
      where = s.joint_sets[index].where;
      key = "joint_sets." + s.joint_sets[index].name;
    }
    throw SceneError(s.file, where, key, e.what());
  }
  a.adapter = std::make_unique<core::ContactAdapter>(*a.contacts);
  try {
    a.engine = std::make_unique<core::Engine>(built.model, *a.adapter);
  } catch (const core::ModelError& e) {
    // The engine's key names a block ("blocks[3]...") or a setting: point at the scene's entry.
    SourceLocation where = s.analysis.where;
    int index = -1;
    if (std::sscanf(e.key().c_str(), "blocks[%d]", &index) == 1 && index >= 0 &&
        index < static_cast<int>(s.blocks.size()))
      where = s.blocks[index].where;
    throw SceneError(s.file, where, e.key(), e.what());
  }
  return a;
}

}  // namespace rheodda::scene
