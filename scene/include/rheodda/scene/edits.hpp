// Changes to a running model from outside a scene file (the Python scripting
// API, docs/guide/python.md "Joint sets between steps"): read with the checks
// and the messages of a stage's (load_stages.cpp), applied as a stage applies
// them (run_stages.cpp), so that a change is refused in the same words wherever
// it is given.
#pragma once

#include <string>
#include <vector>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// Reads `text`, a YAML (or JSON) map `{NAME: {friction_angle, cohesion,
/// tensile_strength, residual_friction_angle, residual_cohesion, law}}`, as a
/// stage's `joint_sets:` is read (docs/reference/scene-format.md,
/// "stages.joint_sets"): the same checks, refused with SceneError whose key is
/// `path`.NAME.KEY and whose message is the loader's; `file` names the text.
std::vector<StageJointSet> read_joint_set_changes(const SceneDescription& s, const std::string& text,
                                                  const std::string& path, const std::string& file);

/// The joint set `c` makes of `now` (the contact system's current one): each
/// value `c` gives replaces `now`'s; a law given is built by the registry.
contact::JointSet changed_joint_set(const contact::JointSet& now, const StageJointSet& c);

/// The key, in a scene's words, of what an edit of the engine (a stage's, or one
/// from Python) was refused for (edit_errors.cpp): the engine's lists by their scene
/// names (`add_point_loads` is `add_loads`, `remove_point_loads` `remove_loads`), a
/// bolt's ends `a` and `b` by theirs (`from`, `to`): "add_loads[0].history",
/// "add_bolts[1].from.point".
std::string edit_key(const core::ModelError& e);

}  // namespace rheodda::scene
