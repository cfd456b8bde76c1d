// Collapse stages (core::SettleStage::collapse_dt; docs/reference/engine.md, "Collapse
// stages"): in a static analysis a step that moves as a mechanism is located
// to within collapse_dt and taken as a dynamic stage, so the collapse follows
// the dynamics whatever the static step, and a model that stands takes none.
#include <boost/test/unit_test.hpp>

#include "sim.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

constexpr double kPhi = 30.0;      // friction angle of the joint [deg]
constexpr double kLoadTime = 1.0;  // the push comes on [s]
constexpr double kEnd = 1.5;       // [s]

/// A 1 m x 0.5 m block resting on a fixed horizontal base, static analysis of
/// step dt, pushed horizontally at its centroid from t = 1 s by 1.5 times the
/// friction force W tan(phi). With collapse_dt > 0: a dynamic settling stage
/// of 0.05 s in steps of 1 ms, and collapse stages located within collapse_dt.
core::Model pushed_block(double dt, double collapse_dt, double& push) {
  core::Model m;
  m.settings.dynamic_ratio = 0.0;
  m.settings.dt = dt;
  m.settings.settle.until = 0.05;
  m.settings.settle.dt = 1e-3;
  m.settings.settle.max_displacement_ratio = 0.01;
  m.settings.settle.dynamic = true;
  m.settings.settle.collapse_dt = collapse_dt;
  add_fixed(m, rect(-1.0, -1.0, 5.0, 0.0));
  m.blocks.push_back(block(rect(1.0, 0.0, 2.0, 0.5)));
  const double weight = m.materials[0].density * 0.5 * 9.81;  // [N/m]
  push = 1.5 * weight * std::tan(deg(kPhi));
  core::PointLoad load;
  load.block = 1;
  load.point = Vec2(1.5, 0.25);
  load.history = {{0.0, Vec2::Zero()}, {kLoadTime, Vec2::Zero()}, {kLoadTime + 1e-9, Vec2(push, 0.0)}};
  m.point_loads.push_back(load);
  return m;
}

struct Outcome {
  double slide = 0.0;                 ///< centroid displacement at kEnd [m]
  double first_stage = -1.0;          ///< start of the first collapse stage (-1: none) [s]
  int stages = 0;
  double relative_residual = 0.0;     ///< energy balance [-]
};

Outcome run(double dt, double collapse_dt) {
  double push = 0.0;
  Sim sim(pushed_block(dt, collapse_dt, push), {joint(kPhi)});
  const Vec2 c0 = sim.engine.centroid(1);
  Outcome o;
  while (sim.engine.time() < kEnd - 1e-9) {
    const core::StepReport r = sim.engine.step();
    if (r.collapse_stage) {
      if (o.stages++ == 0) o.first_stage = r.time - r.dt;
    }
  }
  o.slide = sim.engine.point_displacement(1, c0).x();
  o.relative_residual = sim.engine.energy().relative_residual();
  return o;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(collapse_stages)

BOOST_AUTO_TEST_CASE(a_pushed_block_slides_as_the_dynamics_say_whatever_the_static_step) {
  // The push leaves (F - W tan(phi)) = F / 3 unbalanced: the block slides from
  // t = 1 s with a = F / (3 m), x = a (t - 1)^2 / 2 at 1.5 s (0.354 m). The
  // static steps before the push take no stage; the first stage starts within
  // collapse_dt before the push, and the slide follows the closed form at two
  // static steps (Shi's dynamic step is exact for a constant acceleration).
  double push = 0.0;
  const core::Model probe = pushed_block(0.1, 0.01, push);
  const double mass = probe.materials[0].density * 0.5;  // [kg/m]
  const double a = (push - mass * 9.81 * std::tan(deg(kPhi))) / mass;
  const double closed_form = 0.5 * a * (kEnd - kLoadTime) * (kEnd - kLoadTime);
  for (const double dt : {0.1, 0.05}) {
    BOOST_TEST_CONTEXT("static dt " << dt) {
      const Outcome o = run(dt, 0.01);
      BOOST_TEST_MESSAGE("dt " << dt << ": slide " << o.slide << " m (closed form " << closed_form << "), "
                               << o.stages << " stages, the first at " << o.first_stage << " s");
      BOOST_TEST(o.stages >= 1);
      BOOST_TEST(o.first_stage >= kLoadTime - 0.01 - 1e-9);
      BOOST_TEST(o.first_stage <= kLoadTime + 1e-9);
      BOOST_TEST(o.slide == closed_form, boost::test_tools::tolerance(0.01));
      BOOST_TEST(o.relative_residual < 1e-3);
    }
  }
}

BOOST_AUTO_TEST_CASE(without_collapse_stages_the_static_slide_is_set_by_the_step) {
  // The same push in plain static steps: each step starts at rest and moves the
  // block by F dt^2 / (6 m) (the inertia term alone holds the unbalanced force),
  // so the slide depends on dt and falls far short of the dynamics.
  const Outcome coarse = run(0.1, 0.0), fine = run(0.05, 0.0);
  BOOST_TEST_MESSAGE("static slide " << coarse.slide << " m at dt 0.1 s, " << fine.slide << " m at 0.05 s");
  BOOST_TEST(coarse.stages == 0);
  BOOST_TEST(fine.slide < 0.75 * coarse.slide);
  BOOST_TEST(coarse.slide < 0.5 * run(0.1, 0.01).slide);
}

BOOST_AUTO_TEST_CASE(collapse_dt_needs_a_static_analysis_with_a_dynamic_settling_stage) {
  double push = 0.0;
  auto refused = [](const core::Model& m) {
    BOOST_CHECK_EXCEPTION(core::Engine{m}, core::ModelError,
                          [](const core::ModelError& e) { return e.key() == "settings.settle.collapse_dt"; });
  };
  core::Model m = pushed_block(0.1, 0.01, push);
  m.settings.settle.dynamic = false;
  refused(m);
  m = pushed_block(0.1, 0.01, push);
  m.settings.dynamic_ratio = 1.0;
  refused(m);
  m = pushed_block(0.1, 0.2, push);  // not below dt
  refused(m);
}

BOOST_AUTO_TEST_SUITE_END()
