// Static steps by explicit cycles (docs/reference/explicit-step.md, "Static steps by cycles";
// core/src/explicit_static.cpp): the seed's shear creep test with every law against its closed
// form and against the implicit static step, a stack under gravity in equilibrium, a block on
// a slope it cannot hold refused with the reason, the same bits whatever the threads, a stop
// asked within a step's cycles, and the settings' ranges.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "creep_scene.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

/// The explicit integrator's static steps by cycles down to `ratio`.
void by_cycles(core::Model& m, double ratio) {
  m.settings.integrator = core::Integrator::explicit_step;
  m.settings.static_force_ratio = ratio;
}

/// The joint's shear displacement [mm] after each step of the creep scene to t_end [h], and
/// the cycles of its steps.
struct CreepRun {
  std::vector<double> time, shear;
  long long cycles = 0;
};

CreepRun run_creep(const CreepScene& scene, double t_end) {
  contact::ContactSystem contacts({scene.joint}, core::contact_settings_for(scene.model));
  core::ContactAdapter adapter(contacts);
  core::Engine engine(scene.model, adapter);
  CreepRun out;
  while (engine.time() < t_end - 1e-9) {
    out.cycles += engine.step().cycles;
    out.time.push_back(engine.time());
    out.shear.push_back(joint_shear(contacts));
  }
  return out;
}

