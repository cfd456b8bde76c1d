// Integrators: how the engine takes one attempt at a dynamic step (docs/reference/explicit-step.md;
// docs/design/methods.md).
//
// A step's attempt is a trial: after the contacts' begin_step, D (6 per block) and contact
// states that agree, or a failure the step control cuts dt for (engine_impl.hpp, StepTrial). Shi's
// implicit step solves the step's equations (step_trial.cpp, Engine::Impl::implicit_trial); the
// explicit step runs central-difference cycles (explicit_step.cpp, Engine::Impl::cycle_trial). A
// static step carries no inertia to integrate, so every integrator takes it as Shi's step,
// unless the scene asks for the integrator's own static trial (Settings::static_force_ratio:
// the explicit step's cycles from rest to equilibrium, explicit_static.cpp).
//
// Adding one is a member of Engine::Impl in one file that takes a dynamic step's trial, its value
// in Integrator (methods.hpp) and its row in integrators() (integrator.cpp): the engine calls the
// member of its Settings::integrator's row, and the scene's `integrator` key reads its word from
// that row.
#pragma once

#include <span>
#include <string_view>

#include "rheodda/core/engine.hpp"
#include "rheodda/core/methods.hpp"

namespace rheodda::core {

/// One attempt at a step (defined where the engine's internals are: core/src/engine_impl.hpp).
struct StepTrial;

/// A registered integrator: its Settings value, its scene word and the engine's member that takes a
/// dynamic step's trial.
struct IntegratorEntry {
  Integrator method;
  std::string_view word;  ///< the scene's `integrator` word
  /// Takes the trial of a dynamic step of dt after the contacts' begin_step (timed into rep); null
  /// for a choice between integrators that is made before the engine runs (the engine refuses it).
  StepTrial (Engine::Impl::*dynamic_trial)(double dt, StepReport& rep);
  /// Takes the trial of a static step where the scene asks for the integrator's own
  /// (Settings::static_force_ratio); null: Shi's implicit step, as under every integrator.
  StepTrial (Engine::Impl::*static_trial)(double dt, StepReport& rep);
};

/// Every integrator, one row each (integrator.cpp).
std::span<const IntegratorEntry> integrators();

/// The row of `method` (Settings::integrator).
const IntegratorEntry& integrator_entry(Integrator method);

}  // namespace rheodda::core
