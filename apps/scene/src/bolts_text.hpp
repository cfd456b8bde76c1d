// The bolts of a scene in `rheodda check` and summary.json (bolts_text.cpp);
// both add nothing for a scene without bolts.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// `rheodda check`'s lines on the bolts ("" without bolts).
std::string describe_bolts(const SceneDescription& s);
/// summary.json's "inputs": j["bolts"] (nothing without bolts).
void add_bolts_json(const SceneDescription& s, nlohmann::ordered_json& j);

}  // namespace rheodda::scene
