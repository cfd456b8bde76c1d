// The contact system's state between two steps, taken and restored
// (ContactSystem::State; a resumed run, docs/reference/outputs.md "Interrupting and
// resuming"). What begin_step rebuilds from the committed records (the hot
// data, seams, law constants, the keys of the last step, the broad phase's
// buffers) and what lives only within a step (the trial records, the
// step-start records a retraction swaps back) is not part of it.
#include <stdexcept>
#include <string>

#include "rheodda/contact/contact_system.hpp"

namespace rheodda::contact {

ContactSystem::State ContactSystem::state() const {
  State s;
  records_.save(s);
  s.work = energy_.committed;
  s.penalty = penalty_;
  s.allowed_penetration = allowed_penetration_;
  s.last_max_penetration = last_max_penetration_;
  s.stored_before = energy_.stored_before;
  s.previous_stress = creep_error_.previous_stress();
  s.previous_dt = creep_error_.previous_dt();
  s.creep_error = creep_error_.error();
  s.creep_changes = creep_error_.state_changes();
  return s;
}

void ContactSystem::restore(const State& s) {
  // Everything checked before anything is taken up: a refused state leaves the system as it was.
  ContactRecords::check(s, joint_sets_.size());
  if (!s.work.empty() && s.work.size() != s.contacts.size())
    throw std::invalid_argument("contact state: its energy records do not match its " +
                                std::to_string(s.contacts.size()) + " contacts");
  if (!(s.penalty > 0.0)) throw std::invalid_argument("contact state: its penalty is not positive");
  records_.restore(s);
  energy_.committed = s.work;
  penalty_ = s.penalty;
  allowed_penetration_ = s.allowed_penetration;
  last_max_penetration_ = s.last_max_penetration;
  energy_.stored_before = s.stored_before;
  creep_error_.restore(s.previous_stress, s.previous_dt, s.creep_error, s.creep_changes);
  // Between two steps: no trial, nothing to retract.
  abandon_step();
  start_.records.clear();
  start_.work.clear();
  start_.retractable = false;
}

}  // namespace rheodda::contact
