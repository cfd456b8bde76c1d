// From a validated SceneDescription to the objects a run needs: the engine's
// core::Model and the contact layer's joint sets and settings. One field of the
// scene maps to one field of the model; the mapping is listed in
// docs/reference/scene-format.md.
#pragma once

#include <string>
#include <vector>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

struct BuiltScene {
  core::Model model;
  std::vector<contact::JointSet> joint_sets;  ///< same order as SceneDescription::joint_sets
  contact::ContactSettings contact_settings;
  /// Things the scene asks for that this build cannot honour yet; `run` prints them
  /// and summary.json lists them (nothing is dropped silently).
  std::vector<std::string> warnings;
};

/// What is legal in a scene but suspect, one sentence each with the way out:
/// a fixed step beyond the lagged scheme's stability limit of a joint set's law
/// (docs/notes/step-controls.md, "Stability"), a block that is a sliver or has an
/// extreme aspect ratio. `check` prints them, `run` prints them and summary.json
/// lists them.
std::vector<std::string> scene_warnings(const SceneDescription& scene);

/// Builds the model; throws SceneError if the engine refuses it (its ModelError key is reported).
BuiltScene build_scene(const SceneDescription& scene);

/// The engine's fixed point of a scene's `fixed_points` or `add_fixed_points` entry at
/// (x, y) [length] on `block`: `hold: both | x | y` the point held in both directions or in
/// one, `rotation` the block's rotation alone (core::FixedPoint::hold_rotation).
core::FixedPoint build_fixed_point(int block, double x, double y, const std::string& hold);

/// The engine's bolt of a scene's bolt (core/include/rheodda/core/bolt.hpp): its law
/// built by the registry; points as the description gives them.
core::Bolt build_bolt(const BoltDescription& b);

}  // namespace rheodda::scene
