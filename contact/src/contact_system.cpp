// ContactSystem (contact_system.hpp): construction and the checks of the joint
// sets, abandoning a step. The other concerns are one file each:
// contact_transfer.cpp (detection and transfer of states into a step),
// contact_springs.cpp (springs, dashpots and their assembly), contact_check.cpp
// (the open-close check of a trial), contact_creep.cpp (the creep laws'
// coupling), contact_commit.cpp (accepting a step), contact_extrapolation.cpp
// (Richardson extrapolation), contact_energy.cpp (energy balance),
// contact_creep_error.cpp (the creep error estimate and retraction),
// contact_state.cpp (the state between steps), contact_edits.cpp (model edits),
// contact_cycles.cpp (explicit cycles), contact_record.cpp (output names),
// contact_records.cpp (the records of a saved state, checked).
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"
#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/contact/joint_set_specs.hpp"

namespace rheodda::contact {

ContactSystem::ContactSystem(std::vector<JointSet> joint_sets, ContactSettings settings)
    : joint_sets_(std::move(joint_sets)), settings_(settings), penalty_(settings.penalty) {
  if (!(settings_.penalty > 0.0))
    throw std::invalid_argument("contact penalty = " + std::to_string(settings_.penalty) +
                                " must be > 0 (Shi: 10-100 x Young's modulus)");
  check_contact_setting_ranges(settings_);  // the declared settings (contact_settings_specs.hpp)
  if (joint_sets_.empty()) {
    JointSet js;
    js.name = "default";
    joint_sets_.push_back(js);
  }
  for (size_t k = 0; k < joint_sets_.size(); ++k) check_joint_set(joint_sets_[k], k);
  records_.counters.assign(joint_sets_.size(), CreepCounters{});
}

void ContactSystem::abandon_step() {
  records_.work.clear();
  step_.clear();
}

}  // namespace rheodda::contact
