// The records a saved state carries (contact_records.hpp, contact_system_state.hpp): taken,
// checked and taken up again (ContactSystem::state and restore, contact_state.cpp).
#include "rheodda/contact/contact_records.hpp"

#include <stdexcept>
#include <string>

#include "rheodda/contact/contact_system_state.hpp"

namespace rheodda::contact {

void ContactRecords::save(ContactSystemState& s) const {
  s.contacts = committed.contacts;
  s.rheology = committed.rheology;
  s.creep = committed.creep;
  s.counters = counters;
  s.next_id = next_id;
}

void ContactRecords::check(const ContactSystemState& s, std::size_t joint_sets) {
  auto refuse = [](const std::string& what) {
    throw std::invalid_argument("contact state: " + what);
  };
  const std::size_t n = s.contacts.size();
  if (s.counters.size() != joint_sets)
    refuse("it has " + std::to_string(s.counters.size()) + " joint sets, this system " +
           std::to_string(joint_sets));
  if (!s.creep.empty() && s.creep.size() != n)
    refuse("its creep increments do not match its " + std::to_string(n) + " contacts");
  for (std::size_t c = 0; c < n; ++c) {
    const Contact& r = s.contacts[c];
    if (r.joint_set < 0 || r.joint_set >= static_cast<int>(joint_sets) || r.rheology < -1 ||
        r.rheology >= static_cast<int>(s.rheology.size()) || r.id == 0 || r.id >= s.next_id)
      refuse("contact " + std::to_string(c) + " has a joint set, rheology slot or id out of range");
    if (c > 0 && r.key < s.contacts[c - 1].key) refuse("its contacts are not sorted by key");
  }
}

void ContactRecords::restore(const ContactSystemState& s) {
  committed.contacts = s.contacts;
  committed.rheology = s.rheology;
  committed.creep = s.creep;
  counters = s.counters;
  next_id = s.next_id;
}

}  // namespace rheodda::contact
