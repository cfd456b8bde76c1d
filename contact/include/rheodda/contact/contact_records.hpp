// The contact records of a ContactSystem (contact_system.hpp): those of the last
// accepted step (committed) and those of the step being solved (work), each with
// the creep histories its contacts own and their creep increments, the creep
// counters per joint set and the next contact id. The records of a step are
// built apart from the committed ones, so that abandoning the step drops them
// and accepting it swaps them in: the step-start states are never overwritten
// by a trial.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rheodda/contact/contact_record.hpp"
#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::contact {

struct ContactSystemState;

/// One set of contact records with what they own, parallel arrays.
struct RecordSet {
  std::vector<Contact> contacts;               ///< sorted by key
  std::vector<laws::RheologyState> rheology;   ///< creep histories, indexed by Contact::rheology
  std::vector<double> creep;                   ///< creep increment Delta d_c of the step, parallel to contacts [length]

  void clear() {
    contacts.clear();
    rheology.clear();
    creep.clear();
  }
  void swap(RecordSet& other) noexcept {
    contacts.swap(other.contacts);
    rheology.swap(other.rheology);
    creep.swap(other.creep);
  }
};

/// The records of the last accepted step and of the step being solved.
struct ContactRecords {
  RecordSet committed;  ///< the last accepted step's
  RecordSet work;       ///< the step being solved's (trial states); empty between steps
  std::vector<CreepCounters> counters;  ///< per joint set, accepted steps only
  std::uint64_t next_id = 1;            ///< id of the next new contact

  /// The committed records with their creep histories and increments, the counters
  /// and the next id into a saved state (ContactSystem::state; contact_records.cpp).
  void save(ContactSystemState& s) const;
  /// Throws std::invalid_argument ("contact state: ...") unless the records of the saved
  /// state `s` can be those of a system with `joint_sets` joint sets: a counter per joint
  /// set, a creep increment per contact (or none), each contact's joint set, rheology
  /// slot and id in range, the contacts sorted by key.
  static void check(const ContactSystemState& s, std::size_t joint_sets);
  /// Takes up the records of a saved state that check accepted, as the committed ones.
  void restore(const ContactSystemState& s);
};

}  // namespace rheodda::contact
