// Adaptive creep stepping (Settings::creep_tolerance, docs/reference/step-controls.md)
// on the seed's two-block shear creep test (Section 4; Burgers joint of
// Table 1 row 1; MPa, mm, h) under a staged shear load with unloading:
// tau from 0 h, ramp to 2 tau over 80-85.5 h, ramp to 0 over 140-143.3 h, 0-200 h.
// Reference: the Boltzmann superposition of the closed form (eqs. 20-21),
// staged_two_block.hpp. Steps are counted, never timed.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/laws/history.hpp"
#include "rheodda/laws/registry.hpp"
#include "staged_two_block.hpp"

using namespace rheodda;

namespace {

using namespace rheodda::test::staged;

/// Block A (w x w) on block B (3w x w, fixed by three fixed points), static
/// analysis without gravity at a first step dt, creep tolerance `tolerance`.
core::Model two_blocks(double w, double dt, double tolerance) {
  core::Model m = test::staged::two_blocks(w, dt);
  m.settings.creep_tolerance = tolerance;
  return m;
}

struct Run {
  std::vector<core::StepReport> reports;
  std::vector<double> t, d;  ///< time [h] and joint displacement [mm] after each step
  double error = 0.0;  ///< largest |d - d_exact| over the steps [mm]
  int steps = 0;
};

/// Block A (100 x 100 mm) on fixed block B; normal load sigma w and staged shear
/// load on A at the joint line.
Run run(double dt, double tolerance, double t_end = kEnd, double held_by = 0.0,
        double friction_angle = 60.0, bool restart_on_contact_change = false) {
  const double w = 100.0;
  core::Model m = two_blocks(w, dt, tolerance);
  m.settings.creep_restart_on_contact_change = restart_on_contact_change;
  if (held_by > 0.0) {  // A also held at its top corners by fixed-point springs [N/mm]
    m.settings.fixed_point_stiffness = held_by;
    const auto& top = m.blocks[1].vertices;  // A's corners
    m.fixed_points.push_back({1, top[2]});
    m.fixed_points.push_back({1, top[3]});
  }
  add_staged_loads(m, w);
  const std::shared_ptr<const laws::ContactRheology> law = burgers_row1();
  contact::JointSet j;
  j.name = "joint";
  j.friction_angle = friction_angle;
  j.normal_stiffness = 1e4;
  j.law = law;
  contact::ContactSystem contacts({j}, core::contact_settings_for(m));
  core::ContactAdapter adapter(contacts);
  core::Engine engine(m, adapter);
  Run r;
  engine.add_observer([&](const core::Engine& e, const core::StepReport&) {
    double sum = 0.0;
    int n = 0;
    for (const auto& c : contacts.contacts())
      if (c.key.vblock == 1) sum -= c.shear_displacement, ++n;
    const double exact = test::staged::exact(e.time());
    r.error = std::max(r.error, std::abs(sum / n - exact));
    r.t.push_back(e.time());
    r.d.push_back(sum / n);
  });
  engine.run_until(t_end);
  r.reports = engine.reports();
  r.steps = engine.step_count();
  return r;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(adaptive_stepping)

BOOST_AUTO_TEST_CASE(keeps_the_staged_creep_error_under_the_tolerance_in_fewer_steps_than_a_fixed_step) {
  const double tol = 1e-7;  // [mm]; the peak displacement is 0.021 mm
  const Run adaptive = run(0.01, tol);
  BOOST_TEST(adaptive.error <= tol);
  // The largest fixed step (default scheme, run as given: its steps do not land
  // on the ramp ends, adaptive steps do) that is at least as accurate.
  std::optional<Run> fixed;
  for (double dt : {20.0, 10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01}) {
    Run r = run(dt, 0.0);
    if (r.error <= adaptive.error) {
      fixed = std::move(r);
      break;
    }
  }
  BOOST_TEST_REQUIRE(fixed.has_value());
  BOOST_TEST_MESSAGE("adaptive: " << adaptive.steps << " steps, error " << adaptive.error
                                  << " mm; fixed: " << fixed->steps << " steps, error "
                                  << fixed->error << " mm");
  BOOST_TEST(adaptive.steps < fixed->steps);
}

// Block A also held by springs (fixed points of 2000 N/mm at its top corners,
// block B's fixed points as soft): the joint's creep moves load onto the
// springs, so the joint force changes continuously - no closed form. The
// reference is a fixed-step run at dt = 0.005 h (default scheme); error = the
// joint displacement at 100 h against it.
BOOST_AUTO_TEST_CASE(on_a_redistributing_load_a_tighter_tolerance_takes_more_steps_and_errs_less) {
  const double t_end = 100.0, held_by = 2000.0;
  const Run ref = run(0.005, 0.0, t_end, held_by);
  BOOST_TEST_REQUIRE(std::abs(ref.t.back() - t_end) < 1e-9);
  auto error = [&](const Run& r) { return std::abs(r.d.back() - ref.d.back()); };
  int last_steps = 0;
  double last_error = INFINITY;
  for (double tol : {1e-6, 1e-7, 1e-8, 1e-9}) {
    const Run a = run(0.01, tol, t_end, held_by);
    BOOST_TEST_MESSAGE("tolerance " << tol << " mm: " << a.steps << " steps, error " << error(a));
    BOOST_TEST(a.steps > last_steps);
    BOOST_TEST(error(a) < last_error);
    last_steps = a.steps;
    last_error = error(a);
  }
  // At 1e-8 mm: fewer steps than every fixed step at least as accurate.
  const Run a = run(0.01, 1e-8, t_end, held_by);
  for (double dt : {10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1}) {
    const Run f = run(dt, 0.0, t_end, held_by);
    BOOST_TEST_INFO("fixed dt = " << dt << " h: " << f.steps << " steps, error " << error(f));
    if (error(f) <= error(a)) BOOST_TEST(a.steps < f.steps);
  }
}

BOOST_AUTO_TEST_CASE(the_step_restarts_from_dt_after_a_load_change) {
  const double dt = 0.01;
  const Run r = run(dt, 1e-7);
  // The step ending at the ramp start is long; the step after it is dt again.
  double before = 0.0, after = 0.0;
  for (std::size_t k = 0; k + 1 < r.reports.size(); ++k)
    if (std::abs(r.reports[k].time - kStage2) < 1e-9) {
      before = r.reports[k].dt;
      after = r.reports[k + 1].dt;
    }
  BOOST_TEST(before > 10 * dt);
  BOOST_TEST(after == dt);
}

BOOST_AUTO_TEST_CASE(the_step_doubles_while_the_load_is_constant) {
  // Constant load up to 80 h: both schemes' increments agree (estimate 0), so
  // each step doubles (up to the end of the run).
  const Run r = run(0.01, 1e-7, 79.0);
  for (std::size_t k = 1; k + 1 < r.reports.size(); ++k)
    BOOST_TEST(r.reports[k].dt == std::min(2 * r.reports[k - 1].dt, 79.0 - r.reports[k - 1].time),
               boost::test_tools::tolerance(1e-12));
}

/// The contacts of `inner` with a scripted creep error estimate: any attempt
/// longer than `dt_limit` [h] that starts before `until` [h] reports 100 x the
/// tolerance, which forces the engine to reject and redo it; everything else,
/// retract_step included, is the real adapter's.
class ForcedRejection final : public core::ContactModel {
 public:
  ForcedRejection(core::ContactAdapter& inner, double tol, double dt_limit, double until)
      : inner_(inner), tol_(tol), dt_limit_(dt_limit), until_(until) {}
  void begin_step(std::span<const contact::BlockView> b, const core::StepContext& ctx) override {
    force_ = ctx.dt > dt_limit_ && ctx.time < until_;
    inner_.begin_step(b, ctx);
  }
  void assemble(std::span<const contact::BlockView> b, contact::SystemSink& s) override {
    inner_.assemble(b, s);
  }
  core::ContactCheck check(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    return inner_.check(b, D);
  }
  void end_step(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    inner_.end_step(b, D);
  }
  void abandon_step() override { inner_.abandon_step(); }
  double creep_error_estimate() const override {
    return force_ ? 100.0 * tol_ : inner_.creep_error_estimate();
  }
  bool retract_step() override { return inner_.retract_step(); }
  int creep_state_changes() const override { return inner_.creep_state_changes(); }

 private:
  core::ContactAdapter& inner_;
  double tol_, dt_limit_, until_;
  bool force_ = false;
};

// A step whose creep error estimate exceeds 2 x the tolerance is redone
// smaller (Engine::Impl::step), the contacts rolled back exactly by
// ContactAdapter::retract_step. Under the creep test's constant load every step
// size integrates the law exactly (docs/guide/choosing-step-controls.md), so a rollback that
// left any trace (creep counted twice, a moved locking point) would show as an
// error against the closed form (the seed's eqs. 20-21).
BOOST_AUTO_TEST_CASE(a_step_whose_creep_error_exceeds_twice_the_tolerance_is_redone_smaller) {
  const double w = 100.0, tol = 1e-7, dt = 0.01, dt_limit = 1.0, until = 50.0;  // mm, h
  struct Out {
    std::vector<core::StepReport> reports;
    double error = 0.0;  ///< largest |d - d_exact| over the steps / peak d_exact [-]
  };
  // Constant shear load tau from t = 0; rejections forced before `forced_until` [h].
  auto creep_run = [&](double forced_until) {
    core::Model m = two_blocks(w, dt, tol);
    m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {0.0, -kSigma * w}}}});
    m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {kTau * w, 0.0}}}});
    const std::shared_ptr<const laws::ContactRheology> law = laws::LawRegistry::builtin().create(
        "burgers", {{"E1", kE1}, {"E2", kE2}, {"eta1", kEta1}, {"eta2", kEta2}});
    contact::JointSet j;
    j.name = "joint";
    j.friction_angle = 60.0;
    j.normal_stiffness = 1e4;
    j.law = law;
    contact::ContactSystem contacts({j}, core::contact_settings_for(m));
    core::ContactAdapter adapter(contacts);
    ForcedRejection forced(adapter, tol, dt_limit, forced_until);
    core::Engine engine(m, forced);
    double worst = 0.0, peak = 0.0;  // [mm]
    engine.add_observer([&](const core::Engine& e, const core::StepReport&) {
      double sum = 0.0;
      int n = 0;
      for (const auto& c : contacts.contacts())
        if (c.key.vblock == 1) sum -= c.shear_displacement, ++n;
      const double exact = law->displacement_closed_form(kTau, e.time());
      peak = std::max(peak, exact);
      worst = std::max(worst, std::abs(sum / n - exact));
    });
    engine.run_until(kEnd);
    return Out{engine.reports(), worst / peak};
  };
  const Out plain = creep_run(0.0), forced = creep_run(until);
  int rejections = 0;
  for (const auto& r : forced.reports) {
    rejections += r.rejections;
    BOOST_TEST_INFO("step " << r.step << " ending at " << r.time << " h, dt " << r.dt << " h");
    if (r.time - r.dt < until) BOOST_TEST(r.dt <= dt_limit);  // every longer attempt was redone
  }
  for (const auto& r : plain.reports) BOOST_TEST(r.rejections == 0);
  BOOST_TEST(rejections > 10);
  BOOST_TEST(forced.reports.size() > plain.reports.size());
  BOOST_TEST(forced.reports.back().dt > dt_limit);  // after `until` the steps grow again
  // The forced run is as exact as the plain one (round-off: ~6e-8 of the peak
  // after the small first steps); a rejected attempt that left its creep behind
  // would add about tau dt / eta1 ~ 1e-5 mm (~1e-3 of the peak) per rejection.
  BOOST_TEST_MESSAGE("error / peak: plain " << plain.error << " (" << plain.reports.size()
                     << " steps), forced " << forced.error << " (" << forced.reports.size()
                     << " steps, " << rejections << " rejections)");
  BOOST_TEST(forced.error <= 2.0 * plain.error);
}

