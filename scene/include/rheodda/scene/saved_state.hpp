// An engine's and its contact system's state between two steps as bytes, in
// the format of a checkpoint's state file (checkpoint_state.hpp;
// docs/reference/outputs.md, "Interrupting and resuming"): the engine part of
// what rheodda.Simulation.save() holds (docs/guide/python.md, "Saving and
// restoring"). Doubles are kept bit for bit.
#pragma once

#include <string>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/engine.hpp"

namespace rheodda::scene {

struct EngineSnapshot {
  core::EngineState engine;                ///< Engine::save()
  contact::ContactSystem::State contacts;  ///< ContactSystem::state()
};

/// The state file's bytes of `s`, for the scene whose YAML text is `scene_text`
/// with `joint_sets` joint sets.
std::string encode_snapshot(const EngineSnapshot& s, const std::string& scene_text, std::size_t joint_sets);

/// Reads encode_snapshot's bytes back; refuses (std::invalid_argument naming
/// `what`) bytes that are not a state, of another format or program version,
/// of another scene text, cut or not matching their checksum.
EngineSnapshot decode_snapshot(const std::string& bytes, const std::string& what, const std::string& scene_text);

}  // namespace rheodda::scene
