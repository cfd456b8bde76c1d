// Joint sets and contact settings: the inputs of the contact layer.
//
// Why this split. A joint set describes the rock (friction, cohesion, tensile
// strength, joint stiffness, optionally a creep law); ContactSettings describes
// the numerics (penalty, tolerances, iteration limit). Every block edge names
// the joint set it belongs to (BlockView::edge_joint_set), and a contact takes
// the joint set of its entrance edge.
//
// Units. 2D, unit thickness. A contact spring is a force per unit thickness per
// unit length of relative displacement, i.e. [force/length/thickness] = [stress],
// the unit of the penalty (the seed's eqs. 17-18: p_n = k1 E). Joint stiffnesses
// are given per unit joint area, [stress/length]; a contact with a contact length
// l (edge-edge contacts, each with half the shared length) gets the spring
// k_joint * l. Point contacts (vertex-edge, vertex-vertex: l = 0) use the
// penalty springs, except the shear spring on a joint set with a creep law:
// every contact there has a tributary length l_t (Contact::tributary_length)
// and the shear spring E1 l_t or shear_stiffness l_t.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::contact {

/// Damping ratio zeta [-] of a linear spring-dashpot contact whose free impact
/// has the coefficient of restitution e (Cundall & Strack 1979: a damped
/// half-oscillation returns e = exp(-zeta pi / sqrt(1 - zeta^2)); solved for
/// zeta): zeta = -ln e / sqrt(pi^2 + ln^2 e), 1 (critical: no rebound) at e = 0.
inline double restitution_damping_ratio(double e) {
  if (e <= 0.0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// A joint set refused by the contact layer (ContactSystem's constructor): which one,
/// as data (its index in the list given, and the key at fault), so that a reader can
/// point at its entry in a scene file without parsing the message. Its text names the
/// joint set and key as the scene loader does: "joint_sets.NAME.KEY: MESSAGE".
class JointSetError : public std::invalid_argument {
 public:
  JointSetError(std::size_t index, std::string name, std::string key, const std::string& message)
      : std::invalid_argument("joint_sets." + name + "." + key + ": " + message),
        index_(index),
        key_(std::move(key)),
        message_(message) {}
  std::size_t joint_set() const { return index_; }  ///< index into the joint sets given
  const std::string& key() const { return key_; }    ///< e.g. "cohesion", "shear_stiffness"
  const std::string& message() const { return message_; }  ///< the text after the key

 private:
  std::size_t index_;
  std::string key_;
  std::string message_;
};

/// The scalar properties of one family of joints, each declared once (its scene word,
/// unit, range, default and meaning) in joint_set_specs.hpp, bound to its member here;
/// the members' initializers are the defaults the declarations read.
struct JointProperties {
  double friction_angle = 0.0;    ///< Mohr-Coulomb friction angle phi [deg]
  double cohesion = 0.0;          ///< cohesion c [stress]; acts on contact length, until the contact first fails
  double tensile_strength = 0.0;  ///< tensile strength [stress]; acts on contact length, until the contact first fails
  /// Residual friction angle phi_r [deg], in [0, friction_angle]: a contact's friction once
  /// it is no longer intact (it slid or opened, or its damage law failed), UDEC's and
  /// 3DEC's residual strength (Itasca, UDEC Constitutive Models, "Coulomb slip with
  /// residual strength"); unset: friction_angle.
  std::optional<double> residual_friction_angle;
  /// Residual cohesion c_r [stress], in [0, cohesion]: a contact's cohesion once it is no
  /// longer intact (as residual_friction_angle); 0 by default (the cohesion is lost).
  double residual_cohesion = 0.0;
  /// The friction angle [deg] of a contact intact or not.
  double friction_angle_of(bool intact) const {
    return intact ? friction_angle : residual_friction_angle.value_or(friction_angle);
  }
  /// The cohesion [stress] of a contact intact or not.
  double cohesion_of(bool intact) const { return intact ? cohesion : residual_cohesion; }
  /// Joint normal stiffness per unit joint area [stress/length]; unset: penalty spring.
  std::optional<double> normal_stiffness;
  /// Joint shear stiffness per unit joint area [stress/length]; unset: the
  /// penalty's shear spring p_n / shear_normal_ratio (the seed's eqs. 17-18).
  std::optional<double> shear_stiffness;
  /// Coefficient of restitution e of an impact on this joint set [-], in
  /// [0, 1]; unset: no contact dashpots (Shi's contact, elastic once the step
  /// resolves its vibration). Set: the linear spring-dashpot contact of
  /// Cundall & Strack (1979), a dashpot beside each spring (normal, and shear
  /// while locked) of damping ratio zeta = -ln e / sqrt(pi^2 + ln^2 e)
  /// (zeta = 1 at e = 0), c = 2 zeta sqrt(k m) with m the reduced mass of the
  /// two blocks (docs/reference/contacts.md, "Contact damping"). Dynamic analysis only.
  std::optional<double> restitution;
};

/// One family of joints: its name, its declared properties (JointProperties) and its creep law.
struct JointSet : JointProperties {
  std::string name;  ///< joint_set name as the user gave it
  /// Creep law of the joint's shear spring, or none (docs/reference/rheology-in-dda.md).
  /// Contacts on a joint set with a law get a laws::RheologyState slot that
  /// follows the contact (transfer, change of kind, rollback); the creep
  /// increment of every locked contact enters through ShearSeam
  /// (contact_system.hpp), with the stress tau = F / l_t over the contact's
  /// tributary length l_t (its contact length for edge-edge contacts,
  /// point_tributary_length for point contacts). A law with an instantaneous
  /// spring E1 (burgers, maxwell, nishihara) sets the joint's elastic shear
  /// stiffness, k_s = E1 l_t: shear_stiffness must then be unset.
  std::shared_ptr<const laws::ContactRheology> law;
};

/// Numerical settings of the contact layer (defaults: Shi's DDA code).
struct ContactSettings {
  /// Normal penalty spring p_n [stress] (force per unit thickness per length);
  /// Shi: 10-100 x Young's modulus E (the seed's eq. 17, k1 = 10-100).
  double penalty = 0.0;
  /// p_n / p_s for penalty shear springs [-]; Shi: 2.5 = 2 (1 + nu) with nu = 0.25 (eq. 17).
  double shear_normal_ratio = 2.5;
  /// Contact search distance as a multiple of the allowed step displacement
  /// max_displacement_ratio w0 (StepContext::max_displacement) [-]; Shi: 2.5.
  double search_factor = 2.5;
  /// Search distance used when the host gives no allowed displacement [length].
  double min_search_distance = 0.0;
  /// Angle tolerance of the angle rule and of edge parallelism [deg]; Shi: 3.
  double angle_tolerance = 3.0;
  /// Allowed penetration as a fraction of the half model size w0 [-]. A step
  /// whose largest penetration exceeds it raises the penalty for the next steps.
  double penetration_ratio = 1e-4;
  /// A sliding contact whose normal force moved by more than this fraction
  /// between two iterates asks for another iteration (its friction force
  /// N tan(phi) is taken from the previous iterate) [-].
  double friction_tolerance = 0.01;
  /// Force resolution of the open-close decisions, as a fraction of the
  /// largest contact normal force of the last iterate [-]: a contact closes
  /// only when its spring would push by more than this, opens only when pulled
  /// by more than tensile strength plus this, slides only when its shear
  /// exceeds the Mohr-Coulomb limit by more than this.
  double force_resolution = 1e-3;
  /// Anti-chattering: after this many state changes in one step a contact may
  /// only change to locked for the rest of the step [-].
  int max_flips = 2;
  /// Friction refinements (see friction_tolerance) a contact may ask for in one step [-].
  int max_refinements = 3;
  /// A sliding contact that sticks keeps the friction force it slid against
  /// in its shear spring (elastic-plastic joint) instead of restarting the
  /// spring unstretched (Shi's rule) [-]. Off by default: on a creeping slope
  /// at its friction limit it changes which way the slope goes, with the step
  /// (docs/notes/contact-solves.md, "Why the iteration does not settle").
  bool stick_keeps_force = false;
  /// The rule of stick_keeps_force in the dynamic steps of a static analysis
  /// (a dynamic settling stage, docs/reference/engine.md "Settling stage") when set;
  /// unset: stick_keeps_force in every step [-]. The scene sets it true there
  /// unless the scene gives `stick_keeps_force`: a dynamic step keeps the
  /// force (the dynamic default), the static steps after it follow Shi.
  std::optional<bool> stick_keeps_force_dynamic;
  /// A contact that closes across a gap locks its shear spring where the
  /// vertex touches (the step's tangential motion before the touch is flight,
  /// not stretch) instead of at the vertex's step-start projection (Shi) [-].
  /// The hosts set it for dynamic analyses, where it makes the outcome of an
  /// impact independent of where in its step the contact is reached. Off in
  /// static analysis, where a step has no flight and the rule would only cost
  /// steps and accuracy (docs/reference/contacts.md, "Contact damping";
  /// docs/notes/contact-rules.md, "Locking at touch").
  bool lock_at_touch = false;
  /// A sliding contact turns back (sticks) once its backward slip in the step
  /// exceeds f_res / (p_n + m_red / (beta dt^2)), the slip a force residual moves
  /// the vertex by against the normal spring and the step's inertia (the
  /// `inertia` of begin_step), instead of f_res / k_s (Shi's spring) [-]. The
  /// hosts set it for dynamic analyses: with a soft joint (k_s << p_n) and a
  /// small step, the coarser resolution lets a vertex that moves backwards keep
  /// a friction force that pushes it on, step after step, friction doing
  /// negative work (docs/notes/contact-solves.md, "Friction that pushed"); without the
  /// inertia, contacts that stop stay sliding, more of them the smaller the step
  /// (docs/notes/contact-solves.md, "Contacts that stop"). Off in static analysis, where no
  /// velocity carries the error to the next step and the finer resolution keeps
  /// the static iteration from settling (docs/notes/contact-solves.md, "Friction that
  /// pushed").
  bool reversal_at_normal_resolution = false;
  /// Factor by which the penalty is raised [-].
  double penalty_raise = 2.0;
  /// Upper bound of the penalty as a multiple of the initial one [-].
  double penalty_max_factor = 64.0;
  /// Scheme of the creep laws (docs/reference/rheology-in-dda.md, "Schemes"). Unset
  /// (default): per joint set and step, exponential-linear (2nd order) where
  /// the step is below its no-ringing limit dt (k + E_i) <= 2 eta_i for every
  /// creep element i (k the joint's elastic shear stiffness per unit area),
  /// implicit (1st order, monotone at any dt) otherwise.
  std::optional<laws::Scheme> scheme;
  /// Newton on a nonlinear law's force (docs/reference/rheology-in-dda.md, "Nonlinear laws:
  /// Newton in the open-close iteration"): a locked contact asks for another
  /// iterate while its law's creep increment at the iterate's stress differs
  /// from the tangent model the iterate was solved with by more than this
  /// fraction of the stress it carries (measured as the stress that error
  /// moves through the spring) [-].
  double creep_newton_tolerance = 1e-10;
  /// Newton iterates a contact may ask for in one step [-].
  int max_creep_newton = 25;
};

}  // namespace rheodda::contact
