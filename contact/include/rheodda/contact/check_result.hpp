// What a check of trial displacements against the contact states found: the
// changes by kind and the deepest penetration. One type from the contact layer,
// where ContactSystem::check and end_cycles produce it, up to the host, which
// sums the changes into its step reports (core::ContactCheck and
// core::ContactChanges name these types; core/contact_model.hpp).
#pragma once

namespace rheodda::contact {

/// What the open-close iteration changed, by kind (docs/reference/contacts.md, "States and
/// the open-close iteration") [contacts].
struct ContactChanges {
  int closed = 0;       ///< open -> locked or sliding
  int opened = 0;       ///< locked or sliding -> open
  int slipped = 0;      ///< locked -> sliding
  int stuck = 0;        ///< sliding -> locked
  int refinements = 0;  ///< no state change, but one more iterate asked for (a sliding
                        ///< contact's friction force moved, a piecewise law changed piece,
                        ///< a nonlinear law's Newton model not yet within its tolerance)
  /// Of closed ... stuck, the changes that undo the contact's last change in the
  /// step (A -> B -> A, a 2-cycle; docs/notes/rock-mass-steps.md), and of those the
  /// corner (vertex-vertex) contacts' (diagnosis; not counted in total()).
  int cycled = 0, cycled_corners = 0;
  int total() const { return closed + opened + slipped + stuck + refinements; }
  ContactChanges& operator+=(const ContactChanges& o) {
    closed += o.closed, opened += o.opened, slipped += o.slipped, stuck += o.stuck;
    refinements += o.refinements;
    cycled += o.cycled, cycled_corners += o.cycled_corners;
    return *this;
  }
};

/// Result of checking a trial solution against the contact states.
struct CheckResult {
  int state_changes = 0;         ///< changes that ask for another iterate (0: converged):
                                 ///< open<->closed and slide<->lock changes, plus sliding
                                 ///< contacts whose friction force is not yet settled
  double max_penetration = 0.0;  ///< largest d_n over closed contacts [length]
  ContactChanges changes;        ///< state_changes by kind (they add up to it; left zero by
                                 ///< contact models that do not tell the kinds apart)
};

}  // namespace rheodda::contact
