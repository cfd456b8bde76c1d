// The contact system's state between two steps, taken and restored
// (ContactSystem::State; a resumed run, docs/reference/outputs.md "Interrupting and
// resuming"). What begin_step rebuilds from the committed records (the hot
// data, seams, law constants, the keys of the last step, the broad phase's
// buffers) and what lives only within a step (the trial records, the
// step-start records a retraction swaps back) is not part of it.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "rheodda/contact/contact_system.hpp"

namespace rheodda::contact {

ContactSystem::State ContactSystem::state() const {
  State s;
  s.contacts = records_.committed.contacts;
  s.rheology = records_.committed.rheology;
  s.creep = records_.committed.creep;
  s.work = energy_.committed;
  s.counters = records_.counters;
  s.penalty = penalty_;
  s.allowed_penetration = allowed_penetration_;
  s.last_max_penetration = last_max_penetration_;
  s.stored_before = energy_.stored_before;
  s.next_id = records_.next_id;
  s.previous_stress = creep_error_.previous_stress();
  s.previous_dt = creep_error_.previous_dt();
  s.creep_error = creep_error_.error();
  s.creep_changes = creep_error_.state_changes();
  return s;
}

void ContactSystem::restore(const State& s) {
  auto refuse = [](const std::string& what) {
    throw std::invalid_argument("contact state: " + what);
  };
  const std::size_t n = s.contacts.size();
  if (s.counters.size() != joint_sets_.size())
    refuse("it has " + std::to_string(s.counters.size()) + " joint sets, this system " +
           std::to_string(joint_sets_.size()));
  if ((!s.creep.empty() && s.creep.size() != n) || (!s.work.empty() && s.work.size() != n))
    refuse("its creep increments or energy records do not match its " + std::to_string(n) + " contacts");
  for (std::size_t c = 0; c < n; ++c) {
    const Contact& r = s.contacts[c];
    if (r.joint_set < 0 || r.joint_set >= static_cast<int>(joint_sets_.size()) || r.rheology < -1 ||
        r.rheology >= static_cast<int>(s.rheology.size()) || r.id == 0 || r.id >= s.next_id)
      refuse("contact " + std::to_string(c) + " has a joint set, rheology slot or id out of range");
    if (c > 0 && r.key < s.contacts[c - 1].key) refuse("its contacts are not sorted by key");
  }
  if (!(s.penalty > 0.0)) refuse("its penalty is not positive");
  records_.committed.contacts = s.contacts;
  records_.committed.rheology = s.rheology;
  records_.committed.creep = s.creep;
  energy_.committed = s.work;
  records_.counters = s.counters;
  penalty_ = s.penalty;
  allowed_penetration_ = s.allowed_penetration;
  last_max_penetration_ = s.last_max_penetration;
  energy_.stored_before = s.stored_before;
  records_.next_id = s.next_id;
  creep_error_.restore(s.previous_stress, s.previous_dt, s.creep_error, s.creep_changes);
  // Between two steps: no trial, nothing to retract.
  abandon_step();
  start_.records.clear();
  start_.work.clear();
  start_.retractable = false;
}

}  // namespace rheodda::contact
