// Reading a scene file (docs/reference/scene-format.md) into a validated SceneDescription.
//
// Every key is known (an unknown one is an error with the nearest valid name),
// every value is type- and range-checked, NaN/inf are refused anywhere, names
// (materials, joint sets, blocks) must resolve, polygons must be simple with a
// positive area, blocks must not overlap at the start, and every fixed, load and
// measurement point must lie on a block. The first fault found throws a
// SceneError with file, line, column and key; nothing is returned half-read.
#pragma once

#include <string>
#include <vector>

#include "rheodda/scene/error.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// The text of the scene file at `path`; throws SceneError if it cannot be read.
std::string read_scene_text(const std::string& path);

/// Reads and validates the scene file at `path`; throws SceneError.
SceneDescription load_scene(const std::string& path);

/// Parses and validates scene text; `file` names the source in error messages.
SceneDescription parse_scene(const std::string& text, const std::string& file);

/// One map of a scene file and the keys it may hold.
struct SceneMapKeys {
  /// Dotted path as in error keys, `*` standing for a user's name or a list index:
  /// "" (the top level), "analysis", "materials.*", "joint_sets.*.law", "blocks[*].grid", ...
  std::string path;
  std::vector<std::string> keys;  ///< every valid key, in the order of docs/reference/scene-format.md
};

/// The scene file's schema: every map with its valid keys. These are the very lists
/// the loader reads each map through (an unknown key is refused with them), so the
/// schema cannot drift from what is read; tests check docs/reference/scene-format.md against it.
/// A law map (`joint_sets.*.law`) also takes the parameters of its law, by the names
/// of laws::LawRegistry (`rheodda law list`); they are not listed here.
std::vector<SceneMapKeys> scene_schema();

}  // namespace rheodda::scene
