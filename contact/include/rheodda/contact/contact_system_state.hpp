// A ContactSystem's state between two steps (contact_system.hpp; a resumed run,
// docs/reference/outputs.md "Interrupting and resuming"): what ContactSystem::state()
// gives and restore() takes up. The checkpoint files write its fields in order
// (scene/src/checkpoint_state.cpp).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "rheodda/contact/contact_record.hpp"
#include "rheodda/contact/energy_book.hpp"
#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::contact {

/// Everything of the system that the next steps depend on, between two
/// steps (contact_state.cpp): the records of the last accepted step with
/// their creep histories and energy terms, the counters, the penalty as
/// raised so far, the next contact id, and the stresses the creep error
/// estimate remembers. A system restored from it steps on bit for bit as
/// the one it was taken from (a resumed run, docs/reference/outputs.md).
struct ContactSystemState {
  std::vector<Contact> contacts;                 ///< contacts(), sorted by key
  std::vector<laws::RheologyState> rheology;     ///< rheology_states()
  std::vector<double> creep;                     ///< creep_increments() [length]
  std::vector<StepWork> work;                    ///< energy terms of the last step, parallel to contacts
  std::vector<CreepCounters> counters;           ///< creep_counters(), per joint set
  double penalty = 0.0;                          ///< [stress]
  double allowed_penetration = 0.0;              ///< [length]
  double last_max_penetration = 0.0;             ///< [length]
  double stored_before = 0.0;                    ///< stored energy before the last step [force x length]
  std::uint64_t next_id = 1;
  /// Stress at the last step's start by contact id, sorted by id [stress].
  std::vector<std::pair<std::uint64_t, double>> previous_stress;
  double previous_dt = 0.0;                      ///< last accepted step with the creep estimate [time]
  double creep_error = 0.0;                      ///< creep_error_estimate() [length]
  int creep_changes = 0;                         ///< creep_state_changes() [-]
};

}  // namespace rheodda::contact
