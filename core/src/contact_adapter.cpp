#include "rheodda/core/contact_adapter.hpp"

#include "rheodda/core/defaults.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rheodda::core {

contact::ContactSettings contact_settings_for(const Model& model, double penalty_factor) {
  contact::ContactSettings s;
  s.penalty = penalty_factor * largest_young_modulus(model.materials);  // defaults.hpp
  // Dynamic analysis, or a dynamic settling stage (ContactSettings::lock_at_touch;
  // the steps say which are dynamic: StepContext::dynamic).
  s.lock_at_touch = model.settings.has_dynamic_steps();
  s.reversal_at_normal_resolution = s.lock_at_touch;     // (ContactSettings::reversal_at_normal_resolution)
  return s;
}

void ContactAdapter::begin_step(std::span<const contact::BlockView> blocks, const StepContext& ctx) {
  system_.begin_step(blocks, ctx);  // what the contacts need of the step (contact_model.hpp)
}

void ContactAdapter::assemble(std::span<const contact::BlockView> blocks,
                              contact::SystemSink& sink) {
  system_.assemble(blocks, sink);
}

ContactCheck ContactAdapter::check(std::span<const contact::BlockView> blocks,
                                   const Eigen::VectorXd& D) {
  return system_.check(blocks, D);
}

ContactCheck ContactAdapter::end_cycles(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D,
                                        const Eigen::VectorXd& V) {
  return system_.end_cycles(blocks, D, V);
}

void ContactAdapter::end_step(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) {
  system_.end_step(blocks, D);
}

void ContactAdapter::abandon_step() { system_.abandon_step(); }

namespace {
struct SystemSnapshot final : ContactSnapshot {
  explicit SystemSnapshot(const contact::ContactSystem& s) : system(s) {}
  contact::ContactSystem system;
};
}  // namespace

std::unique_ptr<ContactSnapshot> ContactAdapter::snapshot() const {
  return std::make_unique<SystemSnapshot>(system_);
}

void ContactAdapter::restore(const ContactSnapshot& s) {
  system_ = dynamic_cast<const SystemSnapshot&>(s).system;
}

bool ContactAdapter::extrapolate(const ContactSnapshot& coarse) {
  return system_.extrapolate(dynamic_cast<const SystemSnapshot&>(coarse).system);
}

bool ContactAdapter::retract_step() { return system_.retract_step(); }

}  // namespace rheodda::core
