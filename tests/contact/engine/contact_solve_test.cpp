// The two contact solves of a step (docs/reference/contacts.md, "Contact solves"): the
// Newton solve, converged on the residual of the step's equations
// (Settings::contact_residual_tolerance), runs the settling brick wall of the
// performance benchmark as Shi's open-close iteration does, in fewer iterates;
// where the open-close iteration converges on a step whose contact states do
// not flip, both accept the same displacements.
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

core::Model with_solver(core::Model m, core::ContactSolver solver, double tolerance = 1e-4) {
  m.settings.contact_solver = solver;
  m.settings.contact_residual_tolerance = tolerance;
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(contact_solve)

BOOST_AUTO_TEST_CASE(newton_settles_the_brick_wall_as_open_close_does_in_fewer_iterates) {
  // 10 x 10 running-bond wall, 30 dynamic steps of 1 ms: every step changes
  // contact states. Each Newton step leaves a residual of at most 1e-4 of the
  // contact forces (the default contact_residual_tolerance), so its step
  // displacements are within about that of the open-close ones: over the 30
  // steps the accumulated displacements agree within ten times it.
  const core::Model wall = running_bond_wall(10, 10, core::SolverKind::cholmod);
  Sim a(with_solver(wall, core::ContactSolver::open_close), {joint(30.0)});
  Sim b(with_solver(wall, core::ContactSolver::newton), {joint(30.0)});
  const auto n = static_cast<Eigen::Index>(6 * a.engine.block_count());
  Eigen::VectorXd sum_a = Eigen::VectorXd::Zero(n), sum_b = sum_a;
  int iterates_a = 0, iterates_b = 0;
  for (int k = 0; k < 30; ++k) {
    const core::StepReport ra = a.engine.step(), rb = b.engine.step();
    BOOST_TEST(ra.cuts == 0);
    BOOST_TEST(rb.cuts == 0);
    iterates_a += ra.iterations;
    iterates_b += rb.iterations;
    sum_a += a.engine.last_displacements();
    sum_b += b.engine.last_displacements();
  }
  BOOST_TEST_MESSAGE("iterates: open-close " << iterates_a << ", newton " << iterates_b
                                              << "; accumulated displacements differ by "
                                              << (sum_a - sum_b).norm() / sum_a.norm());
  BOOST_TEST(iterates_a > 30);  // the open-close iteration really changed states
  BOOST_TEST(iterates_b <= iterates_a);
  BOOST_TEST((sum_a - sum_b).norm() <= 1e-3 * sum_a.norm());
}

BOOST_AUTO_TEST_CASE(on_a_block_that_slides_steadily_both_solves_take_the_same_steps) {
  // A block sliding down a 30 deg incline with 20 deg friction: one contact
  // state set per step, found by both. The displacements agree to round-off
  // of the tolerance (the residual at the open-close answer is round-off).
  auto incline = [](core::ContactSolver solver) {
    core::Model m;
    m.settings.dt = 1e-3;
    m.settings.contact_solver = solver;
    const double alpha = deg(30.0);
    add_fixed(m, rect(-1.0, -1.0, 7.0, 0.0, alpha));
    m.blocks.push_back(block(rect(4.0, 0.0, 5.0, 0.5, alpha)));
    return m;
  };
  Sim a(incline(core::ContactSolver::open_close), {joint(20.0)});
  Sim b(incline(core::ContactSolver::newton), {joint(20.0)});
  const Vec2 c0 = a.engine.centroid(1);
  for (int k = 0; k < 200; ++k) {
    const core::StepReport ra = a.engine.step(), rb = b.engine.step();
    BOOST_TEST_REQUIRE(ra.cuts == 0);
    BOOST_TEST_REQUIRE(rb.cuts == 0);
  }
  const Vec2 ca = a.engine.centroid(1), cb = b.engine.centroid(1);
  const double travelled = (ca - c0).norm();
  BOOST_TEST_MESSAGE("travelled " << travelled << " m; centroids differ by " << (ca - cb).norm() << " m");
  BOOST_TEST(travelled > 0.01);
  BOOST_TEST((ca - cb).norm() <= 1e-6 * travelled);
}

BOOST_AUTO_TEST_CASE(a_tolerance_outside_zero_to_one_is_refused) {
  core::Model m = running_bond_wall(2, 2, core::SolverKind::cholmod);
  m.settings.contact_solver = core::ContactSolver::newton;
  for (double bad : {0.0, 1.0, -1e-3}) {
    m.settings.contact_residual_tolerance = bad;
    contact::ContactSystem contacts({joint(30.0)}, core::contact_settings_for(m, 40.0));
    core::ContactAdapter adapter(contacts);
    BOOST_CHECK_THROW(core::Engine(m, adapter), core::ModelError);
  }
}

BOOST_AUTO_TEST_SUITE_END()
