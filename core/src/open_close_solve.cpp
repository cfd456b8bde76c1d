// Shi's open-close iteration (Shi 1988; docs/contacts.md, "States and the
// open-close iteration"): solve K(S) D = F(S) for the trial states S, let the
// contacts check D and update S, repeat until a check changes nothing, at most
// Settings::max_open_close iterates. The reference contact solve.
#include "contact_solves.hpp"

namespace rheodda::core {

namespace {

class OpenCloseSolve final : public ContactSolve {
 public:
  ContactSolveResult solve(StepProblem& p, Eigen::VectorXd& D) override {
    const Settings& s = p.settings();
    ContactSolveResult out;
    // Inexact iterates (docs/notes/contact-solves.md, "Inexact iterates"): while the
    // states still change, an iterative solve stops at a loose tolerance; a
    // trial converges only on a check of a solve at the full one.
    // At most a third of the limit's worth of iterates is solved loosely, and
    // those do not count towards the limit: an iteration that has not settled
    // by then (a wall whose contacts chatter) goes on with exact solves as
    // without the option, with the whole limit ahead of it.
    const bool may_loosen = s.pcg_iterate_tolerance > s.pcg_tolerance && p.iterative_solver();
    bool tight_next = false;
    int loose_iterates = 0;
    const int limit = p.iteration_limit();
    while (out.iterations - loose_iterates < limit) {
      const bool loose = may_loosen && !tight_next && 3 * loose_iterates < limit;
      if (loose) ++loose_iterates;
      D = p.solve_system(loose);
      ++out.iterations;
      out.check = p.check(D);
      if (out.check.state_changes == 0) {
        if (loose) {  // settled on an inexact solve: confirm on an exact one
          tight_next = true;
          continue;
        }
        out.converged = true;
        break;
      }
      tight_next = false;
    }
    return out;
  }
};

}  // namespace

std::unique_ptr<ContactSolve> make_open_close_solve() { return std::make_unique<OpenCloseSolve>(); }

}  // namespace rheodda::core
