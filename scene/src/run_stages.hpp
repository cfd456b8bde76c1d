// A run's stages (docs/reference/stages.md): which come next, what each did, and the
// names of the model's fixed points and loads as the stages change them.
// Part of Run (run_internal.hpp); the code is run_stages.cpp.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace rheodda::scene {

/// A stage that has begun: summary.json's `stages` list.
struct AppliedStage {
  std::string name;
  double time = 0.0;   ///< when it began [time]
  int step = 0;        ///< steps accepted before it [-]
  std::vector<std::string> actions;  ///< what it did, one phrase each
};

/// Thrown by the step observer when a stage `after: settled` is due at the end
/// of the step just taken (leaves Engine::run_until between two steps).
struct StageDue {};

/// The stages of a run.
struct StageRun {
  std::size_t next = 0;      ///< index of the next stage to begin
  std::string current;       ///< the stage in force: history.csv's `stage` column ("" before the first)
  std::vector<AppliedStage> applied;
  std::vector<std::string> fixed_names;  ///< name of each fixed point of the engine's model ("" unnamed)
  std::vector<std::string> load_names;   ///< name of each point load of the engine's model ("" unnamed)
  std::size_t watch_events = 0;  ///< engine events when the settling stage the next stage waits for opened
  bool due = false;              ///< an `after: settled` stage is due now
};

}  // namespace rheodda::scene
