// The input of a DDA analysis: plain structs, one per idea, every field with
// its unit and default. A scene reader (scene/) or a test fills a Model; the
// Engine (engine.hpp) validates it once and owns the run-time state.
//
// Why plain structs: the reader and the engine stay independent, a model can
// be written by hand in a test in a few lines, and defaults live in one place
// (here; settings.hpp reads them). Units: any consistent system (defaults in SI:
// kg, m, s, Pa). Bodies are plates of unit thickness, so "force" below is
// force per unit thickness and "stress" is force/length^2.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rheodda/core/methods.hpp"
#include "rheodda/core/water.hpp"
#include "rheodda/core/bolt.hpp"

namespace rheodda::core {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// An entry of one of the model's lists, or of an edit's ("blocks", 3), with the
/// part of it an error is in ("vertices"; "a.point": the first end's point of a
/// bolt): what a ModelError says as data, so that a reader maps it to its own
/// entry (a scene file's line) without reading the key's text.
struct ModelEntry {
  std::string list{};  ///< "blocks", "materials", "point_loads", "add_bolts", "water.history", ...
  std::size_t index = 0;
  std::string part{};  ///< a dotted path within the entry; "" for the entry as a whole
  /// The part `p` of this entry (of this part).
  ModelEntry within(const std::string& p) const { return {list, index, part.empty() ? p : part + "." + p}; }
  /// "blocks[3].vertices": the list, the index, the part.
  std::string key() const { return list + "[" + std::to_string(index) + "]" + (part.empty() ? "" : "." + part); }
};

/// Bad model input (geometry, parameters, indices). key() names the offending
/// entry, e.g. "blocks[3].vertices" or "settings.max_displacement_ratio"; an error in an entry of a
/// list says which as data (entry()), its message() apart from the key.
class ModelError : public std::invalid_argument {
 public:
  /// An error in a setting or a list as a whole (`key`: "settings.max_displacement_ratio", "blocks").
  ModelError(std::string key, const std::string& message)
      : std::invalid_argument(key + ": " + message), key_(std::move(key)), message_(message) {}
  /// An error in the part `field` ("" for the whole) of the list entry `entry`.
  ModelError(const ModelEntry& entry, const std::string& field, const std::string& message)
      : ModelError(field.empty() ? entry : entry.within(field), message) {}
  /// An error in the list entry `entry` (its part included).
  ModelError(ModelEntry entry, const std::string& message) : ModelError(entry.key(), message) {
    entry_ = std::move(entry);
  }
  const std::string& key() const { return key_; }
  /// What is wrong, without the key.
  const std::string& message() const { return message_; }
  /// The list entry it is in, its part included; none for a setting or a whole list.
  const std::optional<ModelEntry>& entry() const { return entry_; }

