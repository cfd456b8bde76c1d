// The declarations of core::Settings (settings.hpp), one entry per setting, in the order
// of the docs. Each entry: the member, its unit, its range and its meaning; the default
// is the member's initializer (model.hpp), read from Settings{}.
#include "rheodda/core/settings.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rheodda/core/contact_solve.hpp"
#include "rheodda/core/defaults.hpp"
#include "rheodda/core/integrator.hpp"
#include "rheodda/core/property_specs.hpp"
#include "rheodda/core/solver.hpp"
#include "rheodda/laws/spec_lookup.hpp"

namespace rheodda::core {

namespace {

constexpr double kInf = std::numeric_limits<double>::max();

using Range = laws::ParameterRange;  ///< [min or (min, max] or max)
constexpr Range kPositive = laws::kPositiveRange;        ///< > 0
constexpr Range kNonNegative = laws::kNonNegativeRange;  ///< >= 0
constexpr Range kFraction{0.0, false, 1.0, true};      ///< [0, 1)
constexpr Range kOpenFraction{0.0, true, 1.0, true};   ///< (0, 1)

/// The declaration of the member `field`, named `name` (the scene's word).
template <class T>
SettingSpec declare(const char* name, const char* unit, Range r, T Settings::*field, const char* meaning) {
  return laws::declare_setting(name, unit, r, field, meaning);
}

std::vector<SettingSpec> declare_settings() {
  std::vector<SettingSpec> out;
  auto add = [&out](SettingSpec s) -> SettingSpec& { return out.emplace_back(std::move(s)); };

  add(declare("dt", "time", kPositive, &Settings::dt,
              "first and largest time step; ≤ `duration`")).between_steps = true;
  add(declare("dt_growth", "–", {1.0, false, kInf, false}, &Settings::dt_growth,
              "fixed-step runs: after a cut, each accepted step is `dt_growth` × the last one, up to "
              "`dt` (1: the step stays cut); refused under `creep_tolerance` or `step_tolerance` "
              "(the control sizes the steps)")).between_steps = true;
  add(declare("dt_cut", "–", kOpenFraction, &Settings::dt_cut,
              "factor on the step when a step is cut (open–close iteration not converged, or a step "
              "displacement above `max_displacement_ratio` × half model size); also the smallest factor "
              "an adaptive control shrinks a step by at once")).between_steps = true;
  add(declare("max_cuts", "–", {0.0, false, 200.0, false}, &Settings::max_cuts,
              "times dt may be cut (× `dt_cut` each) in one step before the run fails")).between_steps = true;
  add(declare("max_displacement_ratio", "–", kPositive, &Settings::max_displacement_ratio,
              "Shi's g2: allowed displacement per step / half model size")).between_steps = true;
  SettingSpec& dynamic_ratio = add(declare("dynamic_ratio", "–", {0.0, false, 1.0, false}, &Settings::dynamic_ratio,
              "share of velocity carried to the next step (0: a static analysis, no velocity at all); "
              "given only with `type: dynamic`"));
  dynamic_ratio.static_default = 0.0;
  add(declare("creep_tolerance", "length", kNonNegative, &Settings::creep_tolerance,
              "adaptive creep stepping (docs/guide/choosing-step-controls.md): the creep error allowed per step; the "
              "step grows (up to ×2) while the estimate stays below it, restarts from `dt` after a load "
              "change, and a step whose estimate exceeds 2× the tolerance is redone smaller (not below "
              "`dt`); 0 = fixed `dt`")).between_steps = true;
  add(declare("step_tolerance", "length", kNonNegative, &Settings::step_tolerance,
              "adaptive stepping by step doubling (docs/reference/step-controls.md, \"Step doubling\"): each "
              "step is taken once with dt and twice with dt/2 from the same state; the largest "
              "difference over the block vertices must stay below the tolerance; the step grows (up to "
              "×2) while it does, restarts from `dt` after a load change, never falls below `dt`, and a "
              "step whose difference exceeds 2× the tolerance is redone smaller; 3 solves per step; not "
              "with `creep_tolerance`; 0 = off")).between_steps = true;
  add(declare("step_extrapolation", "–", {}, &Settings::step_extrapolation,
              "under `step_tolerance`: accept 2 y(dt/2) − y(dt) (Richardson: second order) when both "
              "runs end with the same contacts in the same states, else y(dt/2); `false`: always "
              "y(dt/2) (first order); only with `step_tolerance`")).between_steps = true;
  add(declare("dt_max", "time", kNonNegative, &Settings::dt_max,
              "largest step under `creep_tolerance` or `step_tolerance` (refused without one); 0 = no "
              "limit; >= `dt` when given")).between_steps = true;
  add(declare("creep_restart_on_contact_change", "–", {}, &Settings::creep_restart_on_contact_change,
              "under `creep_tolerance`: the step after one in which a creeping contact locked, slid or "
              "opened restarts from `dt` (as after a load change)"));
  SettingSpec& open_close = add(declare("open_close_limit", "–", {1.0, false, 1000.0, false}, &Settings::open_close_limit,
              "open–close iterations before a step is cut (the static default is Shi's; docs/notes/contact-solves.md, \"The "
              "iteration limit in static analysis\")"));
  open_close.static_default = 8.0;
  open_close.between_steps = true;
  SettingSpec& fixed = add(declare("fixed_point_stiffness", "force/length", kPositive, &Settings::fixed_point_stiffness,
              "spring holding a fixed point (times J/S, the block's polar radius of gyration squared: the rotational "
              "spring of `hold: rotation` [force·length/rad])"));
  fixed.default_meaning = fmt::format("{:g} × the largest `young_modulus`", kFixedPointFactor);
  add(declare("solver_tolerance", "–", kOpenFraction, &Settings::solver_tolerance,
              "`amg` and `pcg` stop when ‖F − K D‖ ≤ solver_tolerance ‖F‖ (the true residual)")).between_steps = true;
  add(declare("solver_max_iterations", "–", {1.0, false, 1.0e9, false}, &Settings::solver_max_iterations,
              "conjugate-gradient iterations allowed per solve of `amg` and `pcg`; a solve that reaches "
              "it without meeting `solver_tolerance` stops the run with an error")).between_steps = true;
  add(declare("solver_iterate_tolerance", "–", kFraction, &Settings::solver_iterate_tolerance,
              "`amg` and `pcg` stop at this relative residual in an open–close iterate whose contact "
              "states are still changing; a step is accepted only on a check of a solve at "
              "`solver_tolerance` (docs/notes/contact-solves.md, \"Inexact iterates\"); 0 = "
              "every solve at `solver_tolerance`; no effect with `cholmod` (exact)")).between_steps = true;
  add(declare("explicit_safety", "–", {0.0, true, 1.0, false}, &Settings::explicit_safety,
              "under `integrator: explicit`, the cycle as a share of the stable one 2/ω_max (ω_max bounded "
              "per block from its mass and the stiffness of its contacts, elasticity and fixed points)"));
  add(declare("explicit_damping", "–", {0.0, false, 1.0, false}, &Settings::explicit_damping,
              "under `integrator: explicit`, the damping ratio the cycles give what has no damping of its own: "
              "contacts whose joint set has no `restitution` (dashpots beside their springs, the scene's "
              "highest mode at this ratio) and the strain modes of blocks whose material has no "
              "`damping_ratio` (each at this ratio). The implicit step damps both within a step; undamped "
              "they rattle for ever (docs/reference/explicit-step.md, \"Damping\"); 0 = none"));
  add(declare("stage_local_damping", "–", kFraction, &Settings::stage_local_damping,
              "under `integrator: explicit`, local (non-viscous) damping α of the cycles in the dynamic "
              "stages of a static analysis, where only the state at rest matters: each degree of freedom "
              "takes −α \\|R\\| sign(v) beside its unbalanced force R (UDEC's default is 0.8); "
              "0 = none; never in a dynamic analysis"));
  add(declare("stage_cycles", "–", {0.0, false, 1.0e8, false}, &Settings::stage_cycles,
              "under `integrator: explicit`, density scaling in the dynamic stages of a static analysis, "
              "where only the state at rest matters: the most cycles a step of a stage takes; a block whose "
              "stable cycle is shorter has its mass scaled up until it is not, its loads unchanged "
              "(docs/reference/explicit-step.md, \"Density scaling\"); 0 = none; never in a dynamic analysis"));
  add(declare("static_force_ratio", "–", kFraction, &Settings::static_force_ratio,
              "under `integrator: explicit`, the static steps of a static analysis (its creep steps) taken by "
              "cycles from rest, each block's mass scaled to a common cycle and locally damped, until the "
              "largest unbalanced force of a block is at most this fraction of the mean applied force (UDEC's "
              "ratio; 1e-5 is customary) (docs/reference/explicit-step.md, \"Static steps by cycles\"); "
              "0 = the static steps implicit; a static analysis only"));
  add(declare("static_max_cycles", "–", {1.0, false, 1.0e9, false}, &Settings::static_max_cycles,
              "with `static_force_ratio`, the most cycles a static step takes; a step that has not settled by "
              "then is cut as an open–close iteration that does not settle is (and taken as a collapse stage "
              "where `settle.collapse_dt` asks for them)"));
  add(declare("static_local_damping", "–", kOpenFraction, &Settings::static_local_damping,
              "with `static_force_ratio`, the local (non-viscous) damping α of the static steps' cycles "
              "(UDEC's default 0.8)"));
  add(declare("contact_residual_tolerance", "–", kOpenFraction, &Settings::contact_residual_tolerance,
              "under `contact_solver: newton`, a step is accepted when the residual of its equations, "
              "\\|F0 − K0 D − f(D)\\|, is at most this fraction of the contact forces \\|f(D)\\| "
              "(rotation and strain rows divided by the block's size)"));
  return out;
}

/// The declaration of the stage's member `field`, named `name` (the scene's word under
/// `analysis.settle`), whose default 0 is the mark `mark` ("0 (none)").
template <class T>
SettleSpec declare_stage(const char* name, const char* unit, Range r, T SettleStage::*field, std::string mark,
                         const char* meaning) {
  SettleSpec s = laws::declare_setting(name, unit, r, field, meaning);
  s.default_meaning = std::move(mark);
  return s;
}

std::vector<SettleSpec> declare_settle() {
  using S = SettleStage;
  std::vector<SettleSpec> out;
  out.push_back(declare_stage("until", "time", kPositive, &S::until, "0 (no settling stage)",
      "end of the settling stage, > 0, before `duration`; with `rest_tolerance` optional: the "
      "longest the stage may last. Until then the steps are at most `dt`, with the "
      "displacement limit `max_displacement_ratio` and without `creep_tolerance` or "
      "`step_tolerance`; then the analysis's `dt` and `max_displacement_ratio` take over"));
  out.push_back(declare_stage("dt", "time", kPositive, &S::dt, "0 (none: required with a stage)",
      "largest step of the settling stage, > 0, ≤ `until`"));
  out.push_back(declare_stage("max_displacement_ratio", "–", {0.0, true, 1.0, false}, &S::max_displacement_ratio,
      "the analysis's `max_displacement_ratio`", "Shi's g2 of the stage's steps, (0, 1]"));
  out.push_back(declare_stage("collapse_dt", "time", kPositive, &S::collapse_dt, "0 (none)",
      "collapse stages (docs/reference/engine.md, \"Collapse stages\"): a later static step that moves as "
      "a mechanism (its inertia share above 0.1) is cut down to `collapse_dt`, and there taken "
      "as a dynamic stage as long as this one, with its `dt` and `max_displacement_ratio`; > 0, "
      "below the analysis's `dt`; a dynamic stage in a static analysis only; not with "
      "`step_tolerance`; `rheodda check --refine` halves it with the other step controls"));
  out.push_back(declare_stage("gravity_ramp", "time", kPositive, &S::gravity_ramp, "0 (gravity at once)",
      "gravity rises linearly from zero at t = 0 to its full value at this time, so that a "
      "model that stands is loaded slowly instead of at once (docs/reference/engine.md, \"Gravity "
      "ramp\"); > 0, ≤ `until`; a physical loading time, not a step control: `check --refine` "
      "keeps it"));
  out.push_back(declare_stage("rest_tolerance", "–", kOpenFraction, &S::rest_tolerance, "0 (stages last `until`)",
      "the stage, and every collapse stage, ends at rest — after a step whose motion's kinetic energy "
      "is below this fraction of the energy the stage took in or released (the largest of the work "
      "gravity and the loads did over it, its dissipation and its kinetic peak) and no longer rising, "
      "not before the gravity ramp has ended (docs/reference/engine.md, \"Dynamic stages\", which also says how to "
      "choose it); each stage is a row of events.csv (docs/reference/outputs.md); in (0, 1); `type: "
      "dynamic` only"));
  out.push_back(declare_stage("force_ratio", "–", kOpenFraction, &S::force_ratio, "0 (the kinetic-energy test)",
      "with the explicit step: a stage's explicit step is at rest when the largest unbalanced "
      "force of a moving block is below this fraction of the mean force applied to the moving "
      "blocks (UDEC's ratio; 1e-5 is customary), instead of the kinetic-energy test of "
      "`rest_tolerance` (docs/reference/explicit-step.md, \"Rest by the unbalanced force\"); in "
      "(0, 1); with `rest_tolerance` and `integrator: explicit` or `automatic`"));
  out.push_back(declare_stage("open_close_limit", "–", {1.0, false, 1000.0, false}, &S::open_close_limit,
      "the analysis's `open_close_limit`",
      "open–close iterates before a step of the settling stage or a collapse stage is cut, "
      "1–1000 (a dynamic stage of a static analysis needs more than the 8 of its static steps "
      "where many contacts change at once; docs/reference/contacts.md, \"Contact solves\")"));
  return out;
}

/// The choices of Settings (laws::ChoiceSpec), in the order of the docs: each the words of
/// its method table, its meaning and Settings{}'s value as its default.
std::vector<ChoiceSpec> declare_choices() {
  std::vector<ChoiceSpec> out;
  out.push_back(laws::declare_choice("time_integration", time_integrations(), &Settings::time_integration,
      "integration of the inertia terms (docs/reference/engine.md, \"Time integration\"): `shi` (Shi's "
         "scheme, Newmark β = 1/2, γ = 1: exact for constant acceleration, damps vibrations "
         "numerically, for quasi-static and creep runs) or `trapezoidal` (β = 1/4, γ = 1/2: keeps "
         "the energy of linear vibrations); `trapezoidal` only with `type: dynamic` and "
         "`dynamic_ratio` > 0"));
  out.push_back(laws::declare_choice("solver", linear_solvers(), &Settings::solver,
      "`automatic` (`cholmod` below 2 000 blocks, `amg` from 2 000), `cholmod` (sparse "
         "Cholesky), `amg` (conjugate gradient with a multigrid V-cycle whose coarse unknowns are "
         "the DDA unknowns of groups of blocks; O(N) per iteration, for large models) or `pcg` "
         "(block-Jacobi conjugate gradient, a reference); docs/reference/engine.md, \"Solvers\""));
  out.back().between_steps = true;  // the solver keeps no state another cannot restore (solver_state.cpp)
  out.push_back(laws::declare_choice("contact_solver", contact_solves(), &Settings::contact_solver,
      "how a step's contacts are solved (docs/reference/contacts.md, \"Contact solves\"): `open-close` "
         "(Shi's iteration: solve, check every contact, repeat until none changes its state) or "
         "`newton` (the same iterates, a step accepted once the residual of its equations is "
         "within `contact_residual_tolerance` of the contact forces, a dynamic step starting from "
         "the states its inertia alone would give)"));
  out.back().between_steps = true;  // how a step's contacts are solved, not what they are
  out.push_back(laws::declare_choice("integrator", integrators(), &Settings::integrator,
      "how dynamic steps are integrated (docs/reference/explicit-step.md): `implicit` (Shi's step: "
         "the step's equations solved with the open–close iteration), `explicit` (each dynamic "
         "step in cycles of central difference with every contact's state decided on its own: no "
         "matrix, no iteration, in parallel; the static steps of a static analysis stay implicit, "
         "its dynamic stages (`settle`) are explicit) or `automatic` (the one whose estimated cost "
         "per dynamic step is lower on the scene's initial state; `rheodda check` prints which and "
         "why)"));
  return out;
}

std::vector<SettleChoiceSpec> declare_settle_choices() {
  static constexpr std::array<laws::ChoiceWord<bool>, 2> kKinds{{{false, "static"}, {true, "dynamic"}}};
  std::vector<SettleChoiceSpec> out;
  out.push_back(laws::declare_choice("type", kKinds, &SettleStage::dynamic,
      "`static` or `dynamic`: in a static analysis the stage's steps carry velocity (the blocks "
         "move with their inertia, with the materials' `damping_ratio` and the joint sets' "
         "`restitution`, which a static analysis then accepts; a sticking contact keeps its force "
         "unless `stick_keeps_force` is given), and the first static step after it starts at "
         "rest; a dynamic analysis's stage is dynamic (`type: static` is refused there)"));
  out.back().default_note = "(the stage's steps are the analysis's kind)";
  return out;
}

}  // namespace

std::span<const laws::ChoiceWord<TimeIntegration>> time_integrations() {
  static constexpr std::array<laws::ChoiceWord<TimeIntegration>, 2> kRows{
      {{TimeIntegration::shi, "shi"}, {TimeIntegration::trapezoidal, "trapezoidal"}}};
  return kRows;
}

const std::vector<ChoiceSpec>& choice_specs() {
  static const std::vector<ChoiceSpec> specs = declare_choices();
  return specs;
}

const ChoiceSpec& choice_spec(std::string_view name) {
  return laws::spec_named(choice_specs(), name, "core::Settings", "choice");
}

const std::vector<SettleChoiceSpec>& settle_choice_specs() {
  static const std::vector<SettleChoiceSpec> specs = declare_settle_choices();
  return specs;
}

const SettleChoiceSpec& settle_choice_spec(std::string_view name) {
  return laws::spec_named(settle_choice_specs(), name, "core::SettleStage", "choice");
}

const VectorSettingSpec& gravity_spec() {
  static const VectorSettingSpec spec{"gravity", "length/time²", "`[gx, gy]`", &Settings::gravity};
  return spec;
}

const std::vector<SettleSpec>& settle_specs() {
  static const std::vector<SettleSpec> specs = declare_settle();
  return specs;
}

const SettleSpec& settle_spec(std::string_view name) {
  return laws::spec_named(settle_specs(), name, "core::SettleStage", "setting");
}

const std::vector<SettingSpec>& setting_specs() {
  static const std::vector<SettingSpec> specs = declare_settings();
  return specs;
}

const SettingSpec& setting_spec(std::string_view name) {
  return laws::spec_named(setting_specs(), name, "core::Settings", "setting");
}


std::string settings_table_markdown() { return laws::settings_table_markdown(setting_specs()); }

void check_setting_ranges(const Settings& s) {
  check_declared(setting_specs(), s, std::string("settings"));
}

}  // namespace rheodda::core
