// How the engine drives a ContactModel and controls the step size:
// - the protocol begin_step -> {assemble -> solve -> check}* -> end_step, with
//   abandon_step and a dt cut (x0.3) when the open-close limit is reached;
// - contact terms given through the SystemSink couple blocks, and CHOLMOD and
//   PCG runs of the same coupled model agree;
// - a step whose displacement exceeds max_displacement_ratio * w0 is cut and redone, and dt grows
//   back afterwards;
// - a settling stage (Settings::settle_*) takes its own steps and limit, then hands over.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;
using rheodda::contact::BlockView;
using rheodda::contact::SystemSink;

namespace {

/// Springs k between the same point seen from two blocks (energy
/// k/2 |T_a(p) D_a - T_b(p) D_b|^2). check() reports one state change on the
/// first iteration of each attempt, then none.
class SpringContacts : public ContactModel {
 public:
  struct Spring {
    int a, b;
    Vec2 p;
  };
  std::vector<Spring> springs;
  double k = 1e9;
  int failing_attempts = 0;  // attempts that never converge (forcing cuts)
  std::string log;
  std::vector<double> dts;

  void begin_step(std::span<const BlockView>, const StepContext& ctx) override {
    log += "B";
    dts.push_back(ctx.dt);
    iteration_ = 0;
  }
  void assemble(std::span<const BlockView> blocks, SystemSink& sink) override {
    log += "A";
    for (const auto& s : springs) {
      const auto Ta = rheodda::contact::displacement_matrix(blocks[s.a].centroid, s.p);
      const auto Tb = rheodda::contact::displacement_matrix(blocks[s.b].centroid, s.p);
      sink.add_stiffness(s.a, s.a, k * Ta.transpose() * Ta);
      sink.add_stiffness(s.b, s.b, k * Tb.transpose() * Tb);
      sink.add_stiffness(s.b, s.a, -k * Tb.transpose() * Ta);  // host adds the transpose to (a, b)
    }
  }
  ContactCheck check(std::span<const BlockView>, const Eigen::VectorXd&) override {
    log += "C";
    ContactCheck c;
    c.state_changes = (failing_attempts > 0 || iteration_ == 0) ? 1 : 0;
    // Told apart by kind: a slip on the first iterate of an attempt, a stick after.
    (iteration_ == 0 ? c.changes.slipped : c.changes.stuck) = c.state_changes;
    ++iteration_;
    return c;
  }
  void end_step(std::span<const BlockView>, const Eigen::VectorXd&) override { log += "E"; }
  void abandon_step() override {
    log += "X";
    --failing_attempts;
  }