 private:
  std::string key_;
  std::string message_;
  std::optional<ModelEntry> entry_;
};

/// Plane stress (thin plate, sigma_z = 0) or plane strain (long body, epsilon_z = 0).
enum class PlaneMode { plane_stress, plane_strain };

/// Elastic material of a block (isotropic, linear).
struct Material {
  double density = 2600.0;        ///< mass density rho [mass/length^3]; > 0
  double young_modulus = 1.0e10;  ///< Young's modulus E [stress]; > 0
  double poisson_ratio = 0.25;    ///< Poisson's ratio nu [-]; in [0, 0.5)
  PlaneMode plane = PlaneMode::plane_stress;  ///< default plane stress
  /// Damping ratio zeta of the lowest strain mode of each block of this
  /// material [-], in [0, 1]; dynamic analysis only (0: none, Shi's DDA).
  /// Kelvin-Voigt strain damping sigma = E_e (eps + tau eps_dot), stiffness
  /// proportional, tau = 2 zeta / omega_1 per block (block_terms.hpp,
  /// strain_damping_time; docs/reference/engine.md, "Block damping").
  double damping_ratio = 0.0;
};

/// One block: a simple polygon (convex or concave) given in either orientation.
/// The engine normalises it to counter-clockwise; edge_joint_set follows the
/// edges through that reversal (edge k always joins vertex k to vertex k+1).
struct BlockDef {
  std::vector<Vec2> vertices;      ///< >= 3 vertices, first not repeated [length]
  std::vector<int> edge_joint_set; ///< joint set index of edge k (vertex k -> k+1 as given);
                                   ///< empty = every edge in joint set 0; else one per edge, >= 0
  int material = 0;                ///< index into Model::materials
  Vec3 initial_stress = Vec3::Zero();  ///< (sigma_x, sigma_y, tau_xy) at t = 0 [stress], tension > 0
  Vec2 initial_velocity = Vec2::Zero();  ///< centroid velocity at t = 0 [length/time]
  double initial_angular_velocity = 0.0; ///< rotation rate at t = 0, counter-clockwise > 0 [1/time]
};

/// One sample of a load time history.
struct LoadSample {
  double time = 0.0;           ///< [time]
  Vec2 force = Vec2::Zero();   ///< (fx, fy) [force]
};

/// A point load attached to a material point of a block (it moves with the
/// block). Its force is piecewise-linear in time between samples and held
/// constant before the first and after the last sample; it is evaluated at
/// the end of each step (t + dt).
struct PointLoad {
  int block = 0;                     ///< index into Model::blocks
  Vec2 point = Vec2::Zero();         ///< initial position of the material point [length]
  std::vector<LoadSample> history;   ///< >= 1 sample, times strictly increasing
};

/// A fixed point: a stiff penalty spring holding a material point of a block
/// at its initial position, in x and y or in one of them only (a spring in
/// that direction alone: the point moves freely in the other), and/or a
/// rotational penalty spring holding the block's rotation (hold_rotation; with
/// neither hold_x nor hold_y, the block held in rotation alone).
struct FixedPoint {
  int block = 0;                ///< index into Model::blocks
  Vec2 point = Vec2::Zero();    ///< initial (and held) position [length]
  /// A point added by a stage (Engine::edit) holds, at `point`, the material
  /// point that stood there when it was added: this is that material point's
  /// initial position [length]; unset: `point`.
  std::optional<Vec2> material_point = std::nullopt;
  bool hold_x = true;           ///< the spring acts in x
  bool hold_y = true;           ///< the spring acts in y
  /// The block's rotation is held: a rotational spring k_r = p J/S [force x length/rad]
  /// (rotation_hold_stiffness, defaults.hpp; J the polar second moment of the block's
  /// area about its centroid, S its area: p spread over the area) on the block's mean
  /// rotation about its centroid (block_terms.hpp, RotationHold), holding it at
  /// held_rotation. The point itself then holds only in the directions hold_x, hold_y
  /// say (none: it only names the block, and must lie on it).
  bool hold_rotation = false;
  /// The mean rotation held [rad], counter-clockwise > 0, measured from the block's
  /// initial orientation. Unset: 0 in a Model (the block held as it starts); in an
  /// edit (ModelEdit::add_fixed_points) the rotation the block has at the edit,
  /// which EditReport::replay sets.
  std::optional<double> held_rotation = std::nullopt;
  /// Initial position of the held material point [length].
  const Vec2& material() const { return material_point ? *material_point : point; }
  /// The directions held: diag(hold_x, hold_y); the spring is p S (x - x0).
  Eigen::Matrix2d held() const {
    Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
    s(0, 0) = hold_x ? 1.0 : 0.0;
    s(1, 1) = hold_y ? 1.0 : 0.0;
    return s;
  }
};

/// A measurement point: the engine records the displacement of this material
/// point after every accepted step.
struct MeasurementPoint {
  int block = 0;                ///< index into Model::blocks
  Vec2 point = Vec2::Zero();    ///< initial position of the material point [length]
};

/// Time integration of the inertia terms (Newmark family; docs/reference/engine.md).
enum class TimeIntegration {
  shi,          ///< beta = 1/2, gamma = 1 (Shi 1988): exact for constant acceleration, dissipative
  trapezoidal,  ///< beta = 1/4, gamma = 1/2: keeps the energy of linear vibrations (dynamic only)
};

/// The settling stage at the start of a run and the collapse stages of a static analysis
/// (docs/reference/engine.md, "Settling stage", "Collapse stages", "Dynamic stages",
/// "Gravity ramp"): Settings::settle, the scene's `analysis.settle` map, each member named as
/// its key (`dynamic` is the key `type: dynamic`). Its numbers are declared in settings.hpp
/// (settle_specs: unit, range, default mark and meaning); a default of 0 is a mark.
struct SettleStage {
  /// End of the settling stage: until this time the steps are at most `dt`, with the
  /// displacement limit `max_displacement_ratio` and without the adaptive controls; from
  /// it on, Settings::dt and max_displacement_ratio (the next step starts at dt); the
  /// longest a collapse stage lasts [time]; 0 = no settling stage; >= 0
  double until = 0.0;
  double dt = 0.0;        ///< largest step of the stage [time]; > 0 with until
  double max_displacement_ratio = 0.0;  ///< Shi's g2 of the stage's steps [-]; > 0 with until
  /// The stage is dynamic: its steps carry the whole velocity (dynamic_ratio 1, with the
  /// materials' damping_ratio and the joint sets' restitution), whatever the analysis's
  /// dynamic_ratio; a static analysis then starts its first step after the stage at rest
  /// (the kinetic energy left is booked as dissipated by the time integration) [-]
  bool dynamic = false;
  /// Collapse stages: with a dynamic settling stage, a later static step that moves as a
  /// mechanism (its inertia share above kMechanismStepShare) is cut down to this size; one
  /// that still does at it is not taken, and a dynamic stage as long as the settling stage
  /// (`until`, with `dt` and `max_displacement_ratio`) carries the collapse from the step's
  /// start [time]; 0 = off; >= 0, < Settings::dt
  double collapse_dt = 0.0;
  /// Gravity ramp: the body force rises linearly from zero at t = 0 to its full value at
  /// this time, which lies within the stage (0 < gravity_ramp <= until), so that the model
  /// is loaded slowly on the scale of its vibration instead of at once [time]; 0 = gravity at once
  double gravity_ramp = 0.0;
  /// Dynamic stages end at rest: a settling or collapse stage ends after a step whose
  /// motion's kinetic energy is below this fraction of the energy the stage took in or
  /// released, and no longer rising (not before the gravity ramp has ended), else at its
  /// longest, `until` from its start [-]; 0 = stages run to their longest; in [0, 1)
  double rest_tolerance = 0.0;
  /// A stage's explicit step is at rest when its unbalanced-force ratio (explicit_step.cpp
  /// (8)) is below this, instead of the kinetic-energy test of rest_tolerance [-];
  /// 0 = the kinetic-energy test; in [0, 1); with rest_tolerance only.
  double force_ratio = 0.0;
  /// Open-close iterates before a step of the settling stage or a collapse stage is cut
  /// [-]; 0 = Settings::open_close_limit. A static analysis limits its static steps to
  /// Shi's 8 (docs/notes/contact-solves.md, "The iteration limit in static analysis"); its
  /// dynamic stages are dynamic steps, which a dynamic analysis gives 30.
  int open_close_limit = 0;
};

/// Analysis settings (Shi's control parameters); settings.hpp declares most once (scene word, unit, range, meaning).
struct Settings {
  double dt = 1.0e-3;            ///< largest (and first) step size [time]; > 0
  double dt_growth = 1.5;        ///< after a cut, each accepted step lets dt grow by this factor,
                                 ///< up to dt [-]; >= 1
  double dt_cut = 0.3;           ///< factor applied to dt when a step is cut [-]; in (0, 1)
  double creep_tolerance = 0.0;  ///< adaptive creep stepping (docs/reference/step-controls.md): largest
                                 ///< creep error estimate allowed per step [length]; 0 = off
                                 ///< (fixed dt). When > 0, dt is the first step and the step
                                 ///< after every point-load sample time; steps end on those
                                 ///< times; the next step is dt_n min(2, max(dt_cut,
                                 ///< 0.9 sqrt(tol/err))), err the contacts' estimate; a step
                                 ///< with err > 2 tol is redone smaller (not below dt); >= 0
  double step_tolerance = 0.0;   ///< adaptive stepping by step doubling (docs/reference/step-controls.md,
                                 ///< "Step doubling"): largest difference allowed between one
                                 ///< step of dt and two of dt/2, over every block vertex
                                 ///< [length]; 0 = off. When > 0, dt is the first step and the
                                 ///< step after every point-load sample time, steps end on those
                                 ///< times, the next step is dt_n min(2, max(dt_cut,
                                 ///< 0.9 sqrt(tol/err))), a step with err > 2 tol is redone
                                 ///< smaller (not below dt); not with creep_tolerance; >= 0
  bool step_extrapolation = true;  ///< under step_tolerance: accept 2 y(dt/2) - y(dt)
                                 ///< (Richardson, second order) when both runs end with the
                                 ///< same contacts in the same states; false: accept y(dt/2)
  double dt_max = 0.0;           ///< largest step under creep_tolerance or step_tolerance [time];
                                 ///< 0 = no limit; >= 0, and >= dt under either
  bool creep_restart_on_contact_change = false;  ///< under creep_tolerance: the step after one in
                                 ///< which a contact on a creeping joint set locked, slid, opened,
                                 ///< appeared or vanished restarts from dt [-]
  int max_cuts = 30;             ///< cuts allowed in one step before the engine gives up [-]; >= 0
  double max_displacement_ratio = 0.01;  ///< allowed displacement per step as a fraction of the
                                        ///< half model size (Shi's g2) [-]; > 0
  /// The settling stage and the collapse stages (SettleStage above; the scene's
  /// `analysis.settle`); until = 0: none.
  SettleStage settle;
  /// The body acceleration at time t: gravity times min(1, t / settle.gravity_ramp)
  /// [length/time^2].
  Vec2 gravity_at(double t) const { return gravity_factor(t) * gravity; }
  /// The share of gravity on at time t: min(1, t / settle.gravity_ramp) [-]; the
  /// water's weight (its unit weight, water.hpp) ramps with it.
  double gravity_factor(double t) const {
    return settle.gravity_ramp > 0.0 && t < settle.gravity_ramp ? t / settle.gravity_ramp : 1.0;
  }
  /// Some steps carry velocity: a dynamic analysis, or a dynamic settling stage.
  bool has_dynamic_steps() const { return dynamic_ratio > 0.0 || (settle.until > 0.0 && settle.dynamic); }
  /// Integrator of the dynamic steps (docs/reference/explicit-step.md): the dynamic steps of a
  /// dynamic analysis and the dynamic stages of a static one; default implicit.
  Integrator integrator = Integrator::implicit;
  /// The explicit step's cycle is this share of the stable one, 2 / omega_max (omega_max
  /// bounded per block from its mass and the stiffness on it) [-]; in (0, 1]
  double explicit_safety = 0.8;
  /// Local (non-viscous) damping of the explicit cycles in the dynamic stages of a static
  /// analysis, where only the state at rest matters (Cundall's; UDEC's default is 0.8):
  /// each degree of freedom takes the force -alpha |R| sign(v) beside its unbalanced
  /// force R [-]; in [0, 1); 0 = none. Never in a dynamic analysis.
  double stage_local_damping = 0.0;
  /// Density scaling of the explicit cycles in the dynamic stages of a static analysis,
  /// where only the state at rest matters: the most cycles a step of such a stage takes [-];
  /// 0 = no scaling. A block whose stable cycle is shorter than dt / (stage_cycles *
  /// explicit_safety) has its mass matrix scaled up (BlockState::mass_scale) until it is
  /// not; its loads stay (gravity acts on the block's true mass). Never in a dynamic analysis.
  int stage_cycles = 0;
  /// Static steps by explicit cycles (docs/reference/explicit-step.md, "Static steps by
  /// cycles"; core/src/explicit_static.cpp): with the explicit integrator, each static step
  /// (a creep step) is taken by cycles from rest, every block's mass scaled to a common
  /// cycle and locally damped (static_local_damping), until the unbalanced-force ratio is at
  /// most this (UDEC's "solve ratio") [-]; 0 = static steps implicit; in [0, 1).
  double static_force_ratio = 0.0;
  /// The most cycles a static step by cycles takes before it counts as not settling (it is
  /// then cut as an open-close iteration that does not settle is) [-]; >= 1.
  int static_max_cycles = 100000;
  /// Local damping alpha of the static steps by cycles (Cundall's; UDEC's default 0.8) [-];
  /// in (0, 1).
  double static_local_damping = 0.8;
  /// Damping ratio the explicit cycles give what has no damping of its own [-], in [0, 1]:
  /// each contact whose joint set has no restitution (dashpots c = tau k beside its springs,
  /// tau = 2 zeta / omega_max: the scene's highest mode at zeta, the lower ones less), and
  /// each strain mode of a block whose material has no damping_ratio (modal damping of the
  /// block's elastic vibration, each mode at zeta). The
  /// implicit step's scheme damps both within a step (their periods are micro- to
  /// milliseconds); the cycles resolve them, and undamped they rattle for ever and, with
  /// friction, pump a sliding block off its joint (docs/reference/explicit-step.md,
  /// "Damping"). 0 = none: the elastic dynamics undamped.
  double explicit_damping = 0.5;
  /// OpenMP threads of the explicit cycles; 0 = OpenMP's default (OMP_NUM_THREADS). The
  /// results are the same bits whatever the number [-]; >= 0
  int threads = 0;
  double dynamic_ratio = 1.0;    ///< share of the velocity carried to the next step [-], in [0, 1];
                                 ///< 0 = static analysis (no velocities at all), 1 = fully dynamic
  TimeIntegration time_integration = TimeIntegration::shi;  ///< default shi
  Vec2 gravity{0.0, -9.81};      ///< body acceleration (gx, gy) [length/time^2]
  double fixed_point_stiffness = 0.0;  ///< penalty spring of fixed points [force/length];
                                       ///< 0 = automatic: 100 x the largest Young's modulus
  int open_close_limit = 30;     ///< open-close iterations before a step is cut [-]; >= 1 (docs/notes/contact-solves.md, "The wall converges when the iteration is not cut")
  SolverKind solver = SolverKind::automatic;  ///< default automatic
  ContactSolver contact_solver = ContactSolver::open_close;  ///< default open_close
  /// ContactSolver::newton accepts a step when the residual of its equations,
  /// |F0 - K0 D - f(D)|, is at most this fraction of the contact forces |f(D)|
  /// (docs/reference/contacts.md, "Contact solves") [-]; in (0, 1)
  double contact_residual_tolerance = 1.0e-4;
  double solver_tolerance = 1.0e-10;  ///< stop of the iterative solvers (pcg, amg):
                                      ///< ||F - K D|| <= tol ||F|| [-]; > 0. 1e-10: what double
                                      ///< precision attains on contact-dominated systems
                                      ///< (condition numbers 1e5-1e6)
  int solver_max_iterations = 10000;  ///< iteration limit per solve of pcg and amg [-]; >= 1
  /// Stop of the iterative solvers in an open-close iterate whose contact
  /// states are still changing [-]: ||F - K D|| <= solver_iterate_tolerance ||F||;
  /// a trial is accepted only on a check of a solve at solver_tolerance (docs/notes/contact-solves.md,
  /// "Inexact iterates"). 0 = every solve at solver_tolerance; in [0, 1)
  double solver_iterate_tolerance = 1.0e-4;
};

/// A complete DDA model.
struct Model {
  std::vector<Material> materials{Material{}};  ///< default: one default material
  std::vector<BlockDef> blocks;
  std::vector<PointLoad> point_loads;
  std::vector<FixedPoint> fixed_points;
  std::vector<MeasurementPoint> measurement_points;
  Water water;  ///< water in the joints (water.hpp); default none
  std::vector<Bolt> bolts;  ///< rock bolts (bolt.hpp, docs/reference/bolts.md); none: no bolt work at all
  Settings settings;
};

}  // namespace rheodda::core
