// Adapter: the contact layer's ContactSystem driven by the host as a
// ContactModel (contact_model.hpp). The host owns the interface; the contact
// layer knows nothing of the engine.
//
// Usage:
//   rheodda::contact::ContactSystem contacts(joint_sets,
//       rheodda::core::contact_settings_for(model));
//   rheodda::core::ContactAdapter adapter(contacts);
//   rheodda::core::Engine engine(model, adapter);
//   engine.run(100);
//   for (const auto& c : contacts.contacts()) ...   // forces, shear, state, joint set
#pragma once

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_model.hpp"
#include "rheodda/core/model.hpp"

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

namespace rheodda::core {

/// Contact settings for a model: the normal penalty is `penalty_factor` times
/// the largest Young's modulus of the model's materials (the seed's eq. 17,
/// k1 = 10-100; default 40) [stress]; the other settings keep their defaults.
contact::ContactSettings contact_settings_for(const Model& model, double penalty_factor = 40.0);

class ContactAdapter final : public ContactModel {
 public:
  /// `system` is not owned and must outlive the adapter.
  explicit ContactAdapter(contact::ContactSystem& system) : system_(system) {}

  void begin_step(std::span<const contact::BlockView> blocks, const StepContext& ctx) override;
  void assemble(std::span<const contact::BlockView> blocks, contact::SystemSink& sink) override;
  ContactCheck check(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) override;
  void end_step(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) override;
  void abandon_step() override;
  /// Largest local creep error estimate of the last accepted step over the
  /// contacts locked with a law at both ends of the step [length]. For a joint
  /// set stepped with the lagged or implicit scheme: |Delta d_c(scheme) -
  /// Delta d_c(exponential-linear)| from the same history and start and end
  /// stresses (exponential-linear is exact for a force linear over the step).
  /// For exponential-linear: |tau''| dt^2/12 c, tau'' from the stresses at the
  /// last three step boundaries and c the implicit step compliance (~ dt/eta).
  /// Zero under a constant force. Computed only when the step context asked for it.
  double creep_error_estimate() const override { return creep_error_; }
  /// Restores the contact system and the estimate's history to the start of the
  /// last accepted step (a copy taken in end_step when the estimate was asked for).
  bool retract_step() override;
  /// Edge contacts on joint sets with a law whose state changed in the last
  /// accepted step (or that appeared closed, or vanished locked).
  int creep_state_changes() const override { return creep_changes_; }
  double time_to_failure() const override { return system_.time_to_failure(); }
  /// A copy of the contact system (records, histories, penalty) for step doubling.
  std::unique_ptr<ContactSnapshot> snapshot() const override;
  void restore(const ContactSnapshot& s) override;
  /// contact::ContactSystem::extrapolate with the snapshot's system.
  bool extrapolate(const ContactSnapshot& coarse) override;
  /// contact::ContactSystem::energy.
  ContactEnergy energy() const override { return system_.energy(); }

  contact::ContactSystem& system() { return system_; }
  const contact::ContactSystem& system() const { return system_; }
  /// Records of the last accepted step.
  std::span<const contact::Contact> contacts() const { return system_.contacts(); }

 private:
  contact::ContactSystem& system_;
  double dt_ = 0.0;            ///< step size of the step being solved [time]
  bool want_error_ = false;
  double creep_error_ = 0.0;   ///< [length]
  int creep_changes_ = 0;
  /// The contact system just before the last end_step (when the estimate was
  /// asked for): its committed records are the step-start states; retract_step
  /// copies it back.
  std::optional<contact::ContactSystem> saved_;
  bool can_retract_ = false;
  std::unordered_map<std::uint64_t, double> prev_tau_;  ///< stress at the last step's start, by contact id [stress]
  double prev_dt_ = 0.0;                                ///< last accepted step [time]
  std::unordered_map<std::uint64_t, double> saved_prev_tau_;  ///< prev_tau_ before the last end_step
  double saved_prev_dt_ = 0.0;                                ///< prev_dt_ before the last end_step [time]
};

}  // namespace rheodda::core
