// Reading a scene file (docs/scene-format.md) into a validated SceneDescription.
//
// Every key is known (an unknown one is an error with the nearest valid name),
// every value is type- and range-checked, NaN/inf are refused anywhere, names
// (materials, joint sets, blocks) must resolve, polygons must be simple with a
// positive area, blocks must not overlap at the start, and every fixed, load and
// measurement point must lie on a block. The first fault found throws a
// SceneError with file, line, column and key; nothing is returned half-read.
#pragma once

#include <string>

#include "rheodda/scene/error.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// The text of the scene file at `path`; throws SceneError if it cannot be read.
std::string read_scene_text(const std::string& path);

/// Reads and validates the scene file at `path`; throws SceneError.
SceneDescription load_scene(const std::string& path);

/// Parses and validates scene text; `file` names the source in error messages.
SceneDescription parse_scene(const std::string& text, const std::string& file);

}  // namespace rheodda::scene
