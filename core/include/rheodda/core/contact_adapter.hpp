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

#include "rheodda/core/defaults.hpp"

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_model.hpp"
#include "rheodda/core/model.hpp"


namespace rheodda::core {

/// Contact settings for a model: the normal penalty is `penalty_factor` times
/// the largest Young's modulus of the model's materials (the seed's eq. 17,
/// k1 = 10-100; default 40) [stress]; the other settings keep their defaults.
contact::ContactSettings contact_settings_for(const Model& model, double penalty_factor = kPenaltyFactor);

class ContactAdapter final : public ContactModel {
 public:
  /// `system` is not owned and must outlive the adapter.
  explicit ContactAdapter(contact::ContactSystem& system) : system_(system) {}

  void begin_step(std::span<const contact::BlockView> blocks, const StepContext& ctx) override;
  void assemble(std::span<const contact::BlockView> blocks, contact::SystemSink& sink) override;
  ContactCheck check(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) override;
  void end_step(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D) override;
  /// contact::ContactSystem::contact_forces.
  bool contact_forces(const Eigen::VectorXd& D, Eigen::VectorXd& f) const override {
    system_.contact_forces(D, f);
    return true;
  }
  /// contact::ContactSystem::begin_cycles, cycle_stiffness, cycle_forces, end_cycles.
  bool begin_cycles(std::span<const contact::BlockView> blocks, int threads) override {
    system_.begin_cycles(blocks, threads);
    return true;
  }
  void cycle_stiffness(std::vector<Mat6>& K) const override { system_.cycle_stiffness(K); }
  void cycle_damping(double tau, std::vector<Mat6>& C) override { system_.cycle_damping(tau, C); }
  void cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, Eigen::VectorXd& f) override {
    system_.cycle_forces(D, V, kick, f);
  }
  int cycle_relinearize(const Eigen::VectorXd& D) override { return system_.cycle_relinearize(D); }
  ContactCheck end_cycles(std::span<const contact::BlockView> blocks, const Eigen::VectorXd& D,
                          const Eigen::VectorXd& V) override;
  void abandon_step() override;
  /// contact::ContactSystem::creep_error_estimate (asked for by the step context).
  double creep_error_estimate() const override { return system_.creep_error_estimate(); }
  /// contact::ContactSystem::retract_step.
  bool retract_step() override;
  /// contact::ContactSystem::creep_state_changes.
  int creep_state_changes() const override { return system_.creep_state_changes(); }
  double time_to_failure() const override { return system_.time_to_failure(); }
  /// A copy of the contact system (records, histories, penalty) for step doubling.
  std::unique_ptr<ContactSnapshot> snapshot() const override;
  void restore(const ContactSnapshot& s) override;
  /// contact::ContactSystem::extrapolate with the snapshot's system.
  bool extrapolate(const ContactSnapshot& coarse) override;
  /// contact::ContactSystem::energy.
  ContactEnergy energy() const override { return system_.energy(); }
  /// contact::ContactSystem::remove_blocks (model_edits.cpp).
  int remove_blocks(std::span<const char> removed) override;
  /// contact::ContactSystem::set_joint_set (model_edits.cpp).
  void set_joint_set(int index, const contact::JointSet& joint_set) override;

  contact::ContactSystem& system() { return system_; }
  const contact::ContactSystem& system() const { return system_; }
  /// Records of the last accepted step.
  std::span<const contact::Contact> contacts() const { return system_.contacts(); }

 private:
  contact::ContactSystem& system_;
};

}  // namespace rheodda::core