/// Three 1 x 0.25 m blocks stacked on a fixed base, a static analysis of 1 s steps by cycles
/// to an unbalanced-force ratio of 1e-9.
core::Model stack_model() {
  core::Model m;
  m.materials[0].young_modulus = 5e10;
  m.settings.dt = 1.0;
  m.settings.dynamic_ratio = 0.0;
  by_cycles(m, 1e-9);
  add_fixed(m, rect(0.0, -1.0, 3.0, 0.0));
  for (int k = 0; k < 3; ++k) m.blocks.push_back(block(rect(1.0, 0.25 * k, 2.0, 0.25 * (k + 1))));
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(explicit_static)

BOOST_AUTO_TEST_CASE(every_law_creeps_by_cycles_as_its_closed_form_and_as_the_implicit_static_step) {
  // The seed's two-block test (creep_scene.hpp; Table 1's first row; every law, Nishihara below
  // and above its threshold), 0-200 h in steps of 2 h:
  // each creep step taken by cycles to an unbalanced-force ratio of 1e-8 follows the closed
  // form within 0.5 %, as the implicit static step does (shear_creep_test.cpp), and equals the
  // implicit step's displacement to 1e-6 of it (the creep scene's blocks carry no inertia,
  // so both find the same equilibrium; what is left is the ratio's residual).
  const Table1Row& r = kTable1[0];
  std::vector<LawCase> cases{
      {"burgers", "burgers", {{"E1", r.E1}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}}, std::nullopt}};
  for (const LawCase& c : other_law_cases()) cases.push_back(c);
  for (const LawCase& c : cases) {
    BOOST_TEST_CONTEXT(c.name) {
      auto law = make_law(c.law, c.p);
      CreepScene implicit_scene(law, r.sigma, r.tau, 2.0);
      implicit_scene.joint.shear_stiffness = c.shear_stiffness;
      CreepScene cycled_scene = implicit_scene;
      by_cycles(cycled_scene.model, 1e-8);
      const CreepRun imp = run_creep(implicit_scene, 200.0);
      const CreepRun cyc = run_creep(cycled_scene, 200.0);
      BOOST_TEST_REQUIRE(cyc.shear.size() == imp.shear.size());
      const double elastic = c.shear_stiffness ? r.tau / *c.shear_stiffness : 0.0;
      double worst_closed = 0.0, worst_implicit = 0.0;
      for (std::size_t k = 0; k < cyc.shear.size(); ++k) {
        const double exact = elastic + law->displacement_closed_form(r.tau, cyc.time[k]);
        worst_closed = std::max(worst_closed, std::abs(cyc.shear[k] - exact) / exact);
        worst_implicit = std::max(worst_implicit, std::abs(cyc.shear[k] - imp.shear[k]) / imp.shear[k]);
      }
      BOOST_TEST_MESSAGE(c.name << ": d(200 h) = " << cyc.shear.back() << " mm by cycles, " << imp.shear.back()
                                << " mm implicit; against the closed form " << worst_closed
                                << ", against the implicit step " << worst_implicit << "; "
                                << static_cast<double>(cyc.cycles) / static_cast<double>(cyc.shear.size())
                                << " cycles per step");
      BOOST_TEST(worst_closed < 0.005);
      BOOST_TEST(worst_implicit < 1e-6);
      BOOST_TEST(cyc.cycles > 0);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_stack_under_gravity_is_held_in_equilibrium) {
  // Three blocks on a fixed base, a static analysis of 1 s steps by cycles to 1e-9: each
  // block's contacts below carry the weight of the blocks above it and its own, rho g A per
  // unit thickness, within 1e-6; every contact locked.
  core::Model m = stack_model();
  const double weight = m.materials[0].density * 9.81 * 0.25;  // one block's [N/m]
  Sim sim(std::move(m), {joint(30.0)});
  sim.engine.run(3);
  for (int b = 1; b <= 3; ++b) {
    double carried = 0.0;  // normal force of the contacts under block b [N/m]
    for (const contact::Contact& c : sim.contacts.contacts()) {
      const bool below = (c.key.vblock == b && c.key.eblock == b - 1) || (c.key.eblock == b && c.key.vblock == b - 1);
      if (below) carried += c.normal_force;
      BOOST_TEST((c.state == contact::ContactState::locked));
    }
    BOOST_TEST_MESSAGE("under block " << b << ": " << carried << " N/m, weight above " << (4 - b) * weight);
    BOOST_TEST(carried == (4 - b) * weight, boost::test_tools::tolerance(1e-6));
  }
}

BOOST_AUTO_TEST_CASE(a_stop_asked_within_a_static_steps_cycles_abandons_it_and_the_steps_after_are_the_same_bits) {
  // The stack of a_stack_under_gravity_is_held_in_equilibrium: its static steps by cycles look
  // at the stop request as the dynamic step's do (Engine::set_stop_request). Answered yes
  // within the first step's cycles (gravity on at once: thousands of them), the step is
  // abandoned (StepInterrupted) with the blocks and the contacts as at the start; the steps
  // taken from there are those of the run that was never stopped, to the last bit.
  Sim whole(stack_model(), {joint(30.0)});
  const std::vector<double> start = engine_state(whole);
  whole.engine.run(3);
  BOOST_TEST_REQUIRE(whole.engine.reports().front().cycles > core::Engine::kStopPollCycles);

  Sim stopped(stack_model(), {joint(30.0)});
  bool stop = false;
  stopped.engine.set_stop_request([&stop] { return stop; });
  stop = true;
  BOOST_CHECK_THROW(stopped.engine.step(), core::StepInterrupted);
  BOOST_TEST(stopped.engine.step_count() == 0);
  BOOST_TEST((engine_state(stopped) == start));
  stop = false;
  stopped.engine.run(3);
  BOOST_TEST((engine_state(stopped) == engine_state(whole)));
}

BOOST_AUTO_TEST_CASE(a_block_on_a_slope_it_cannot_hold_does_not_settle_and_says_why) {
  // 30 deg slope, phi 20 deg: no equilibrium, so the cycles of each attempt run out and the
  // step is cut until max_cuts, with the reason named.
  core::Model m = incline_scene(deg(30.0), 1.0, 0.5, 4.0);
  m.settings.dynamic_ratio = 0.0;
  m.settings.dt = 1.0;
  m.settings.max_cuts = 2;
  by_cycles(m, 1e-6);
  m.settings.static_max_cycles = 2000;
  Sim sim(std::move(m), {joint(20.0)});
  BOOST_CHECK_EXCEPTION(sim.engine.step(), std::runtime_error, [](const std::runtime_error& e) {
    BOOST_TEST_MESSAGE(e.what());
    return std::string(e.what()).find("did not settle") != std::string::npos &&
           std::string(e.what()).find("static_max_cycles") != std::string::npos;
  });
}

BOOST_AUTO_TEST_CASE(the_same_bits_whatever_the_number_of_threads) {
  // A running-bond wall of 22 bricks on a fixed base (rows of 6 and 5, every brick borne
  // by two below; enough blocks to be kicked in parallel), three static steps by cycles at
  // 1, 2 and 3 threads: every vertex equal to the last bit.
  std::vector<std::vector<Vec2>> runs;
  for (int threads : {1, 2, 3}) {
    core::Model m;
    m.materials[0].young_modulus = 5e9;
    m.settings.dt = 1.0;
    m.settings.dynamic_ratio = 0.0;
    m.settings.threads = threads;
    by_cycles(m, 1e-7);
    add_fixed(m, rect(-1.0, -0.5, 3.0, 0.0));
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < (row % 2 ? 5 : 6); ++k) {
        const double x = 0.4 * k + (row % 2 ? 0.2 : 0.0);
        m.blocks.push_back(block(rect(x, 0.2 * row, x + 0.4, 0.2 * (row + 1))));
      }
    const int bricks = static_cast<int>(m.blocks.size()) - 1;
    Sim sim(std::move(m), {joint(30.0)});
    sim.engine.run(3);
    std::vector<Vec2> v;
    for (int b = 1; b <= bricks; ++b)
      for (const Vec2& x : sim.engine.vertices(b)) v.push_back(x);
    runs.push_back(v);
  }
  BOOST_TEST(runs[0].size() == 22u * 4u);
  for (std::size_t t = 1; t < runs.size(); ++t)
    for (std::size_t i = 0; i < runs[0].size(); ++i) {
      BOOST_TEST(runs[t][i].x() == runs[0][i].x());
      BOOST_TEST(runs[t][i].y() == runs[0][i].y());
    }
}

BOOST_AUTO_TEST_CASE(settings_out_of_range_are_refused) {
  auto refused = [](core::Model m, const std::string& key) {
    BOOST_CHECK_EXCEPTION(core::Engine{m}, core::ModelError,
                          [&](const core::ModelError& e) { return e.key() == key; });
  };
  core::Model m = incline_scene(deg(20.0), 1.0, 0.5, 4.0);
  m.settings.dynamic_ratio = 0.0;
  core::Model implicit_integrator = m;
  implicit_integrator.settings.static_force_ratio = 1e-5;  // without the explicit integrator
  refused(implicit_integrator, "settings.static_force_ratio");
  by_cycles(m, 1e-5);
  core::Model dynamic = m;
  dynamic.settings.dynamic_ratio = 1.0;  // a dynamic analysis has no static steps
  refused(dynamic, "settings.static_force_ratio");
  core::Model ratio = m;
  ratio.settings.static_force_ratio = 1.0;
  refused(ratio, "settings.static_force_ratio");
  core::Model cycles = m;
  cycles.settings.static_max_cycles = 0;
  refused(cycles, "settings.static_max_cycles");
  for (double alpha : {0.0, 1.0}) {
    core::Model damping = m;
    damping.settings.static_local_damping = alpha;
    refused(damping, "settings.static_local_damping");
  }
  BOOST_CHECK_NO_THROW(core::Engine{m});  // a static analysis whose static steps are cycled
}

BOOST_AUTO_TEST_SUITE_END()
