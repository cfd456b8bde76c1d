// The record of one contact between steps (docs/reference/contacts.md): its
// identity, state, locking point, forces, accumulated shear and creep, and the
// slot of its creep law's history. ContactSystem keeps them (contact_records.hpp)
// and hands them out as its output.
#pragma once

#include <cstdint>

#include "rheodda/contact/detection.hpp"

namespace rheodda::contact {

/// State of a contact.
enum class ContactState : std::uint8_t {
  open,     ///< no spring, no force
  sliding,  ///< normal spring + Mohr-Coulomb friction force along the entrance edge
  locked    ///< normal spring + shear spring to the locking point
};

/// Name used in outputs: "open", "sliding", "locked".
const char* contact_state_name(ContactState s);

/// What the joint set's creep law did to a contact in the last accepted step.
enum class CreepState : std::uint8_t {
  none,      ///< the joint set has no law
  creeping,  ///< locked: the law advanced its history and moved its locking point
  idle       ///< has a law but did not creep: open or sliding (history lost), or a step without creep time (dt = 0)
};

/// Name used in outputs: "none", "creeping", "idle".
const char* creep_state_name(CreepState s);

/// Creep counters of one joint set since the ContactSystem was made (restored
/// with the system on rollback).
struct CreepCounters {
  int contacts = 0;            ///< contacts the law advanced in at least one accepted step [-]
  double contact_time = 0.0;   ///< sum over accepted steps of dt x contacts it advanced [time]
  int failures = 0;            ///< contacts whose law reached failure (damage 1) [-]
};

/// Persistent record of one contact (also the per-step output record).
/// Forces are per unit thickness [force/length]; positive normal force is compression.
struct Contact {
  std::uint64_t id = 0;  ///< unique, kept from step to step while the contact persists
  ContactKey key;        ///< vertex block/vertex, entrance-edge block/edge
  ContactKind kind = ContactKind::vertex_edge;
  ContactState state = ContactState::open;
  int joint_set = 0;          ///< joint set of the entrance edge
  double length = 0.0;        ///< contact length [length] (half the shared length for edge_edge)
  /// Joint length the contact stands for in its joint set's law [length]:
  /// `length` for edge_edge, point_tributary_length (detection.hpp) for a point
  /// contact; on a joint set with a law it sets the shear spring (E1 l_t or
  /// shear_stiffness l_t) and the stress tau = F / l_t. Step-start geometry.
  double tributary_length = 0.0;
  double locking_ratio = 0.0; ///< locking point P0 on the entrance edge, as a fraction of its length [-]
  int slide_direction = 0;    ///< +1 / -1: the vertex slides along +/- the edge direction
  double normal_force = 0.0;  ///< p_n d_n [force/length]
  double shear_force = 0.0;   ///< along the edge direction a->b; p_s d_t (locked) or friction (sliding) [force/length]
  double shear_displacement = 0.0;  ///< accumulated relative slip + shear of the vertex along the edge [length]
  double penetration = 0.0;   ///< d_n at the end of the step (trial records: of the last iterate), > 0 into the edge's block [length]
  bool intact = true;         ///< cohesion and tensile strength act until the contact first slides or opens
  int rheology = -1;          ///< slot in rheology_states(), or -1 without a law
  /// Accumulated creep of the contact along the edge direction a->b [length]:
  /// the sum of its creep increments Delta d_c since it was created. Kept
  /// through transfer to the adjacent edge and changes of kind; not reset
  /// when it slides or opens (the law's history is, rheology_states()).
  double creep_displacement = 0.0;
  CreepState creep_state = CreepState::none;  ///< in the last accepted step
  bool has_crept = false;     ///< the law advanced it in at least one accepted step
  /// Its damage law reached failure (docs/reference/rheology-in-dda.md, "Failure"): from
  /// then on a residual frictional joint (no cohesion, no tensile strength, no creep).
  bool creep_failed = false;
};

}  // namespace rheodda::contact
