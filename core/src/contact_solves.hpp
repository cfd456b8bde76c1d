// The contact solves of core/ (contact_solve.hpp), one file each; the factory
// make_contact_solve (contact_solve.cpp) picks one by Settings::contact_solver.
#pragma once

#include <memory>

#include "rheodda/core/contact_solve.hpp"

namespace rheodda::core {

/// Shi's open-close iteration, the reference (open_close_solve.cpp).
std::unique_ptr<ContactSolve> make_open_close_solve();
/// Newton's iterates converged on the residual (newton_solve.cpp).
std::unique_ptr<ContactSolve> make_newton_solve();

}  // namespace rheodda::core
