// The bolts of a scene in `rheodda check` and summary.json (bolts_text.cpp);
// both add nothing for a scene without bolts.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// `rheodda check`'s lines on the bolts ("" without bolts).
std::string describe_bolts(const SceneDescription& s);
/// One bolt as `rheodda check` prints it: "NAME: ENDS, axial_stiffness ...".
std::string bolt_text(const SceneDescription& s, const BoltDescription& b);
/// One bolt as summary.json's "inputs" hold it (the keys of the scene file).
nlohmann::ordered_json bolt_json(const SceneDescription& s, const BoltDescription& b);
/// Every bolt of the scene in the engine's order (core::Model::bolts after every
/// stage): those of `bolts:`, then each stage's `add_bolts:` in stage order.
std::vector<const BoltDescription*> all_bolts(const SceneDescription& s);
/// The scene has bolts: in `bolts:`, or installed by a stage (bolts.csv and the
/// bolt columns of history.csv are written then).
bool has_bolts(const SceneDescription& s);

}  // namespace rheodda::scene
