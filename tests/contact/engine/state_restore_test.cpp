// Engine::save/restore with ContactSystem::state/restore (docs/reference/engine.md, "A
// step"; the state a resumed `rheodda run` takes up): an engine and a contact
// system built anew and restored from a run's state after some steps take the
// next steps bit for bit as the run itself does: a settling brick wall with
// CHOLMOD and with amg (whose multigrid keeps the aggregates of earlier
// systems), a thrown block whose contact search reaches as far as its motion,
// and a creeping joint whose Burgers histories, creep counters and adaptive
// creep steps carry over, with amg's warm start too.
#include <boost/test/unit_test.hpp>

#include "creep_scene.hpp"
#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// The blocks and contacts of two runs agree to the last bit.
void same_state(const Sim& a, const Sim& b) {
  BOOST_TEST(a.engine.step_count() == b.engine.step_count());
  BOOST_TEST(a.engine.time() == b.engine.time());
  for (int k = 0; k < a.engine.block_count(); ++k) {
    BOOST_TEST((a.engine.block(k).vertices == b.engine.block(k).vertices), "block " << k);
    BOOST_TEST((a.engine.block(k).stress == b.engine.block(k).stress), "block " << k);
    BOOST_TEST((a.engine.block(k).velocity == b.engine.block(k).velocity), "block " << k);
  }
  const auto ca = a.contacts.contacts(), cb = b.contacts.contacts();
  BOOST_TEST_REQUIRE(ca.size() == cb.size());
  for (std::size_t c = 0; c < ca.size(); ++c) {
    BOOST_TEST(ca[c].id == cb[c].id);
    BOOST_TEST((ca[c].state == cb[c].state));
    BOOST_TEST(ca[c].normal_force == cb[c].normal_force);
    BOOST_TEST(ca[c].shear_force == cb[c].shear_force);
    BOOST_TEST(ca[c].creep_displacement == cb[c].creep_displacement);
  }
  BOOST_TEST(a.engine.energy().total.residual == b.engine.energy().total.residual);
}

/// Runs `a` `first` steps, restores its state into `b` (built alike, never
/// stepped), then steps both `then` steps and compares them at every step.
void restore_and_step_on(Sim& a, Sim& b, int first, int then) {
  for (int k = 0; k < first; ++k) a.engine.step();
  b.engine.restore(a.engine.save());
  b.contacts.restore(a.contacts.state());
  BOOST_TEST(b.engine.reports().empty());
  for (int k = 0; k < then; ++k) {
    const core::StepReport ra = a.engine.step(), rb = b.engine.step();
    BOOST_TEST(ra.dt == rb.dt);
    BOOST_TEST(ra.iterations == rb.iterations);
    BOOST_TEST(ra.cuts == rb.cuts);
    BOOST_TEST(ra.search_widenings == rb.search_widenings);
    same_state(a, b);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(state_restore)

BOOST_AUTO_TEST_CASE(a_restored_brick_wall_steps_on_bit_for_bit_with_cholmod_and_with_amg) {
  for (const auto solver : {core::SolverKind::cholmod, core::SolverKind::amg}) {
    BOOST_TEST_CONTEXT((solver == core::SolverKind::amg ? "amg" : "cholmod")) {
      Sim a(running_bond_wall(8, 10, solver), {joint(30.0)});
      Sim b(running_bond_wall(8, 10, solver), {joint(30.0)});
      BOOST_TEST_REQUIRE(a.engine.block_count() == 86);  // above amg's coarsest level: a hierarchy
      restore_and_step_on(a, b, 6, 6);
      if (solver == core::SolverKind::amg) BOOST_TEST(b.engine.solver_stats().pcg_iterations > 0);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_restored_falling_block_searches_as_far_as_its_motion_needs) {
  // A block thrown down at 10 m/s onto a base 200 m wide (docs/reference/engine.md,
  // "Contact search reach"; search_reach_test.cpp): the search's reach follows
  // the motion, 0.4 m after the first steps, where a new engine would start
  // from the floor (0.1 m) and widen its first step's search again.
  core::Model m;
  m.settings.dt = 0.02;
  m.settings.max_displacement_ratio = 0.01;
  add_fixed(m, rect(-100.0, -1.0, 100.0, 0.0));
  m.blocks.push_back(block(rect(0.0, 1.0, 1.0, 2.0), Vec2(0.0, -10.0)));
  m.blocks.push_back(block(rect(50.0, 0.0, 51.0, 1.0)));  // at rest: the median block is 1 m
  Sim a(m, {joint(30.0)}), b(m, {joint(30.0)});
  restore_and_step_on(a, b, 2, 8);
  BOOST_TEST(a.engine.block(1).centroid.y() < 1.0);  // it landed
}

BOOST_AUTO_TEST_CASE(a_restored_creeping_joint_steps_on_bit_for_bit) {
  // The seed's two-block shear creep test (Table 1 row 1) under a shear load
  // that ramps up, in adaptive creep steps (creep_tolerance) with the
  // exponential-linear scheme: its error estimate uses the stresses of the last
  // step's start, which the state must carry too. With CHOLMOD, and with amg,
  // whose conjugate gradient starts from the last solution (the steps of a
  // steady creep are alike) rather than from zero.
  for (const auto solver : {core::SolverKind::cholmod, core::SolverKind::amg}) {
    BOOST_TEST_CONTEXT((solver == core::SolverKind::amg ? "amg" : "cholmod")) {
      CreepScene scene(table1_burgers(kTable1[0]), 1.408, 0.232, 0.1);
      scene.model.settings.creep_tolerance = 1e-6;  // [mm]
      scene.model.settings.solver = solver;
      scene.model.point_loads[1].history = {{0.0, {0.0, 0.0}}, {50.0, {0.464 * CreepScene::w, 0.0}}};
      contact::ContactSettings settings = core::contact_settings_for(scene.model);
      settings.scheme = laws::Scheme::exponential_linear;
      Sim a(scene.model, {scene.joint}, settings), b(scene.model, {scene.joint}, settings);
      restore_and_step_on(a, b, 12, 12);
      BOOST_TEST(a.contacts.creep_counters()[0].contact_time > 0.0);
      BOOST_TEST(a.contacts.creep_counters()[0].contact_time == b.contacts.creep_counters()[0].contact_time);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
