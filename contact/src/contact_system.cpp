// ContactSystem (contact_system.hpp): construction and the checks of the joint
// sets, output names, abandoning a step. The other concerns are one file each:
// contact_transfer.cpp (detection and transfer of states into a step),
// contact_springs.cpp (springs, dashpots and their assembly), contact_check.cpp
// (the open-close check of a trial), contact_creep.cpp (the creep laws'
// coupling), contact_commit.cpp (accepting a step), contact_extrapolation.cpp
// (Richardson extrapolation), contact_energy.cpp (energy balance).
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"

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

namespace {

/// A number in its shortest form, as the scene loader prints it ({:g}: 60, 0.25, 1e+09).
std::string shortest(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void check_joint_set(const JointSet& js, size_t index) {
  // The loader's words for the same values (read_joint_sets.cpp, keys_joints.cpp).
  auto refuse = [&](const char* key, const std::string& message) {
    throw JointSetError(index, js.name, key, message);
  };
  auto bad = [&](const char* key, double v) { refuse(key, shortest(v) + " must be > 0"); };
  if (!(js.friction_angle >= 0.0) || !(js.friction_angle < 90.0))
    refuse("friction_angle", shortest(js.friction_angle) + " is out of range [0, 90) [deg]");
  if (!(js.cohesion >= 0.0)) refuse("cohesion", shortest(js.cohesion) + " must be >= 0");
  if (js.residual_friction_angle && !(*js.residual_friction_angle >= 0.0))
    refuse("residual_friction_angle", shortest(*js.residual_friction_angle) + " is out of range [0, 90) [deg]");
  if (js.residual_friction_angle && !(*js.residual_friction_angle <= js.friction_angle))
    refuse("residual_friction_angle", shortest(*js.residual_friction_angle) + " deg is above the peak friction_angle " +
                                          shortest(js.friction_angle) +
                                          " deg: a residual strength is at most the peak");
  if (!(js.residual_cohesion >= 0.0)) refuse("residual_cohesion", shortest(js.residual_cohesion) + " must be >= 0");
  if (!(js.residual_cohesion <= js.cohesion))
    refuse("residual_cohesion", shortest(js.residual_cohesion) + " is above the peak cohesion " +
                                    shortest(js.cohesion) + ": a residual strength is at most the peak");
  if (!(js.tensile_strength >= 0.0)) refuse("tensile_strength", shortest(js.tensile_strength) + " must be >= 0");
  if (js.normal_stiffness && !(*js.normal_stiffness > 0.0)) bad("normal_stiffness", *js.normal_stiffness);
  if (js.shear_stiffness && !(*js.shear_stiffness > 0.0)) bad("shear_stiffness", *js.shear_stiffness);
  if (js.restitution && !(*js.restitution >= 0.0 && *js.restitution <= 1.0))
    refuse("restitution", shortest(*js.restitution) + " is out of range [0, 1]");
  // One elastic shear stiffness per joint: a law's instantaneous spring E1 is it.
  if (js.law && js.law->instantaneous_stiffness() && js.shear_stiffness)
    refuse("shear_stiffness", "shear_stiffness and the E1 of law '" + std::string(js.law->name()) +
                                  "' both set the joint's elastic shear stiffness; give only E1");
}

ContactSystem::ContactSystem(std::vector<JointSet> joint_sets, ContactSettings settings)
    : joint_sets_(std::move(joint_sets)), settings_(settings), penalty_(settings.penalty) {
  if (!(settings_.penalty > 0.0))
    throw std::invalid_argument("contact penalty = " + std::to_string(settings_.penalty) +
                                " must be > 0 (Shi: 10-100 x Young's modulus)");
  if (!(settings_.shear_normal_ratio > 0.0))
    throw std::invalid_argument("shear_normal_ratio must be > 0");
  if (joint_sets_.empty()) {
    JointSet js;
    js.name = "default";
    joint_sets_.push_back(js);
  }
  for (size_t k = 0; k < joint_sets_.size(); ++k) check_joint_set(joint_sets_[k], k);
  creep_counters_.assign(joint_sets_.size(), CreepCounters{});
}

void ContactSystem::abandon_step() {
  work_.clear();
  work_rheology_.clear();
  work_creep_.clear();
  hot_.clear();
  seams_.clear();
}

}  // namespace rheodda::contact
