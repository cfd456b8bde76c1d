// What `rheodda check` prints: the scene as it will be modelled, every default
// filled in, with an estimate of the contacts at the start.
#pragma once

#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// Human-readable account of the scene (units spelled out); ends with a newline.
std::string describe_scene(const SceneDescription& scene);

/// The scene as summary.json's "inputs" (one line of JSON; scene/src/scene_json.cpp):
/// every key the run used, defaults filled in.
std::string scene_json_text(const SceneDescription& scene);

/// The scheme's name, "automatic" when unset.
std::string scheme_text(const Analysis& analysis);

/// The shortest of 6, 10 or 17 significant digits that reads back exactly as `v`
/// (parameters in `check`, values written into scene and study files).
std::string exact_number(double v);

/// Contact search distance at the start: search_factor * max_displacement_ratio * w0 [length] (Shi's rule).
double search_distance(const SceneDescription& scene);

}  // namespace rheodda::scene
