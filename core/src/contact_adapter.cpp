#include "rheodda/core/contact_adapter.hpp"

#include <algorithm>

namespace rheodda::core {

contact::ContactSettings contact_settings_for(const Model& model, double penalty_factor) {
  double e_max = 0.0;
  for (const Material& m : model.materials) e_max = std::max(e_max, m.young_modulus);
  contact::ContactSettings s;
  s.penalty = penalty_factor * e_max;
  return s;
}

void ContactAdapter::begin_step(std::span<const contact::BlockView> blocks, const StepContext& ctx) {
  system_.begin_step(blocks, ctx.max_displacement, ctx.dt);
}

void ContactAdapter::assemble(std::span<const contact::BlockView> blocks,
                              contact::SystemSink& sink) {
  system_.assemble(blocks, sink);
}

ContactCheck ContactAdapter::check(std::span<const contact::BlockView> blocks,
                                   const Eigen::VectorXd& D) {
  const contact::CheckResult r = system_.check(blocks, D);
  return {r.state_changes, r.max_penetration};
}

void ContactAdapter::end_step(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) {
  system_.end_step(blocks, D);
}

void ContactAdapter::abandon_step() { system_.abandon_step(); }

}  // namespace rheodda::core
