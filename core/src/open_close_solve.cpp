// Shi's open-close iteration (Shi 1988; docs/reference/contacts.md, "States and the
// open-close iteration"): solve K(S) D = F(S) for the trial states S, let the
// contacts check D and update S, repeat until a check changes nothing, at most
// Settings::open_close_limit iterates. The reference contact solve.
#include "contact_solves.hpp"

namespace rheodda::core {

namespace {

class OpenCloseSolve final : public ContactSolve {
 public:
  ContactSolveResult solve(StepProblem& p, Eigen::VectorXd& D) override {
    return iterate_contacts(p, D, [](const ContactCheck& c) { return c.state_changes == 0; });
  }
};

}  // namespace

ContactSolveResult iterate_contacts(StepProblem& p, Eigen::VectorXd& D,
                                    const std::function<bool(const ContactCheck&)>& accept) {
  const Settings& s = p.settings();
  ContactSolveResult out;
  const bool may_loosen = s.solver_iterate_tolerance > s.solver_tolerance && p.iterative_solver();
  bool tight_next = false;
  int loose_iterates = 0;
  const int limit = p.iteration_limit();
  while (out.iterations - loose_iterates < limit) {
    const bool loose = may_loosen && !tight_next && 3 * loose_iterates < limit;
    if (loose) ++loose_iterates;
    D = p.solve_system(loose);
    ++out.iterations;
    out.check = p.check(D);
    if (loose) {
      tight_next = out.check.state_changes == 0;  // settled: confirm on an exact solve
      continue;
    }
    tight_next = false;
    if (accept(out.check)) {
      out.converged = true;
      break;
    }
  }
  return out;
}

std::unique_ptr<ContactSolve> make_open_close_solve() { return std::make_unique<OpenCloseSolve>(); }

}  // namespace rheodda::core
