// Names of a contact record's states in outputs (contact_record.hpp).
#include "rheodda/contact/contact_record.hpp"

namespace rheodda::contact {

const char* contact_state_name(ContactState s) {
  switch (s) {
    case ContactState::open: return "open";
    case ContactState::sliding: return "sliding";
    case ContactState::locked: return "locked";
  }
  return "?";
}

const char* creep_state_name(CreepState s) {
  switch (s) {
    case CreepState::none: return "none";
    case CreepState::creeping: return "creeping";
    case CreepState::idle: return "idle";
  }
  return "?";
}

}  // namespace rheodda::contact
