// The engine's choices between methods (docs/reference/contacts.md, "Contact solves";
// docs/reference/explicit-step.md; docs/design/methods.md), apart from the settings that hold them
// so that the scene's description can hold them too. A contact solve is one value here and one
// row of contact_solves() (contact_solve.cpp: its scene word and its maker), an integrator one
// value here and one row of integrators() (integrator.cpp: its scene word and the engine's member
// that takes a dynamic step); the scene's keys take their words from those rows.
#pragma once

namespace rheodda::core {

/// How a step's contact problem is solved (contact_solve.hpp; docs/reference/contacts.md,
/// "Contact solves").
enum class ContactSolver {
  open_close,  ///< Shi's open-close iteration: solve, check every contact, repeat until no
               ///< state changes (the reference)
  newton,      ///< the same Newton iterates, converged on the residual of the step's
               ///< equations (Settings::contact_residual_tolerance)
};

/// How dynamic steps are integrated (docs/reference/explicit-step.md; integrator.hpp). The
/// scene's words are those of the rows of integrators() (`explicit` is a C++ keyword:
/// Integrator::explicit_step).
enum class Integrator {
  implicit,       ///< Shi's implicit step: the step's equations solved with the open-close
                  ///< iteration (the reference; every step of a static analysis is one)
  explicit_step,  ///< dynamic steps in explicit cycles (central difference, each contact's state
                  ///< decided on its own, no matrix); static steps stay implicit
  automatic,      ///< the one of the two estimated cheaper on the scene's initial state, chosen
                  ///< before the engine runs (scene/integrator_choice.hpp); the engine refuses it
};

}  // namespace rheodda::core
