// The progress display of `rheodda run` (docs/reference/cli.md, "Progress"): the
// stage, the simulated time, the steps and the time left. Part of Run
// (run_internal.hpp); the code is run_progress.cpp.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

#include "rheodda/core/engine.hpp"
#include "rheodda/scene/progress.hpp"

namespace rheodda::scene {

struct Run;

class RunProgress {
 public:
  /// Off when `stream` is null (RunOptions::progress false).
  explicit RunProgress(std::FILE* stream) : display_(stream) {}
  /// The first line: the state the run starts from.
  void start(const Run& run);
  /// After each accepted step (cheap when nothing is due).
  void step(const Run& run, const core::StepReport& r);
  /// The last line ("completed", "interrupted"), and the end of the redrawn line.
  void end(const Run& run, const char* how);

 private:
  /// Follows the engine's dynamic stages and the scene's stages; a new one starts a new rate.
  void follow(const Run& run, const core::StepReport* r);
  std::string text(const Run& run, const char* how);

  Progress display_;
  RateEstimate rate_;
  std::string phase_;                 ///< the stage shown ("creep", "stage 'dig': settling")
  bool in_dynamic_ = false;           ///< the engine is in a dynamic stage (settling, mechanism)
  core::StageKind kind_ = core::StageKind::settling;
  std::size_t events_ = 0;            ///< the engine's ended stages when last looked at
  double phase_start_ = 0.0;          ///< simulated time at which the shown stage began [time]
  bool creep_ = false;                ///< a joint set has a creep law
};

}  // namespace rheodda::scene
