// Contact solves: how the host finds one step's displacements and contact
// states (docs/reference/contacts.md, "Contact solves").
//
// A DDA step is the linear system K(S) D = F(S) of the seed's eq. 30 for a set
// S of contact states (open, locked, sliding) that the contacts find
// consistent with D. A ContactSolve finds such a pair, or says it could not.
// The host gives it a StepProblem: the step's block terms without contacts
// (K0 and F0: inertia, elasticity, block damping, loads, fixed points; one 6x6
// matrix per block, no coupling between blocks), the contact model between
// its begin_step and end_step, and a linear solve of the whole system for the
// contacts' current trial states. The solve leaves the contacts in the states
// its D was found with; the host then ends or abandons the step.
//
// Why an interface: the open-close iteration of Shi's DDA is one way to find
// the pair; others (a semismooth Newton method, the dual form over contact
// forces) trade cost per iterate against iterates per step differently, and
// which wins depends on the scene (docs/notes/contact-solves.md). Adding one
// is a class in one file, its value in ContactSolver (methods.hpp) and its row in
// contact_solves(): the scene's `contact_solver` key reads its word from that row.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/block_system.hpp"
#include "rheodda/core/contact_model.hpp"
#include "rheodda/core/model.hpp"

namespace rheodda::core {

/// One step's problem as a contact solve sees it (implemented by the engine).
class StepProblem {
 public:
  virtual ~StepProblem() = default;
  /// Step-start geometry of the blocks (what the contacts were detected on).
  virtual std::span<const contact::BlockView> blocks() const = 0;
  /// K0: the block terms without contacts, one symmetric positive definite 6x6
  /// matrix per block [stress, stress x length, stress x length^2].
  virtual const std::vector<Mat6>& block_matrix() const = 0;
  /// F0: the block terms' load vector, 6 per block [force, force x length].
  virtual const Eigen::VectorXd& block_rhs() const = 0;
  /// The contact model, between its begin_step and end_step.
  virtual ContactModel& contacts() = 0;
  /// The analysis settings (iteration limits, solver tolerances).
  virtual const Settings& settings() const = 0;
  /// Assembles K0, F0 and the contacts' terms for their current trial states
  /// and solves K D = F; `loose`: an iterative solver may stop at
  /// Settings::solver_iterate_tolerance instead of its own tolerance (docs/notes/contact-solves.md,
  /// "Inexact iterates"). Throws SingularSystemError (solver.hpp) when K is not
  /// positive definite. Times itself into the step report.
  virtual Eigen::VectorXd solve_system(bool loose) = 0;
  /// The linear solve is iterative, so a loose solve is cheaper than an exact one.
  virtual bool iterative_solver() const = 0;
  /// The contacts check D and update their trial states (ContactModel::check);
  /// what they changed is counted in the step report.
  virtual ContactCheck check(const Eigen::VectorXd& D) = 0;
  /// The step carries velocity (a dynamic step).
  virtual bool dynamic() const = 0;
  /// Iterates a solve may take before the step is cut (Settings::open_close_limit,
  /// or settle.open_close_limit in the settling stage and collapse stages).
  virtual int iteration_limit() const = 0;
};

/// What a contact solve did in one attempt at a step.
struct ContactSolveResult {
  bool converged = false;  ///< D and the contact states agree (the step can be accepted)
  int iterations = 0;      ///< linear solves of the whole system (open-close iterates) [-]
  ContactCheck check;      ///< the last check of the contacts against D
};

/// A way of solving one step's contact problem.
class ContactSolve {
 public:
  virtual ~ContactSolve() = default;
  /// Finds D (6 per block) and contact states that agree, starting from the
  /// contacts' states after begin_step. May throw SingularSystemError (the
  /// caller abandons the step).
  virtual ContactSolveResult solve(StepProblem& problem, Eigen::VectorXd& D) = 0;
};

/// A registered contact solve: its Settings value, its scene word and its maker.
struct ContactSolveEntry {
  ContactSolver method;
  std::string_view word;  ///< the scene's `contact_solver` word
  std::unique_ptr<ContactSolve> (*make)();
};

/// Every contact solve, one row each (contact_solve.cpp).
std::span<const ContactSolveEntry> contact_solves();

/// The contact solve of `kind` (Settings::contact_solver), made from its row.
std::unique_ptr<ContactSolve> make_contact_solve(ContactSolver kind);

}  // namespace rheodda::core