// Friction angle 15 deg: under the ramp to 2 tau (80-85.5 h) the joint's shear
// stress passes sigma tan(15 deg) = 0.377 MPa at about 83.4 h and the contacts
// slide (block A is held by the springs). With creep_restart_on_contact_change
// the step after any step in which a creeping contact changed state is dt.
BOOST_AUTO_TEST_CASE(the_step_restarts_from_dt_after_a_creeping_contact_changes_state) {
  const double t_end = 100.0, held_by = 2000.0, dt = 0.01, tol = 1e-7;
  for (bool restart : {true, false}) {
    const Run r = run(dt, tol, t_end, held_by, 15.0, restart);
    int changes = 0, longer = 0;
    for (std::size_t k = 0; k + 1 < r.reports.size(); ++k) {
      if (r.reports[k].creep_state_changes == 0) continue;
      ++changes;
      BOOST_TEST_INFO("restart " << restart << ", step " << k << " at " << r.reports[k].time << " h");
      if (restart) BOOST_TEST(r.reports[k + 1].dt <= dt * (1 + 1e-12));
      if (r.reports[k + 1].dt > dt * (1 + 1e-12)) ++longer;
    }
    BOOST_TEST_MESSAGE("restart " << restart << ": " << r.steps << " steps, " << changes
                                  << " steps with contact state changes");
    BOOST_TEST(changes >= 2);  // the contacts closed at t = 0 and slid during the ramp
    if (!restart) BOOST_TEST(longer > 0);  // without the option the step does not restart
  }
}

BOOST_AUTO_TEST_CASE(a_negative_creep_tolerance_is_refused_naming_the_key) {
  core::Model m;
  core::BlockDef b;
  b.vertices = rect(0, 0, 1, 1);
  m.blocks = {b};
  m.settings.creep_tolerance = -1.0;
  try {
    core::Engine e(m);
    BOOST_FAIL("no error");
  } catch (const core::ModelError& e) {
    BOOST_TEST(std::string(e.what()).find("settings.creep_tolerance") != std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
