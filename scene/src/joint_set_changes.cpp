// Joint set changes given outside a scene file (rheodda/scene/edits.hpp): the
// stage reader on a text of their own, and the joint set a change makes.
#include <yaml-cpp/yaml.h>

#include "rheodda/contact/joint_set_specs.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/edits.hpp"
#include "scene_readers.hpp"

namespace rheodda::scene {

std::vector<StageJointSet> read_joint_set_changes(const SceneDescription& s, const std::string& text,
                                                  const std::string& path, const std::string& file) {
  const detail::Ctx ctx{file};
  YAML::Node n;
  try {
    n = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError(file, {e.mark.line + 1, e.mark.column + 1}, path, e.msg);
  }
  return detail::read_stage_joint_sets(ctx, n, path, s);
}

contact::JointSet changed_joint_set(const contact::JointSet& now, const StageJointSet& c) {
  contact::JointSet j = now;
  for (const auto& [name, v] : c.properties) contact::joint_property_spec(name).set(j, v);
  if (c.law_name) j.law = laws::LawRegistry::builtin().create(*c.law_name, c.law_parameters);
  return j;
}

}  // namespace rheodda::scene
