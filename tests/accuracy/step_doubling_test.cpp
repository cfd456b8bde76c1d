// Step doubling with local extrapolation (Settings::step_tolerance,
// docs/reference/step-controls.md "Step doubling") on the seed's two-block shear creep
// test (Section 4; Burgers joint of Table 1 row 1; MPa, mm, h) under the staged
// shear load with unloading of adaptive_stepping_test.cpp: tau from 0 h, ramp
// to 2 tau over 80-85.5 h, ramp to 0 over 140-143.3 h, 0-200 h. The joint set
// uses the implicit scheme, first order on the ramps, so that the fixed-step
// error is first order in dt; reference: the Boltzmann superposition of the
// closed form (eqs. 20-21). Steps and solves are counted, never timed.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/laws/registry.hpp"
#include "staged_two_block.hpp"

using namespace rheodda;

namespace {

using namespace rheodda::test::staged;
constexpr double kWidth = 100.0;  // block side [mm]

struct Control {
  double dt = 1.0;              ///< first (or fixed) step [h]
  double step_tolerance = 0.0;  ///< [mm]; 0 = fixed dt
  bool extrapolation = true;
  double dt_max = 0.0;          ///< [h]
};

struct Run {
  std::vector<core::StepReport> reports;
  std::vector<double> t, d;  ///< time [h] and joint displacement [mm] after each step
  double error = 0.0;        ///< largest |d - d_exact| over the steps [mm]
  long solves = 0;           ///< linear solves (open-close iterates) [-]
  std::size_t samples = 0;   ///< measurement samples recorded
};

/// Block A (100 x 100 mm) on block B (300 x 100 mm, held by three fixed
/// points), static analysis without gravity; normal load sigma w and the
/// staged shear load on A at the joint line.
Run run(const Control& c) {
  const double w = kWidth;
  core::Model m = two_blocks(w, c.dt);
  m.settings.step_tolerance = c.step_tolerance;
  m.settings.step_extrapolation = c.extrapolation;
  m.settings.dt_max = c.dt_max;
  m.measurement_points.push_back({1, {w, w}});
  add_staged_loads(m, w);
  contact::JointSet j;
  j.name = "joint";
  j.friction_angle = 60.0;
  j.normal_stiffness = 1e4;
  j.law = burgers_row1();
  contact::ContactSettings cs = core::contact_settings_for(m);
  cs.scheme = laws::Scheme::implicit;
  contact::ContactSystem contacts({j}, cs);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(m, adapter);
  Run r;
  engine.add_observer([&](const core::Engine& e, const core::StepReport& rep) {
    double sum = 0.0;
    int n = 0;
    for (const auto& ct : contacts.contacts())
      if (ct.key.vblock == 1) sum -= ct.shear_displacement, ++n;
    r.error = std::max(r.error, std::abs(sum / n - exact(e.time())));
    r.t.push_back(e.time());
    r.d.push_back(sum / n);
    r.solves += rep.iterations;
  });
  engine.run_until(kEnd);
  r.reports = engine.reports();
  r.samples = engine.measurements().front().size();
  return r;
}

/// Uniform doubled steps of h: a tolerance no step reaches, dt_max = h.
Control uniform_doubling(double h, bool extrapolation) {
  Control c;
  c.dt = h;
  c.dt_max = h;
  c.step_tolerance = 1e3;  // [mm]: 5e4 x the peak displacement
  c.extrapolation = extrapolation;
  return c;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(step_doubling)

BOOST_AUTO_TEST_CASE(without_extrapolation_a_doubled_step_ends_where_two_fixed_half_steps_do) {
  // The doubled step takes dt once, rolls engine and contacts back to the step
  // start, and takes dt/2 twice: the rollback must be exact, so the run is the
  // fixed run at dt/2 sampled every other step.
  // h = 0.1 h: every load sample time is a multiple of h, so both runs step
  // on them without shortened steps.
  const double h = 0.1;
  const Run d = run(uniform_doubling(h, false));
  const Run f = run({0.5 * h});
  BOOST_TEST_REQUIRE(d.t.size() == 2000u);
  BOOST_TEST_REQUIRE(f.t.size() == 4000u);
  // Up to the first ramp (constant load, the joint creeping 0.2 to 1.2 um/h)
  // to round-off. On and after the ramps the two clocks differ by round-off
  // (the fixed run sums 0.05 h steps, the doubled run lands on the load sample
  // times), which moves the ramp loads by ~1e-13 of their change: 1e-9 there.
  for (std::size_t k = 0; k < d.t.size(); ++k) {
    BOOST_TEST_INFO("step " << k << ", t = " << d.t[k] << " h");
    const double tol = d.t[k] <= kStage2 + 1e-9 ? 1e-12 : 1e-9;
    BOOST_TEST(d.t[k] == f.t[2 * k + 1], boost::test_tools::tolerance(1e-12));
    BOOST_TEST(d.d[k] == f.d[2 * k + 1], boost::test_tools::tolerance(tol));
  }
  for (const auto& rep : d.reports) BOOST_TEST(!rep.extrapolated);
}

BOOST_AUTO_TEST_CASE(extrapolation_raises_the_order_from_one_to_two) {
  // Fixed steps (on the load sample times for these h) and doubled steps with
  // extrapolation, each at h and h/2: the error ratio is 2^p for order p.
  const double h = 0.5;
  const Run f1 = run({h}), f2 = run({0.5 * h});
  const Run x1 = run(uniform_doubling(h, true)), x2 = run(uniform_doubling(0.5 * h, true));
  BOOST_TEST_MESSAGE("fixed: " << f1.error << " " << f2.error << " mm; extrapolated: " << x1.error
                               << " " << x2.error << " mm");
  const double fixed_order = std::log2(f1.error / f2.error);
  const double doubling_order = std::log2(x1.error / x2.error);
  BOOST_TEST(fixed_order == 1.0, boost::test_tools::tolerance(0.1));
  BOOST_TEST(doubling_order == 2.0, boost::test_tools::tolerance(0.1));
  // Every step was extrapolated (the joint stays locked, the contacts the same).
  for (const auto& rep : x1.reports) BOOST_TEST(rep.extrapolated);
  // At equal h the extrapolated run is far more accurate than either fixed run.
  BOOST_TEST(x1.error < 0.05 * f2.error);
}

BOOST_AUTO_TEST_CASE(a_tighter_tolerance_takes_more_solves_errs_less_and_beats_fixed_steps) {
  // The finest fixed step tried, 0.02 h (10 000 solves), errs 1.9e-6 mm.
  const Run finest = run({0.02});
  long last_solves = 0;
  double last_error = INFINITY;
  for (double tol : {1e-5, 1e-6, 1e-7, 1e-8}) {  // [mm]; the peak displacement is 0.021 mm
    const Run a = run({0.01, tol});
    BOOST_TEST_MESSAGE("step_tolerance " << tol << " mm: " << a.reports.size() << " steps, "
                                         << a.solves << " solves, error " << a.error
                                         << " mm; fixed 0.02 h: " << finest.solves
                                         << " solves, error " << finest.error << " mm");
    BOOST_TEST(a.solves > last_solves);
    BOOST_TEST(a.error < last_error);
    BOOST_TEST(a.error <= tol);
    // More accurate than the finest fixed step, in fewer solves.
    BOOST_TEST(a.error < finest.error);
    BOOST_TEST(a.solves < finest.solves);
    last_solves = a.solves;
    last_error = a.error;
  }
}

BOOST_AUTO_TEST_CASE(steps_end_on_the_load_sample_times_and_restart_from_dt_after_them) {
  const double dt = 0.01;
  const Run a = run({dt, 1e-7});
  for (double t : {kStage2, kRamp2, kStage3, kRamp3}) {
    BOOST_TEST_CONTEXT("load sample time " << t << " h") {
      const auto it = std::find_if(a.reports.begin(), a.reports.end(), [&](const auto& r) {
        return std::abs(r.time - t) < 1e-9;
      });
      BOOST_TEST_REQUIRE((it != a.reports.end()));
      BOOST_TEST_REQUIRE((it + 1 != a.reports.end()));
      BOOST_TEST((it + 1)->dt == dt);
    }
  }
  // One report and one measurement sample per doubled step (plus the initial sample).
  BOOST_TEST(a.samples == a.reports.size() + 1);
  BOOST_TEST(a.t.back() == kEnd, boost::test_tools::tolerance(1e-12));
  // The step grows while the load is constant: the step ending at 80 h is long.
  const auto at80 = std::find_if(a.reports.begin(), a.reports.end(),
                                 [](const auto& r) { return std::abs(r.time - kStage2) < 1e-9; });
  BOOST_TEST(at80->dt > 10 * dt);
}

BOOST_AUTO_TEST_CASE(no_step_is_shorter_than_dt_unless_it_ends_on_a_load_sample_time) {
  // A tolerance no step of 0.5 h meets: the control would shrink the step
  // without end; dt (the first step) is its floor, and only steps cut short
  // to land on a load sample time or the end are shorter.
  const double dt = 0.5;
  const double tol = 1e-20;  // [mm]: below round-off
  const Run a = run({dt, tol});
  BOOST_TEST_REQUIRE(a.reports.size() > 10u);
  std::size_t missed = 0;  // steps whose estimate asked for a smaller step
  for (const auto& r : a.reports) {
    if (r.step_error > 2 * tol) ++missed;
    const bool lands = std::abs(r.time - kStage2) < 1e-9 || std::abs(r.time - kRamp2) < 1e-9 ||
                       std::abs(r.time - kStage3) < 1e-9 || std::abs(r.time - kRamp3) < 1e-9 ||
                       std::abs(r.time - kEnd) < 1e-9;
    BOOST_TEST_INFO("step ending at " << r.time << " h, dt " << r.dt << " h");
    BOOST_TEST((r.dt >= dt * (1 - 1e-12) || lands));
  }
  BOOST_TEST(missed > a.reports.size() / 2);
}

BOOST_AUTO_TEST_CASE(bad_step_doubling_settings_are_refused_naming_the_key) {
  auto refused = [](core::Settings s, const std::string& key) {
    core::Model m;
    core::BlockDef b;
    b.vertices = rect(0, 0, 1, 1);
    m.blocks = {b};
    m.settings = s;
    try {
      core::Engine e(m);
    } catch (const core::ModelError& err) {
      return std::string(err.what()).find(key) != std::string::npos;
    }
    return false;
  };
  core::Settings negative;
  negative.step_tolerance = -1.0;
  BOOST_TEST(refused(negative, "settings.step_tolerance"));
  core::Settings both;
  both.step_tolerance = 1e-3;
  both.creep_tolerance = 1e-3;
  BOOST_TEST(refused(both, "settings.step_tolerance"));
  core::Settings small_max;
  small_max.step_tolerance = 1e-3;
  small_max.dt = 1.0;
  small_max.dt_max = 0.5;
  BOOST_TEST(refused(small_max, "settings.dt_max"));
}

BOOST_AUTO_TEST_CASE(a_model_without_contacts_is_stepped_by_doubling_too) {
  // A free block under a constant point load in a dynamic analysis: Shi's
  // scheme is exact for a constant acceleration, so every doubled step agrees
  // with its halves (error estimate at round-off) and the step doubles up to dt_max.
  core::Model m;
  core::BlockDef b;
  b.vertices = rect(0, 0, 1, 1);
  m.blocks = {b};
  m.settings.gravity = {0.0, -9.81};
  m.settings.dt = 1e-3;
  m.settings.dt_max = 0.064;
  m.settings.step_tolerance = 1e-6;
  m.settings.max_displacement_ratio = 1e3;  // free fall over 1 s: no displacement limit
  core::Engine e(m);
  e.run_until(1.0);
  double largest = 0.0;
  for (const auto& r : e.reports()) largest = std::max(largest, r.dt);
  BOOST_TEST(largest == 0.064, boost::test_tools::tolerance(1e-12));
  for (const auto& r : e.reports()) BOOST_TEST(r.step_error < 1e-9);
  // Free fall: y = -g t^2 / 2 at the centroid.
  BOOST_TEST(e.centroid(0).y() - 0.5 == -0.5 * 9.81, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_SUITE_END()
