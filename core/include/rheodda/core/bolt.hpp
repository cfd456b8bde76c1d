// Rock bolts (docs/reference/bolts.md): an axial bar joining a material point of one
// block to a material point of another block, or to a fixed point in space.
//
// The bolt is a spring along its current axis, elastic-perfectly plastic
// (|N| <= yield_force), ruptured for good once its elongation exceeds
// rupture_elongation, with an optional creep law of the library on its axial
// force (relaxation at constant length; the same laws::ContactRheology
// interface the joints use). Tension is positive; the bolt carries
// compression too, elastically up to -yield_force (a grouted bar), and
// ruptures in tension only.
//
// Units: "force" is per unit thickness, as everywhere in a 2-D model (a row
// of bolts at spacing s out of the plane carries s x this force each). A law
// on a bolt reads its force as the bolt's axial force [force] and its
// displacement as the bolt's elongation [length]: its stiffnesses are
// [force/length], its viscosities [force x time/length].
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <memory>

#include "rheodda/laws/contact_rheology.hpp"

namespace rheodda::core {

using Vec2 = Eigen::Vector2d;  // as in model.hpp, which includes this header

/// A bolt's properties, declared in core/property_specs.hpp (their units, ranges and
/// meanings; the scene's keys of the same names, whose BoltDescription is one).
struct BoltProperties {
  double axial_stiffness = 0.0;  ///< k, axial force per unit elongation [force/length]; > 0
  /// Axial force when installed (t = 0, or the stage that installs it) [force] (tension
  /// > 0): the bolt's unstressed length is L_rest = L0 - pretension / k, L0 its length
  /// when installed (installed_length); |pretension| <= yield_force
  double pretension = 0.0;
  /// Yield force N_y [force], > 0: |N| <= N_y; beyond, the bolt stretches plastically
  /// at N_y (elastic-perfectly plastic). Infinity: never yields.
  double yield_force = std::numeric_limits<double>::infinity();
  /// Rupture elongation [length], > 0: when the elongation L - L_rest exceeds it, the
  /// bolt breaks and carries nothing for the rest of the run. Infinity: never.
  double rupture_elongation = std::numeric_limits<double>::infinity();
};

/// One bolt of the Model (Model::bolts): its properties and where it is.
struct Bolt : BoltProperties {
  int block_a = 0;             ///< index into Model::blocks of the first end's block
  Vec2 point_a = Vec2::Zero(); ///< initial position of the first end, on block_a [length]
  int block_b = -1;            ///< index into Model::blocks of the second end's block; -1: the
                               ///< second end is fixed in space at point_b
  Vec2 point_b = Vec2::Zero(); ///< initial position of the second end [length]; != point_a
  /// Length between the two ends when the bolt was installed [length]; 0: a bolt of
  /// the model from t = 0, installed at L0 = |point_b - point_a|. A bolt a stage
  /// installs (ModelEdit::add_bolts) joins blocks that have moved since t = 0: its
  /// L0 is the distance between its ends then, and L_rest = L0 - pretension / k.
  double installed_length = 0.0;
  /// Creep of the axial force (bolt relaxation), or none. A law with an instantaneous
  /// stiffness E1 must have E1 == axial_stiffness (the law's spring is the bolt's).
  std::shared_ptr<const laws::ContactRheology> law;
};

/// What a bolt is doing.
enum class BoltMode {
  elastic,   ///< |N| < yield_force: the spring (and the creep law) carries the force
  yielding,  ///< |N| = yield_force: the bolt stretches (or shortens) plastically
  ruptured,  ///< broken: no force, for the rest of the run
};

/// Name used in outputs: "elastic", "yielding", "ruptured".
const char* bolt_mode_name(BoltMode m);

/// Run-time state of one bolt after an accepted step (EngineState::bolts).
struct BoltState {
  BoltMode state = BoltMode::elastic;  ///< bolts.csv's `state`
  double force = 0.0;       ///< axial force N [force], tension > 0; 0 once ruptured
  double length = 0.0;      ///< current distance between the two ends [length]
  double elongation = 0.0;  ///< length - L_rest (L_rest: unstressed length at t = 0) [length]
  double plastic_elongation = 0.0;  ///< accumulated plastic elongation e_p [length]
  /// The law's history (its creep elements); creep elongation e_c = rheology.creep()
  /// [length]. N = k (elongation - e_p - e_c) while the bolt is intact.
  laws::RheologyState rheology;
  double rupture_time = -1.0;  ///< time the bolt ruptured [time]; -1 while intact
  double creep_elongation() const { return rheology.creep(); }
};

}  // namespace rheodda::core
