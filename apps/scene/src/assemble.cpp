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
  } catch (const contact::JointSetError& e) {
    // The contact layer says which joint set, as data: point at its entry in the scene.
    if (e.joint_set() < s.joint_sets.size()) {
      const JointSetDescription& js = s.joint_sets[e.joint_set()];
      throw SceneError(s.file, js.where, "joint_sets." + js.name + "." + e.key(), e.what());
    }
    throw SceneError(s.file, s.analysis.where, "analysis", e.what());
  } catch (const std::invalid_argument& e) {
    throw SceneError(s.file, s.analysis.where, "analysis", e.what());  // the contact settings
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