 private:
  int iteration_ = 0;
};

Model hanging_chain(SolverKind solver) {
  Model m;
  m.settings.dt = 1e-3;
  m.settings.max_displacement_ratio = 0.05;
  m.settings.solver = solver;
  m.settings.solver_tolerance = 1e-14;
  for (int k = 0; k < 4; ++k)
    m.blocks.push_back(block({{1.0 * k, 0}, {1.0 * k + 1, 0}, {1.0 * k + 1, 1}, {1.0 * k, 1}}));
  m.fixed_points.push_back({.block = 0, .point = {0.0, 0.0}});
  m.fixed_points.push_back({.block = 0, .point = {0.0, 1.0}});
  return m;
}

void link_chain(SpringContacts& c) {
  for (int k = 0; k < 3; ++k) {
    c.springs.push_back({k, k + 1, {k + 1.0, 0.0}});
    c.springs.push_back({k, k + 1, {k + 1.0, 1.0}});
  }
}

/// The linked chain whose contacts fail to converge in their first `attempts`
/// attempts, with an open-close limit of 3 iterates.
Model failing_chain(SpringContacts& c, int attempts) {
  link_chain(c);
  c.failing_attempts = attempts;
  Model m = hanging_chain(SolverKind::cholmod);
  m.settings.open_close_limit = 3;
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(step_control)

BOOST_AUTO_TEST_CASE(contacts_are_driven_through_the_step_protocol) {
  SpringContacts c;
  link_chain(c);
  Engine e(hanging_chain(SolverKind::cholmod), c);
  const StepReport r = e.step();
  BOOST_TEST(c.log == "BACACE");
  BOOST_TEST(r.iterations == 2);
  BOOST_TEST(r.cuts == 0);
}

BOOST_AUTO_TEST_CASE(open_close_failure_abandons_and_cuts_dt) {
  SpringContacts c;
  const Model m = failing_chain(c, 1);
  Engine e(m, c);
  const StepReport r = e.step();
  BOOST_TEST(c.log == "BACACACX" "BACACE");
  BOOST_TEST(r.cuts == 1);
  // The report sums the changes of every iterate of both attempts by kind:
  // attempt 1 (cut) slip, stick, stick; attempt 2 slip, then none.
  BOOST_TEST(r.changes.slipped == 2);
  BOOST_TEST(r.changes.stuck == 2);
  BOOST_TEST(r.changes.closed + r.changes.opened + r.changes.refinements == 0);
  BOOST_TEST(r.dt == 0.3 * 1e-3, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(c.dts.size() == 2u);
  BOOST_TEST(c.dts[1] == 0.3 * c.dts[0], boost::test_tools::tolerance(1e-15));
  // The next step is allowed to grow back by dt_growth.
  const StepReport r2 = e.step();
  BOOST_TEST(r2.dt == 1.5 * 0.3 * 1e-3, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(an_open_close_iteration_that_never_converges_says_what_still_changed) {
  SpringContacts c;
  Model m = failing_chain(c, 100);
  m.settings.max_cuts = 2;
  Engine e(m, c);
  try {
    e.step();
    BOOST_FAIL("the step should have thrown after max_cuts cuts");
  } catch (const std::runtime_error& err) {
    const std::string what = err.what();
    BOOST_TEST(what.find("open-close iteration did not converge (the last of its iterates still "
                         "changed 1: 1 stuck) after 2 cuts of dt (settings.max_cuts)") !=
                   std::string::npos,
               what);
  }
  BOOST_TEST(e.step_count() == 0);
}

BOOST_AUTO_TEST_CASE(cholmod_and_pcg_runs_of_a_coupled_model_agree) {
  SpringContacts c1, c2;
  link_chain(c1);
  link_chain(c2);
  Engine e1(hanging_chain(SolverKind::cholmod), c1), e2(hanging_chain(SolverKind::pcg), c2);
  for (int k = 0; k < 20; ++k) {
    e1.step();
    e2.step();
    const Eigen::VectorXd& d1 = e1.last_displacements();
    BOOST_TEST((d1 - e2.last_displacements()).norm() <= 1e-8 * d1.norm());
  }
  // The chain really is coupled: the free end moved, the fixed block barely.
  BOOST_TEST(e1.point_displacement(3, {4.0, 0.0}).norm() > 1e3 * e1.point_displacement(0, {0.0, 0.0}).norm());
  BOOST_TEST(e1.solver_stats().analyses == 1);
  BOOST_TEST(e2.solver_stats().pcg_iterations > 0);
}

BOOST_AUTO_TEST_CASE(steps_exceeding_the_allowed_displacement_are_cut) {
  // A falling 1 m square, w0 = 0.5 m, max_displacement_ratio = 0.001: at most 0.5 mm per step.
  Model m;
  m.settings.dt = 0.05;  // first trial step would fall 12 mm
  m.settings.max_displacement_ratio = 0.001;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  Engine e(m);
  BOOST_TEST(e.allowed_displacement() == 5e-4, boost::test_tools::tolerance(1e-15));
  const StepReport r = e.step();
  BOOST_TEST(r.cuts > 0);
  BOOST_TEST(r.max_displacement <= e.allowed_displacement());
  BOOST_TEST(r.dt == 0.05 * std::pow(0.3, r.cuts), boost::test_tools::tolerance(1e-12));
  // Free fall from rest is exact whatever dt: y = -g dt^2/2.
  BOOST_TEST(e.point_displacement(0, {0, 0}).y() == -0.5 * 9.81 * r.dt * r.dt,
             boost::test_tools::tolerance(1e-12));
  double t = r.dt;
  for (int k = 0; k < 30; ++k) {
    const StepReport rk = e.step();
    BOOST_TEST(rk.max_displacement <= e.allowed_displacement());
    t += rk.dt;
  }
  BOOST_TEST(std::abs(e.time() - t) <= 1e-14);
  BOOST_TEST(std::abs(e.centroid(0).y() - (0.5 - 0.5 * 9.81 * t * t)) <= 1e-12);
}

BOOST_AUTO_TEST_CASE(a_step_that_cannot_be_made_small_enough_throws_after_max_cuts) {
  Model m;
  m.settings.dt = 0.05;
  m.settings.max_displacement_ratio = 1e-9;  // would need dt ~ 1e-5: more than 2 cuts of x0.3
  m.settings.max_cuts = 2;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  Engine e(m);
  BOOST_CHECK_THROW(e.step(), std::runtime_error);
  BOOST_TEST(e.step_count() == 0);
  BOOST_TEST(e.centroid(0).y() == 0.5);
}

BOOST_AUTO_TEST_CASE(a_settling_stage_takes_its_own_steps_and_limit_then_hands_over) {
  // docs/reference/engine.md, "Settling stage": a falling 1 m square (w0 = 0.5 m). Until
  // t = 0.03 the steps are at most 0.01 with max_displacement_ratio = 0.01 (5 mm; the 0.01 steps fall
  // less, so none is cut), the stage's last step ends on 0.03; then dt = 0.05 and
  // max_displacement_ratio = 1 (no limit here) apply, the first step after the stage at 0.05.
  Model m;
  m.settings.dt = 0.05;
  m.settings.max_displacement_ratio = 1.0;
  m.settings.settle.until = 0.03;
  m.settings.settle.dt = 0.01;
  m.settings.settle.max_displacement_ratio = 0.01;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  Engine e(m);
  BOOST_TEST(e.allowed_displacement() == 0.005, boost::test_tools::tolerance(1e-15));
  for (int k = 0; k < 3; ++k) {
    const StepReport r = e.step();
    BOOST_TEST(r.dt == 0.01, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(r.cuts == 0);
  }
  BOOST_TEST(e.time() == 0.03, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(e.allowed_displacement() == 0.5, boost::test_tools::tolerance(1e-15));  // max_displacement_ratio = 1 now
  const StepReport after = e.step();
  BOOST_TEST(after.dt == 0.05, boost::test_tools::tolerance(1e-12));
  // A static analysis (no carried velocity) would fall g dt^2/2 per step; this
  // one is dynamic: free fall is exact through the hand-over.
  BOOST_TEST(e.centroid(0).y() == 0.5 - 0.5 * 9.81 * 0.08 * 0.08, boost::test_tools::tolerance(1e-12));
  // The stage's limit cuts its steps as max_displacement_ratio does: settle.max_displacement_ratio 1e-4 (0.05 mm).
  Model tight = m;
  tight.settings.settle.max_displacement_ratio = 1e-4;
  Engine t(tight);
  const StepReport r = t.step();
  BOOST_TEST(r.cuts > 0);
  BOOST_TEST(r.max_displacement <= 0.5e-4 * (1.0 + 1e-12));
  // Bad stage settings name their key.
  Model bad = m;
  bad.settings.settle.dt = 0.0;
  BOOST_CHECK_EXCEPTION(Engine{bad}, ModelError, [](const ModelError& x) { return x.key() == "settings.settle.dt"; });
}

BOOST_AUTO_TEST_CASE(observers_see_every_accepted_step) {
  Model m;
  m.settings.max_displacement_ratio = 1.0;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  Engine e(m);
  std::vector<int> seen;
  e.add_observer([&](const Engine& eng, const StepReport& r) {
    seen.push_back(r.step);
    BOOST_TEST(eng.step_count() == r.step + 1);
  });
  e.run(5);
  BOOST_TEST((seen == std::vector<int>{0, 1, 2, 3, 4}));
  BOOST_TEST(e.reports().size() == 5u);
}

BOOST_AUTO_TEST_SUITE_END()
