// The contact solves of core/ (contact_solve.hpp), one file each; the factory
// make_contact_solve (contact_solve.cpp) picks one by Settings::contact_solver.
#pragma once

#include <functional>
#include <memory>

#include "rheodda/core/contact_solve.hpp"

namespace rheodda::core {

/// The iterates both solves take: solve, let the contacts check D, repeat,
/// until `accept` takes an exact iterate (open_close_solve.cpp). Inexact
/// iterates (docs/notes/contact-solves.md, "Inexact iterates"): while the
/// states still change, an iterative solve stops at a loose tolerance; a loose
/// iterate is never accepted, and one that settled is confirmed on an exact
/// solve. At most a third of the limit's worth of iterates is solved loosely,
/// and those do not count towards the limit.
ContactSolveResult iterate_contacts(StepProblem& p, Eigen::VectorXd& D,
                                    const std::function<bool(const ContactCheck&)>& accept);

/// Shi's open-close iteration, the reference (open_close_solve.cpp).
std::unique_ptr<ContactSolve> make_open_close_solve();
/// Newton's iterates converged on the residual (newton_solve.cpp).
std::unique_ptr<ContactSolve> make_newton_solve();

}  // namespace rheodda::core
