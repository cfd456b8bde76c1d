// DDA spot-check of the stability map (docs/notes/step-controls.md, "Stability
// map", "DDA spot-check"). The map is measured on the law alone (a spring k in
// series with a Kelvin element, held displacement, laws::solve_series_force);
// here the seed's two-block shear creep test (Section 4, Figure 6; the scene of
// creep_scene.hpp) is run by the DDA engine at seven points of the map
// (dt E2/eta2, k/E2) with each scheme, and its stability is compared point by
// point with the law-level result.
//
// Law: kelvin, E2 = 192.43 MPa/mm, eta2 = 2141.23 MPa h/mm (Table 1 row 1),
// with the joint's shear_stiffness k [MPa/mm]: the contact is then exactly the
// map's model, a spring k in series with a Kelvin element (a Burgers law would
// add its dashpot eta1 and tie k to E1).
//
// Two variants of the scene, 200 steps each:
//  - relaxation: A held at a shear displacement delta = tau/k and a normal
//    closure sigma/k_n from t = 0 (the map's load case). Growth = largest
//    |contact shear force| over steps 101-200 divided by its closed-form value
//    at t = 0+, k delta l (the map's measure).
//  - creep: the seed's constant loads F1 = sigma w, F2 = tau w. The load fixes
//    the sum of the contact forces, which no scheme can get wrong; the map
//    applies to the redistribution of force between A's two base contacts
//    (their difference sees the contact spring k, in series with the blocks'
//    elasticity, as a held displacement; seeded by the scene's small asymmetry).
//    Growth = largest |contact shear force| over steps 101-200 divided by the
//    largest one of step 1.
// A run is stopped as diverged when its growth measure exceeds kStop at any step.
// Units MPa, mm, h; forces per unit thickness [N/mm].
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "creep_scene.hpp"
#include "held_spring.hpp"  // tests/models
#include "two_block.hpp"  // tests/models
#include "rheodda/laws/history.hpp"

using namespace rheodda;
using namespace rheodda::testing;

