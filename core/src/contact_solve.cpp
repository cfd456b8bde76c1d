#include "rheodda/core/contact_solve.hpp"

#include "contact_solves.hpp"

namespace rheodda::core {

std::unique_ptr<ContactSolve> make_contact_solve(ContactSolver kind) {
  switch (kind) {
    case ContactSolver::open_close: return make_open_close_solve();
    case ContactSolver::newton: return make_newton_solve();
  }
  return make_open_close_solve();
}

}  // namespace rheodda::core
