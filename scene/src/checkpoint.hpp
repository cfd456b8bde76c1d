// checkpoint.json (docs/reference/outputs.md, "Interrupting and resuming"): where an
// interrupted run stands. Its step and time, how much of history.csv and
// contacts.csv it had written (length and hash), the frames with a hash of
// each, and the state file (checkpoint_state.hpp) that holds the engine and
// contact state of that step. Rewritten whole (to a temporary name, flushed,
// renamed) after the state file it names.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint_state.hpp"

namespace rheodda::scene {

struct Checkpoint {
  std::string scene_hash;  ///< FNV-1a of the scene text (hex)
  std::string scene_file;  ///< the scene's file, for the message refusing another scene
  std::string title;
  int step = 0;            ///< accepted steps [-]
  double time = 0.0;       ///< [time]
  double wall_seconds = 0.0;  ///< of this and earlier sessions [s]
  std::uint64_t history_bytes = 0, history_hash = 0;    ///< history.csv as written [byte], FNV-1a
  std::uint64_t contacts_bytes = 0, contacts_hash = 0;  ///< contacts.csv likewise
  std::vector<std::pair<double, std::string>> frames;   ///< (time, file) as blocks.pvd lists them
  std::vector<std::uint64_t> frame_hashes;              ///< FNV-1a of each frame's two files
  StateFile state;
};

/// checkpoint.json's text.
std::string checkpoint_text(const Checkpoint& ck);

/// Reads `path` (OUT/checkpoint.json) to resume `scene_file`, whose text hashes
/// to `scene_hash`, where at most `max_frames` frames are due. Refuses
/// (std::invalid_argument naming the file and what is wrong) a checkpoint that
/// cannot be read, one of another scene, one without a state file (written by
/// a rheodda that resumed by running the steps again) and an inconsistent one.
Checkpoint read_checkpoint(const std::string& path, const std::string& scene_file, const std::string& scene_hash,
                           std::size_t max_frames);

}  // namespace rheodda::scene