namespace {

const Table1Row& kRow = kTable1[0];
const double kE2 = kRow.E2, kEta2 = kRow.eta2;  // [MPa/mm], [MPa h/mm]
constexpr int kSteps = 200;                     // steps per run [-]
constexpr double kStop = 1e3;  // growth at which a run is stopped as diverged [-]
constexpr double kFixedStiffness = 1e12;  // fixed-point penalty spring [N/mm per mm]

/// Lagged stability limit dt_lim E2/eta2 = -ln(1 - 2 E2/(k + E2)) for k > E2,
/// none for k <= E2 (docs/notes/step-controls.md, "Stability map").
double lagged_limit(double y) { return y <= 1.0 ? INFINITY : -std::log(1.0 - 2.0 / (y + 1.0)); }

struct Point {
  double x, y;  ///< dt E2/eta2 [-], k/E2 [-]
};

/// The spot-check points: k <= E2 at a huge step, k/E2 = 10 and 100 at 0.5x
/// and 2x the lagged limit, and the corner dt E2/eta2 = k/E2 = 1e3.
std::vector<Point> spot_points() {
  return {{1e3, 0.1},
          {1e3, 1.0},
          {0.5 * lagged_limit(10.0), 10.0},
          {2.0 * lagged_limit(10.0), 10.0},
          {0.5 * lagged_limit(100.0), 100.0},
          {2.0 * lagged_limit(100.0), 100.0},
          {1e3, 1e3}};
}

std::shared_ptr<const laws::ContactRheology> kelvin() {
  return make_law("kelvin", {{"E2", kE2}, {"eta2", kEta2}});
}

/// The map's growth (bench/stability_map.cpp, tests/accuracy/stability_map_test.cpp):
/// a spring k in series with the Kelvin element, held at delta from t = 0,
/// laws::solve_series_force per step; largest |F| over steps 101-200 / (k delta).
/// With `closing_step_implicit` the first step is integrated with the implicit
/// constants whatever the scheme, as the DDA contact integrates the step in
/// which it closes (docs/reference/rheology-in-dda.md, "Schemes").
double law_growth(laws::Scheme scheme, Point p, bool closing_step_implicit = false,
                  double* end_ratio = nullptr) {
  const auto law = kelvin();
  const double dt = p.x * kEta2 / kE2, k = p.y * kE2, delta = 1e-3;  // [h], [MPa/mm], [mm]
  const laws::StepConstants ks = law->step_constants(dt, scheme);
  const laws::StepConstants first =
      law->step_constants(dt, closing_step_implicit ? laws::Scheme::implicit : scheme);
  return models::held_spring_growth(*law, first, ks, k, delta, kSteps, end_ratio);  // tests/models/held_spring.hpp
}

/// Closed-form force of the relaxation, relative to k delta: standard linear
/// solid F(t)/(k delta) = [E2 + k exp(-(k + E2) t/eta2)]/(k + E2)
/// (docs/reference/rheology-in-dda.md, Validation: a Kelvin joint under held displacement).
double relaxation_closed_form(double y, double t) {
  const double k = y * kE2;
  return (kE2 + k * std::exp(-(k + kE2) * t / kEta2)) / (k + kE2);
}

enum class Variant { relaxation, creep };

struct DdaRun {
  double growth = 0.0;        ///< the variant's growth measure (see the header) [-]
  int diverged_at = 0;        ///< step at which growth exceeded kStop, 0 if never [-]
  double end_error = 0.0;     ///< relaxation: |F(end)/F_closed(end) - 1| of the mean contact force [-]
  double creep_error = 0.0;   ///< creep: largest |d - d_closed|/d_closed of the joint's mean shear [-]
  double amplification = 0.0; ///< diverged runs: |joint shear force| of the last step / of the one before [-]
};

/// Runs the two-block scene through the DDA engine (as shear_creep_test.cpp does).
DdaRun run_dda(Variant variant, laws::Scheme scheme, Point p) {
  const double dt = p.x * kEta2 / kE2, k = p.y * kE2, w = CreepScene::w;  // [h], [MPa/mm], [mm]
  auto law = kelvin();
  CreepScene scene(law, kRow.sigma, kRow.tau, dt);
  scene.joint.shear_stiffness = k;  // the spring k in series with the Kelvin element
  // A joint that cannot fail below the stop threshold (cohesion and tensile
  // strength >> kStop tau): a diverging scheme then shows its own growth, not
  // the Mohr-Coulomb limit.
  scene.joint.cohesion = 1e4;          // [MPa]
  scene.joint.tensile_strength = 1e4;  // [MPa]
  const double kn = *scene.joint.normal_stiffness;  // [MPa/mm]
  const double delta = kRow.tau / k;  // held shear displacement [mm]: tau at t = 0+
  if (variant == Variant::relaxation) {
    // A fixed point on A (a spring K to its initial position, core/model.hpp)
    // loaded by K u is a displacement u imposed through K: A's joint line is
    // held at (delta, -sigma/k_n). K = 1e12 N/mm/mm >> k w (<= 1.9e7), so
    // the spring seen by the joint is k to within k w/K <= 2e-5.
    scene.model.settings.fixed_point_stiffness = kFixedStiffness;
    scene.model.fixed_points.push_back({1, {0.5 * w, 0.0}});
    const double closure = kRow.sigma / kn;  // [mm]: normal stress sigma in the joint
    scene.model.point_loads[0].history = {{0.0, {0.0, -(kFixedStiffness + kn * w) * closure}}};
    scene.model.point_loads[1].history = {{0.0, {kFixedStiffness * delta, 0.0}}};
  }
  contact::ContactSettings settings = core::contact_settings_for(scene.model);
  settings.scheme = scheme;
  contact::ContactSystem contacts({scene.joint}, settings);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(scene.model, adapter);

  DdaRun run;
  models::GrowthWatch watch;
  double scale = 0.0;  // stress the growth is relative to [MPa]
  for (int n = 1; n <= kSteps; ++n) {
    engine.step();
    const models::JointForces f = models::joint_forces(contacts);
    if (variant == Variant::relaxation) {
      scale = k * delta;  // closed-form stress at t = 0+ [MPa]
      const double closed = relaxation_closed_form(p.y, engine.time());
      run.end_error = std::abs(f.shear_force / f.length / (k * delta) / closed - 1.0);
    } else {
      if (n == 1) scale = f.largest_stress;
      // Kelvin joint's creep curve d(t) = tau/k + tau/E2 (1 - exp(-E2 t/eta2))
      // (docs/reference/rheology-in-dda.md, "Units"; the Kelvin part of the seed's eqs. 20-21).
      const double closed = kRow.tau / k + law->displacement_closed_form(kRow.tau, engine.time());
      run.creep_error = std::max(run.creep_error, std::abs(joint_shear(contacts) - closed) / closed);
    }
    if (watch.diverged(n, kSteps, f, scale, kStop)) break;
  }
  run.growth = watch.growth;
  run.diverged_at = watch.diverged_at;
  run.amplification = watch.amplification;
  return run;
}

std::string describe(laws::Scheme s, Point p) {
  return std::string(laws::scheme_name(s)) + " at dt E2/eta2 = " + std::to_string(p.x) +
         ", k/E2 = " + std::to_string(p.y);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(stability_spot_check)

// Implicit and exponential-linear are stable over the whole law-level map; in
// DDA they must be too at every spot-check point. Relaxation: growth <= 1 and
// equal to the law-level growth computed with the contact's closing-step rule
// (to 1e-5; measured <= 2.1e-7), and the force at the end within 1e-5 of the
// closed form (measured <= 8.7e-7) - the law-level run ends within 1e-9 of it
// at every point, as 200 steps cover >= 200 relaxation times eta2/(k + E2).
// The DDA residuals come from the stiff blocks (E = 1e7 MPa) and the fixed-point
// springs in series with the joint. Creep: no contact force grows, and the
// joint's mean shear follows the closed form within 1e-8 at every step
// (measured <= 3.0e-9).
BOOST_AUTO_TEST_CASE(implicit_and_exponential_linear_are_stable_at_every_point_as_the_map_says) {
  for (const Point& p : spot_points())
    for (laws::Scheme s : {laws::Scheme::implicit, laws::Scheme::exponential_linear}) {
      BOOST_TEST_CONTEXT(describe(s, p)) {
        double law_end = 0.0;
        const double law = law_growth(s, p, false, &law_end);
        const double law_dda_rule = law_growth(s, p, true);
        const double closed_end = relaxation_closed_form(p.y, kSteps * p.x * kEta2 / kE2);
        BOOST_TEST(law <= 1.0 + 1e-12);  // the map's verdict at this point: stable
        BOOST_TEST(std::abs(law_end / closed_end - 1.0) < 1e-9);
        const DdaRun relax = run_dda(Variant::relaxation, s, p);
        const DdaRun creep = run_dda(Variant::creep, s, p);
        BOOST_TEST_MESSAGE(describe(s, p) << ": relaxation growth " << relax.growth << " (law "
                                          << law << "), end error " << relax.end_error
                                          << "; creep growth " << creep.growth
                                          << ", displacement error " << creep.creep_error);
        BOOST_TEST(relax.diverged_at == 0);
        BOOST_TEST(relax.growth <= 1.0 + 1e-9);
        BOOST_TEST(std::abs(relax.growth / law_dda_rule - 1.0) < 1e-5);
        BOOST_TEST(relax.end_error < 1e-5);
        BOOST_TEST(creep.diverged_at == 0);
        BOOST_TEST(creep.growth <= 1.0 + 1e-9);
        BOOST_TEST(creep.creep_error < 1e-8);
      }
    }
}

// The lagged scheme (the seed's eqs. 12-16) amplifies an error by
// 1 - b (k + E2)/E2 per step, b = 1 - exp(-dt E2/eta2): stable for
// dt E2/eta2 < -ln(1 - 2 E2/(k + E2)) when k > E2, at any dt when k <= E2
// (docs/notes/step-controls.md, "Stability map"). At each point the closed-form
// limit, the law-level map and both DDA variants must give the same verdict.
// A stable DDA run meets the same bounds as above (relaxation growth = the
// law-level one with the closing-step rule to 1e-5, end force within 1e-5 of
// the closed form, creep within 1e-8); an unstable one exceeds kStop within
// the 200 steps, and so does the law-level run, and the relaxing joint force
// grows by the law-level amplification factor per step.
BOOST_AUTO_TEST_CASE(lagged_is_stable_below_its_limit_and_diverges_above_it_as_the_map_says) {
  const laws::Scheme s = laws::Scheme::lagged;
  for (const Point& p : spot_points()) {
    BOOST_TEST_CONTEXT(describe(s, p)) {
      const bool predicted_stable = p.x < lagged_limit(p.y);
      const double law = law_growth(s, p);
      const DdaRun relax = run_dda(Variant::relaxation, s, p);
      const DdaRun creep = run_dda(Variant::creep, s, p);
      BOOST_TEST_MESSAGE(describe(s, p) << ": limit dt E2/eta2 = " << lagged_limit(p.y)
                                        << ", law growth " << law << ", relaxation growth "
                                        << relax.growth << " (diverged at step "
                                        << relax.diverged_at << "), creep growth " << creep.growth
                                        << " (diverged at step " << creep.diverged_at
                                        << "), creep displacement error up to then "
                                        << creep.creep_error);
      BOOST_TEST((law <= 1.0 + 1e-12) == predicted_stable);
      BOOST_TEST((relax.growth <= 1.0 + 1e-9) == predicted_stable);
      BOOST_TEST((creep.growth <= 1.0 + 1e-9) == predicted_stable);
      if (predicted_stable) {
        BOOST_TEST_MESSAGE("  law-level growth with the closing-step rule " << law_growth(s, p, true)
                                                                           << ", relaxation end error "
                                                                           << relax.end_error);
        BOOST_TEST(relax.diverged_at == 0);
        BOOST_TEST(creep.diverged_at == 0);
        BOOST_TEST(std::abs(relax.growth / law_growth(s, p, true) - 1.0) < 1e-5);
        BOOST_TEST(relax.end_error < 1e-5);
        BOOST_TEST(creep.creep_error < 1e-8);
      } else {
        BOOST_TEST(law > kStop);
        BOOST_TEST(relax.diverged_at > 0);
        BOOST_TEST(creep.diverged_at > 0);
        // The joint's shear force (the sum over A's base contacts: the map's
        // model) grows by the law-level factor per step, |1 - b (k + E2)/E2|
        // (the derivation above), within 1e-3 (measured <= 2.4e-4).
        const double b = -std::expm1(-p.x);
        const double factor = std::abs(1.0 - b * (p.y + 1.0));
        BOOST_TEST_MESSAGE("  relaxation growth per step " << relax.amplification << ", law-level "
                                                            << factor);
        BOOST_TEST(std::abs(relax.amplification / factor - 1.0) < 1e-3);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
