// Joint set changes given outside a scene file (rheodda/scene/edits.hpp): the
// stage reader on a text of their own, and the joint set a change makes.
#include <yaml-cpp/yaml.h>

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
  if (c.friction_angle) j.friction_angle = *c.friction_angle;
  if (c.cohesion) j.cohesion = *c.cohesion;
  if (c.tensile_strength) j.tensile_strength = *c.tensile_strength;
  if (c.residual_friction_angle) j.residual_friction_angle = *c.residual_friction_angle;
  if (c.residual_cohesion) j.residual_cohesion = *c.residual_cohesion;
  if (c.law_name) j.law = laws::LawRegistry::builtin().create(*c.law_name, c.law_parameters);
  return j;
}

}  // namespace rheodda::scene
