#include "rheodda/core/contact_solve.hpp"

#include <array>
#include <stdexcept>

#include "contact_solves.hpp"

namespace rheodda::core {

namespace {

constexpr std::array<ContactSolveEntry, 2> kContactSolves{{
    {ContactSolver::open_close, "open-close", make_open_close_solve},
    {ContactSolver::newton, "newton", make_newton_solve},
}};

}  // namespace

std::span<const ContactSolveEntry> contact_solves() { return kContactSolves; }

std::unique_ptr<ContactSolve> make_contact_solve(ContactSolver kind) {
  for (const ContactSolveEntry& e : kContactSolves)
    if (e.method == kind) return e.make();
  throw std::logic_error("a contact solve without a row in contact_solves()");
}

}  // namespace rheodda::core
