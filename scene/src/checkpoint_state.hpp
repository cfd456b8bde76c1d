// The state file of a checkpoint (docs/reference/outputs.md, "Interrupting and
// resuming"): the engine, the contacts and the run's totals as they were after
// the checkpoint's step, so that `rheodda run --resume` carries on from there
// without computing any step again.
//
// Format: one line of JSON (the header: "rheodda_state" the format version,
// "program", "scene_hash", "step", "time" as a C99 hex float, "byte_order",
// "payload_bytes" and "payload_fnv1a"), then the payload: the state's numbers
// as raw bytes in the machine's byte order (doubles exactly, bit for bit),
// each vector preceded by its length. The file is written to a temporary name,
// flushed and renamed; checkpoint.json then names it with its length and hash.
#pragma once

#include <cstdint>
#include <string>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/engine.hpp"
#include "run_totals.hpp"

namespace rheodda::scene {

/// Version of the state file's format: raised with any change of what it holds
/// (a file of another version is refused, not misread).
inline constexpr int kStateFormat = 7;

/// The two names a state file alternates between, so that the file the current
/// checkpoint names is never the one being written.
inline constexpr const char* kStateFiles[2] = {"checkpoint-0.state", "checkpoint-1.state"};

/// Everything a resumed run takes up.
struct SavedRun {
  core::EngineState engine;  ///< Engine::save(); of the measurement points' samples only the last
  contact::ContactSystem::State contacts;
  RunTotals totals{0, false};
};

/// A state file as checkpoint.json names it.
struct StateFile {
  std::string name;         ///< in the output folder (one of kStateFiles)
  std::uint64_t bytes = 0;  ///< its length [byte]
  std::uint64_t hash = 0;   ///< FNV-1a of its bytes
};

/// The state file's bytes for `run` of the scene whose text hashes to `scene_hash`.
std::string encode_state(const SavedRun& run, const std::string& scene_hash);

/// Reads a state file's bytes back. Refuses (std::invalid_argument naming
/// `path` and what is wrong) a file that is not a state file, one of another
/// format version or program version, one of another scene (its scene hash is
/// not `scene_hash`), and one whose payload is cut or does not match its checksum.
SavedRun decode_state(const std::string& bytes, const std::string& path, const std::string& scene_hash);

/// Writes `run` into `out_dir` under the name of kStateFiles that `current`
/// (the file the last checkpoint names, or "") is not, durably (fsync), and
/// returns its entry for checkpoint.json.
StateFile write_state_file(const std::string& out_dir, const SavedRun& run, const std::string& scene_hash,
                           const std::string& current);

/// Reads the state file `entry` names in `out_dir`: decode_state, and refused
/// as well when the file is missing or is not the one checkpoint.json
/// recorded (length, hash).
SavedRun read_state_file(const std::string& out_dir, const StateFile& entry, const std::string& scene_hash);

}  // namespace rheodda::scene
