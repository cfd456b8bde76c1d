// The engine's choices between methods (docs/reference/contacts.md, "Contact solves";
// docs/reference/explicit-step.md; docs/reference/engine.md, "Solvers"; docs/design/methods.md),
// apart from the settings that hold them so that the scene's description can hold them too. A
// linear solver is one value here and one row of linear_solvers() (solver.cpp: its scene word). A
// contact solve is one value here and one
// row of contact_solves() (contact_solve.cpp: its scene word and its maker), an integrator one
// value here and one row of integrators() (integrator.cpp: its scene word and the engine's member
// that takes a dynamic step); the declarations of the settings that hold them (core/settings.hpp:
// choice_specs), and so the scene's keys, take their words from those rows.
#pragma once

namespace rheodda::core {

/// Linear solver of the global system K D = F (solver.hpp; its scene words are those of the rows
/// of linear_solvers()).
enum class SolverKind {
  automatic,  ///< cholmod below LinearSolver::kAmgBlocks blocks, amg from there on
  cholmod,  ///< sparse Cholesky LL' (SuiteSparse CHOLMOD), symbolic analysis reused
  pcg,      ///< conjugate gradient with a block-Jacobi (6x6) preconditioner
  amg,      ///< conjugate gradient preconditioned by an aggregation multigrid V-cycle whose
            ///< coarse unknowns are the six DDA unknowns of groups of blocks (O(N) per solve)
};

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
