// Adaptive creep stepping's side of a ContactSystem (contact_system.hpp;
// docs/reference/step-controls.md, "Adaptive creep stepping"): the local creep
// error estimate of an accepted step, and what the commit replaced, kept so
// that a step whose estimate is too large can be retracted. The step-start
// records are those the commit swapped out, so neither the estimate nor a
// retraction copies the contact system.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rheodda/contact/contact_record.hpp"
#include "rheodda/contact/contact_records.hpp"
#include "rheodda/contact/energy_book.hpp"
#include "rheodda/contact/joint_set.hpp"
#include "rheodda/contact/step_arrays.hpp"
#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::contact {

/// What an end_step replaced beside the committed records, kept while its step
/// may be retracted (begin_step's creep_error_wanted; ContactSystem::retract_step).
struct StepStart {
  RecordSet records;             ///< the records at the step start
  std::vector<StepWork> work;    ///< their energy terms
  std::vector<CreepCounters> counters;  ///< per joint set, before the commit
  double last_max_penetration = 0.0;    ///< before the commit [length]
  double penalty = 0.0;                 ///< before the commit [stress]
  double stored_before = 0.0;           ///< before the commit [force x length]
  bool retractable = false;             ///< the last end_step can be retracted
};

/// The local creep error estimate of the accepted steps (contact_creep_error.cpp).
class CreepErrorEstimate {
 public:
  /// Estimates the step of `dt` [time] from the records `start` (with their
  /// histories `start_rheology`) to the committed records `end`: the largest
  /// local creep error over the contacts locked with a law at both ends
  /// (ContactSystem::creep_error_estimate) and the state changes of contacts
  /// on joint sets with a law (creep_state_changes). `law_steps`: the step's
  /// law constants per joint set (step_arrays.hpp).
  void estimate(std::span<const Contact> start, std::span<const laws::RheologyState> start_rheology,
                std::span<const Contact> end, std::span<const JointSet> joint_sets,
                std::span<const step::LawStep> law_steps, double dt);
  /// A step accepted without the estimate: no error, no changes.
  void skip() {
    error_ = 0.0;
    changes_ = 0;
  }
  /// Back to before the last estimate (its step retracted): no error, no changes.
  void retract();

  double error() const { return error_; }         ///< of the last accepted step [length]
  int state_changes() const { return changes_; }  ///< of the last accepted step [-]
  /// Stress at the last step's start by contact id, sorted by id (equal
  /// states give equal files) [stress].
  std::vector<std::pair<std::uint64_t, double>> previous_stress() const;
  double previous_dt() const { return prev_dt_; }  ///< last accepted step with the estimate [time]
  /// Takes up a saved estimate (ContactSystem::restore).
  void restore(std::span<const std::pair<std::uint64_t, double>> previous_stress, double previous_dt,
               double error, int state_changes);

 private:
  std::unordered_map<std::uint64_t, double> prev_tau_;  ///< stress at the last step's start, by contact id [stress]
  double prev_dt_ = 0.0;                                ///< last accepted step [time]
  std::unordered_map<std::uint64_t, double> retract_prev_tau_;  ///< prev_tau_ before the last estimate [stress]
  double retract_prev_dt_ = 0.0;                                ///< prev_dt_ before the last estimate [time]
  double error_ = 0.0;  ///< [length]
  int changes_ = 0;     ///< [-]
};

}  // namespace rheodda::contact
