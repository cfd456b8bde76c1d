// `rheodda run`: a scene through the DDA engine with contacts, writing the
// outputs (docs/reference/outputs.md) as it goes, stoppable between steps and resumable.
//
// Resume. A checkpoint (checkpoint.json, rewritten whole at output frames at
// most once a second, and when a run stops) records the accepted steps, the
// time, the frames written, the byte length and hash of each CSV, a hash of the
// scene text, and the state file that holds the engine, contact and run-total
// state of that step (checkpoint_state.hpp: versioned, checksummed, written
// first). Resuming checks the state file, takes the state up, truncates the
// CSVs to those lengths and carries on writing: it computes no step again
// (unless a frame the checkpoint lists was lost: then the steps up to it). The
// result is the same as that of an uninterrupted run, byte for byte.
#pragma once

#include <limits>

#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "rheodda/core/engine.hpp"

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

struct RunOptions {
  std::string out_dir;   ///< created if missing
  bool resume = false;   ///< continue from out_dir/checkpoint.json
  /// Show the progress on `progress_stream` (progress.hpp; docs/reference/cli.md, "Progress"):
  /// a line redrawn in place on a terminal, else a plain line at the start, every 10 s and at the end.
  bool progress = false;
  std::FILE* progress_stream = stderr;
  /// When non-null and set non-zero (e.g. by a SIGINT handler), the run stops after
  /// the current step, leaving every file consistent and a checkpoint to resume from; a step
  /// taken in cycles (the explicit step, static steps by cycles) is abandoned within its
  /// cycles instead (core::Engine::set_stop_request), the checkpoint at the step before it.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// When >= 0: stop exactly as on a signal once this many steps are accepted
  /// (scripted pauses; the tests' way to interrupt at a known step).
  int stop_after_step = -1;
  /// When >= 0: stop as on a signal within the step that follows this many accepted steps,
  /// at the first look its cycles take at the stop request (the tests' way to interrupt a
  /// step while it cycles); a step not taken in cycles is not stopped by it.
  int stop_within_step = -1;
};

enum class RunStatus { completed, interrupted };

struct RunResult {
  RunStatus status = RunStatus::completed;
  int steps = 0;                 ///< accepted steps (all, those before a resume included)
  int cuts = 0;                  ///< dt cuts over all steps
  int redone = 0;                ///< steps redone smaller by an adaptive control (creep_tolerance,
                                 ///< step_tolerance) over all steps
  int extrapolated = 0;          ///< steps accepted extrapolated under step_tolerance
  double max_penetration = 0.0;  ///< largest contact penetration of any step [length]
  double time = 0.0;             ///< simulated time reached [time]
  int frames = 0;                ///< output frames written
  double wall_seconds = 0.0;     ///< wall time of this and earlier (resumed) sessions [s]
  int resumed_from_step = -1;    ///< -1: not resumed
  int steps_computed = 0;        ///< steps this process computed: of a resume, those after its
                                 ///< checkpoint (and the steps run again to write a lost frame) [-]
  std::vector<std::string> warnings;
  /// Per joint set with a creep law: the contacts the law advanced and their
  /// contact-time [time] (contact::ContactSystem::creep_counters).
  struct JointCreep {
    std::string joint_set;
    int contacts = 0;
    double contact_time = 0.0;
    int failures = 0;  ///< contacts whose damage law failed (damage 1) [-]
    double first_failure_time = std::numeric_limits<double>::quiet_NaN();  ///< end of the step in
                       ///< which the first of them failed; NaN if none [time]
  };
  std::vector<JointCreep> creep;
  /// A static analysis's mechanism motion (docs/reference/engine.md, "Mechanisms in static
  /// analysis"; core::inertia_share): how much of the work of gravity and loads the
  /// static steps' inertia terms took, and which steps moved as a mechanism.
  struct StaticMechanism {
    bool static_analysis = false;  ///< the scene's analysis is static (else nothing below is set)
    double inertia_share = 0.0;    ///< all steps: integration_inertia / work of gravity and loads [-]
    int steps = 0;                 ///< steps whose own share exceeded core::kMechanismStepShare [-]
    double first_time = std::numeric_limits<double>::quiet_NaN();  ///< end of the first of them [time]
    int first_step = -1;           ///< index of the first of them (-1: none) [-]
    double last_time = std::numeric_limits<double>::quiet_NaN();   ///< end of the last of them [time]
    /// Start of each collapse stage (analysis.settle.collapse_dt; docs/reference/engine.md,
    /// "Collapse stages") [time].
    std::vector<double> collapse_stages;
  };
  StaticMechanism mechanism;
  /// The dynamic stages that have ended (analysis.settle; docs/reference/engine.md,
  /// "Dynamic stages"), as in events.csv.
  std::vector<core::StageEvent> events;
};

/// Runs the scene; `scene_text` is the file's text (echoed in summary.json, hashed in
/// checkpoints). Throws SceneError for a scene the engine refuses, std::runtime_error
/// when the run fails (summary.json then says "failed" and why).
RunResult run_scene(const SceneDescription& scene, const std::string& scene_text, const RunOptions& options);

}  // namespace rheodda::scene
