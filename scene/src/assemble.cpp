#include "rheodda/scene/assemble.hpp"

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
      throw SceneError(s.file, js.where, "joint_sets." + js.name + "." + e.key(), e.message());
    }
    throw SceneError(s.file, s.analysis.where, "analysis", e.what());
  } catch (const std::invalid_argument& e) {
    throw SceneError(s.file, s.analysis.where, "analysis", e.what());  // the contact settings
  }
  a.adapter = std::make_unique<core::ContactAdapter>(*a.contacts);
  try {
    a.engine = std::make_unique<core::Engine>(built.model, *a.adapter);
  } catch (const core::ModelError& e) {
    // The engine says which entry, as data (a block, a material): point at it in the scene.
    SourceLocation where = s.analysis.where;
    if (const auto& at = e.entry()) {
      if (at->list == "blocks" && at->index < s.blocks.size()) where = s.blocks[at->index].where;
      if (at->list == "materials" && at->index < s.materials.size()) where = s.materials[at->index].where;
    }
    throw SceneError(s.file, where, e.key(), e.what());
  }
  return a;
}

}  // namespace rheodda::scene
