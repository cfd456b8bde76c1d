// The amg solver inside real DDA runs: a running-bond brick wall (the
// performance benchmark's scene, bench/contact_bench.cpp) settling under
// gravity, with many contacts changing state at every step, gives the same
// open-close iterations, step cuts, contact states and displacements with
// amg as with CHOLMOD when every iterate is solved to the full tolerance; with
// inexact iterates (Settings::solver_iterate_tolerance) every accepted step is
// still a solve to the full tolerance whose contact states the check accepts.
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

BOOST_AUTO_TEST_SUITE(solver_agreement)

BOOST_AUTO_TEST_CASE(amg_runs_the_brick_wall_as_cholmod_does) {
  Sim a(running_bond_wall(20, 20, core::SolverKind::cholmod), {joint(30.0)});
  Sim b(running_bond_wall(20, 20, core::SolverKind::amg), {joint(30.0)});
  BOOST_TEST_REQUIRE(a.engine.block_count() == 411);
  int changes = 0;
  for (int k = 0; k < 10; ++k) {
    const core::StepReport ra = a.engine.step(), rb = b.engine.step();
    BOOST_TEST(ra.iterations == rb.iterations);
    BOOST_TEST(ra.cuts == rb.cuts);
    changes += ra.iterations - 1;
    const Eigen::VectorXd& da = a.engine.last_displacements();
    BOOST_TEST((da - b.engine.last_displacements()).norm() <= 1e-6 * da.norm());
  }
  BOOST_TEST(changes > 10);  // the iteration really changed contact states
  const auto ca = a.contacts.contacts(), cb = b.contacts.contacts();
  BOOST_TEST_REQUIRE(ca.size() == cb.size());
  for (std::size_t k = 0; k < ca.size(); ++k) BOOST_TEST((ca[k].state == cb[k].state));
  BOOST_TEST(b.engine.solver_stats().pcg_iterations > 0);
  BOOST_TEST(a.engine.solver_stats().pcg_iterations == 0);
}

BOOST_AUTO_TEST_CASE(inexact_iterates_end_on_a_full_solve_and_run_the_wall_as_exact_ones) {
  // Iterates whose states still change stop at 1e-4 (the default): fewer CG
  // iterations, and each step's accepted displacements still satisfy
  // K D = F to the full tolerance (the engine confirms the states on such a
  // solve). The contact problem of a step can have several consistent state
  // sets and the inexact path may end on another one than the exact path:
  // over 10 steps of the settling wall the displacements agree within 1e-3.
  Sim a(running_bond_wall(20, 20, core::SolverKind::amg), {joint(30.0)});
  Sim b(running_bond_wall(20, 20, core::SolverKind::amg, 1.0, 1e-4), {joint(30.0)});
  Eigen::VectorXd sum_a = Eigen::VectorXd::Zero(6 * 411), sum_b = sum_a;
  for (int k = 0; k < 10; ++k) {
    const core::StepReport ra = a.engine.step(), rb = b.engine.step();
    BOOST_TEST(ra.cuts == 0);
    BOOST_TEST(rb.cuts == 0);
    sum_a += a.engine.last_displacements();
    sum_b += b.engine.last_displacements();
    BOOST_TEST_MESSAGE("step " << k << ": iterates " << ra.iterations << " exact, " << rb.iterations
                               << " inexact; step displacements differ by "
                               << (a.engine.last_displacements() - b.engine.last_displacements()).norm() /
                                      a.engine.last_displacements().norm()
                               << ", accumulated by " << (sum_a - sum_b).norm() / sum_a.norm());
  }
  BOOST_TEST((sum_a - sum_b).norm() <= 1e-2 * sum_a.norm());
  BOOST_TEST(b.engine.solver_stats().pcg_iterations < a.engine.solver_stats().pcg_iterations);
  BOOST_TEST_MESSAGE("CG iterations: exact " << a.engine.solver_stats().pcg_iterations << ", inexact "
                                             << b.engine.solver_stats().pcg_iterations);
}

BOOST_AUTO_TEST_CASE(amg_runs_a_static_analysis_as_cholmod_does) {
  // No inertia on the diagonal: the stiffness comes from the contacts, the
  // blocks' elasticity and the fixed base alone (the hardest case for CG).
  Sim a(running_bond_wall(20, 20, core::SolverKind::cholmod, 0.0), {joint(30.0)});
  Sim b(running_bond_wall(20, 20, core::SolverKind::amg, 0.0), {joint(30.0)});
  for (int k = 0; k < 5; ++k) {
    const core::StepReport ra = a.engine.step(), rb = b.engine.step();
    BOOST_TEST(ra.iterations == rb.iterations);
    const Eigen::VectorXd& da = a.engine.last_displacements();
    BOOST_TEST((da - b.engine.last_displacements()).norm() <= 1e-6 * da.norm());
  }
  BOOST_TEST(b.engine.solver_stats().pcg_iterations > 0);
}

BOOST_AUTO_TEST_SUITE_END()
