// A run's totals over its accepted steps (summary.json, RunResult;
// docs/reference/outputs.md "summary.json"), added up step by step. They need no list of
// every step's report, and a resumed run takes them up from its checkpoint
// (checkpoint_state.hpp) rather than from steps it does not compute again.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/scene/run.hpp"

namespace rheodda::scene {

struct RunTotals {
  int cuts = 0;                   ///< dt cuts [-]
  int redone = 0;                 ///< steps redone smaller by an adaptive control [-]
  int extrapolated = 0;           ///< steps accepted extrapolated (step_tolerance) [-]
  double max_penetration = 0.0;   ///< largest contact penetration of any step [length]
  core::ContactChanges contact_changes;  ///< what the open-close checks changed [-]
  /// Mechanism motion of a static analysis (RunResult::StaticMechanism; its
  /// inertia_share comes from the engine's energy balance, not from here).
  RunResult::StaticMechanism mechanism;
  /// Per joint set: the end of the step in which its first damage-law failure
  /// was counted (NaN: none yet) [time].
  std::vector<double> first_failure;
  /// (u, v) of each measurement point at the end of the settling stage (analysis.settle),
  /// in point order: what history.csv's POINT.u_after_settling counts from; empty before
  /// the stage has ended [length].
  std::vector<double> settled;

  /// `joint_sets`: how many the scene has; `static_analysis`: whether the
  /// mechanism figures are kept.
  RunTotals(std::size_t joint_sets, bool static_analysis);
  /// Adds the accepted step `r`, after which the contacts' creep counters are
  /// `counters` (indexed like the joint sets).
  void add(const core::StepReport& r, std::span<const contact::CreepCounters> counters);
};

}  // namespace rheodda::scene
