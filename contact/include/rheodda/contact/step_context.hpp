// What ContactSystem::begin_step needs to know of the step it begins
// (docs/reference/contacts.md): how far the blocks may move, how long the creep
// laws integrate over, and which of the dynamic rules apply. The host's own
// step context (core's StepContext, contact_model.hpp) extends it with the
// step's index and time, so each field is stated here alone.
#pragma once

namespace rheodda::contact {

/// The step a contact system begins (ContactSystem::begin_step).
struct StepContext {
  /// Allowed displacement per step [length]: contacts are searched within
  /// ContactSettings::search_factor times it (0: from the model's size).
  double max_displacement = 0.0;
  /// Step size the creep laws integrate over [time] (0: no creep).
  double dt = 0.0;
  /// The step carries velocity (a dynamic analysis, or a dynamic settling stage):
  /// the contact dashpots act and the dynamic rules (ContactSettings::lock_at_touch,
  /// reversal_at_normal_resolution) apply where set. In a static step (false: a
  /// static analysis after a dynamic settling stage) they are off.
  bool dynamic = true;
  /// The step's inertia stiffness per unit mass, 1/(beta dt^2) of the host's
  /// Newmark scheme [1/time^2] (0: unknown; ContactSettings::reversal_at_normal_resolution).
  double inertia = 0.0;
  /// The host will ask creep_error_estimate() and may retract_step() after
  /// this step's end_step.
  bool creep_error_wanted = false;
};

}  // namespace rheodda::contact
