// Model edits between two steps (stages, docs/reference/stages.md): blocks removed with
// their contacts, joint sets given new values. Both act on the committed
// records only: they are called between accepted steps, never within one.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"
#include "rheodda/contact/contact_system.hpp"
#include "rheodda/contact/joint_set_specs.hpp"

namespace rheodda::contact {

void ContactSystem::remove_blocks(std::span<const char> removed) {
  if (removed_.size() < removed.size()) removed_.resize(removed.size(), 0);
  for (std::size_t b = 0; b < removed.size(); ++b)
    if (removed[b]) removed_[b] = 1;
  auto gone = [&](int b) { return b >= 0 && b < static_cast<int>(removed_.size()) && removed_[b]; };
  // Keep the records of contacts between blocks that stay, and the creep
  // histories they own (slots renumbered in order).
  std::vector<Contact> contacts;
  std::vector<laws::RheologyState> rheology;
  std::vector<double> creep;
  std::vector<StepWork> work;
  for (std::size_t c = 0; c < records_.committed.contacts.size(); ++c) {
    Contact r = records_.committed.contacts[c];
    if (gone(r.key.vblock) || gone(r.key.eblock)) continue;
    if (r.rheology >= 0) {
      rheology.push_back(records_.committed.rheology[static_cast<std::size_t>(r.rheology)]);
      r.rheology = static_cast<int>(rheology.size()) - 1;
    }
    if (c < records_.committed.creep.size()) creep.push_back(records_.committed.creep[c]);
    if (c < energy_.committed.size()) work.push_back(energy_.committed[c]);
    contacts.push_back(r);
  }
  records_.committed.contacts = std::move(contacts);
  records_.committed.rheology = std::move(rheology);
  records_.committed.creep = std::move(creep);
  energy_.committed = std::move(work);
  // The next step's restart energy (ContactEnergy::restart) is measured from
  // what the records left store, not from what the dropped ones stored.
  energy_.stored_before = EnergyBook::stored_energy(records_.committed.contacts, energy_.committed);
  // Nothing of the last step is left to retract, nor any trial.
  abandon_step();
  start_.retractable = false;
}

void ContactSystem::set_joint_set(int index, JointSet joint_set) {
  if (index < 0 || index >= static_cast<int>(joint_sets_.size()))
    throw std::invalid_argument("set_joint_set: no joint set " + std::to_string(index));
  const JointSet& old = joint_sets_[static_cast<std::size_t>(index)];
  if (joint_set.name != old.name)
    throw std::invalid_argument("set_joint_set: joint set " + std::to_string(index) + " is '" + old.name + "', not '" +
                                joint_set.name + "'");
  // The creep histories (laws::RheologyState) belong to the law that wrote
  // them: parameters may change, the law may not.
  const bool had = static_cast<bool>(old.law), has = static_cast<bool>(joint_set.law);
  if (had != has || (had && (old.law->name() != joint_set.law->name() ||
                             old.law->internal_count() != joint_set.law->internal_count())))
    throw std::invalid_argument("joint set '" + old.name + "': a stage can change its law's parameters, not " +
                                (had && has ? "replace law '" + std::string(old.law->name()) + "' by '" +
                                                  std::string(joint_set.law->name()) + "'"
                                            : std::string(had ? "remove its law" : "add a law")));
  check_joint_set(joint_set, static_cast<std::size_t>(index));
  joint_sets_[static_cast<std::size_t>(index)] = std::move(joint_set);
  abandon_step();
  start_.retractable = false;
}

}  // namespace rheodda::contact
