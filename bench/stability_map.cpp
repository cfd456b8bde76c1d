// Stability map of the creep schemes (docs/notes/step-controls.md, "Stability map").
//
// Model: a shear spring k in series with a Kelvin element (E2, eta2) - the
// seed's Kelvin part of the Burgers joint, Table 1 row 1 (E2 = 192.43 MPa/mm,
// eta2 = 2141.23 MPa h/mm) - held at a displacement delta from t = 0 (stress
// relaxation). Solved with the law alone: laws::solve_series_force gives the end
// force of each step from the spring and the law's affine creep increment
// (the same algebra as the DDA contact's k_eff = k / (1 + k c), eq. 2 of
// docs/reference/rheology-in-dda.md), then ContactRheology::advance.
// Growth: largest |F| over steps 100-200 divided by the force at t = 0+ (k delta):
// at most 1 for a stable run (the exact force decays monotonically to
// k E2 / (k + E2) delta); > 1 means the step amplifies the force (unstable).
// The lagged scheme (exact exponential under the start force, the seed's
// eqs. 12-16) amplifies an error by 1 - b (k + E2)/E2, b = 1 - exp(-dt E2/eta2):
// stable for dt E2/eta2 < -ln(1 - 2/(k/E2 + 1)) when k > E2, at any dt when
// k <= E2; for k >> E2 this is dt < 2 eta2 / (k + E2) (docs/reference/rheology-in-dda.md).
//
// With --dda: the DDA spot-check of the map instead (docs/notes/step-controls.md,
// "DDA spot-check"; the same runs as tests/contact/engine/stability_spot_check_test.cpp):
// the seed's two-block shear creep test (block A on a fixed block B, Table 1
// row 1's sigma and tau) run by the DDA engine with a kelvin joint (E2, eta2 as
// above, shear_stiffness k, so the contact is the map's spring k in series with
// a Kelvin element) at seven points (dt E2/eta2, k/E2), 200 steps, each scheme:
//  - relaxation: A's joint line held at a shear displacement delta = tau/k (and a
//    normal closure sigma/k_n) through a fixed point of stiffness K = 1e12 N/mm/mm
//    loaded by K delta; growth = largest |contact shear force| over steps 101-200
//    / k delta l (the map's measure);
//  - creep: the seed's constant loads; growth = largest |contact shear force|
//    over steps 101-200 / the largest of step 1 (the load fixes the sum of the
//    contact forces; the map applies to their redistribution).
// A run whose growth exceeds 1e3 at any step is stopped as diverged.
//
// With --power: the map of the nonlinear Norton law (law power-law, docs/reference/laws.md):
// the spring E1 = 26.87 MPa/mm in series with a Norton dashpot A (tau/tau_ref)^n
// (tau_ref = 0.2 MPa, A = tau_ref/34807.72 mm/h), held at delta = tau0/E1, over
// n = 1..20, tau0/tau_ref = 0.01..100 and dt/t0 = 1e-3..1e6 with t0 = tau0 /
// (E1 A (tau0/tau_ref)^n) the initial relaxation time; each step solved by
// Newton (laws::solve_series_force). Growth as above (largest |F| over steps
// 100-200 / tau0); the lagged (explicit) scheme is predicted stable for
// dt < 2 / (E1 A n tau0^(n-1)/tau_ref^n) = 2 t0 / n, the linear limit 2 eta/k
// at the tangent viscosity of tau0 (the stress only falls from there).
//
// Usage: stability_map [--csv FILE]   (prints a Markdown table; FILE gets
//        scheme,dt_E2_over_eta2,k_over_E2,growth for scripts/accuracy-report.sh)
//        stability_map --dda          (prints the DDA spot-check table)
//        stability_map --power        (prints the Norton map's table)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/laws/history.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/seed_table1.hpp"
#include "held_spring.hpp"  // tests/models
#include "two_block.hpp"  // tests/models

using namespace rheodda;

namespace {

constexpr double kE2 = 192.43, kEta2 = 2141.23;  // [MPa/mm], [MPa h/mm] (Table 1 row 1)

/// Growth factor of a relaxation run of `steps` steps (see the header).
double growth(laws::Scheme scheme, double x, double y, int steps = 200) {
  const auto law = laws::LawRegistry::builtin().create("kelvin", {{"E2", kE2}, {"eta2", kEta2}});
  const double dt = x * kEta2 / kE2, k = y * kE2, delta = 1e-3;  // [h], [MPa/mm], [mm]
  const laws::StepConstants ks = law->step_constants(dt, scheme);
  return models::held_spring_growth(*law, ks, ks, k, delta, steps);  // tests/models/held_spring.hpp
}

// ---- DDA spot-check (--dda) ----

constexpr int kDdaSteps = 200;              // steps per DDA run [-]
constexpr double kStop = 1e3;               // growth at which a DDA run is stopped as diverged [-]
constexpr double kFixedStiffness = 1e12;    // fixed-point penalty spring [N/mm per mm]
constexpr double kWidth = 100.0;            // width of A = joint length [mm]
constexpr double kNormalStiffness = 1e4;    // joint normal stiffness [MPa/mm]

/// Lagged limit dt_lim E2/eta2 = -ln(1 - 2 E2/(k + E2)) for k > E2, none for
/// k <= E2 (docs/notes/step-controls.md, "Stability map").
double lagged_limit(double y) { return y <= 1.0 ? INFINITY : -std::log(1.0 - 2.0 / (y + 1.0)); }

/// Closed-form relaxation force relative to k delta, standard linear solid:
/// [E2 + k exp(-(k + E2) t/eta2)]/(k + E2) (docs/reference/rheology-in-dda.md, Validation).
double relaxation_closed_form(double y, double t) {
  const double k = y * kE2;
  return (kE2 + k * std::exp(-(k + kE2) * t / kEta2)) / (k + kE2);
}

struct DdaRun {
  double growth = 0.0;     ///< growth measure (see the header) [-]
  int diverged_at = 0;     ///< step at which growth exceeded kStop, 0 if never [-]
  double end_error = 0.0;  ///< relaxation: |F(end)/F_closed(end) - 1| [-]
  double amplification = 0.0;  ///< diverged: |joint shear force| of the last step / the one before [-]
};

/// The two-block scene (as tests/contact/engine/creep_scene.hpp) with a kelvin
/// joint of shear stiffness k = y E2 at dt = x eta2/E2, run by the DDA engine.
DdaRun dda_run(bool relaxation, laws::Scheme scheme, double x, double y) {
  const laws::SeedTable1Row& row = laws::kSeedTable1[0];
  const double w = kWidth, dt = x * kEta2 / kE2, k = y * kE2;  // [mm], [h], [MPa/mm]
  const double delta = row.tau / k, closure = row.sigma / kNormalStiffness;  // [mm]
  core::Model m = models::two_block_model(w, dt);
  if (relaxation) {
    // A fixed point of stiffness K loaded by K u imposes u through K (core/model.hpp):
    // A's joint line is held at (delta, -closure); K >> k w, so the joint sees k.
    m.settings.fixed_point_stiffness = kFixedStiffness;
    m.fixed_points.push_back({1, {0.5 * w, 0.0}});
    m.point_loads.push_back(
        {1, {0.5 * w, 0.0}, {{0.0, {0.0, -(kFixedStiffness + kNormalStiffness * w) * closure}}}});
    m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {kFixedStiffness * delta, 0.0}}}});
  } else {  // the seed's F1 = sigma w (down) and F2 = tau w (+x) at the joint line
    m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {0.0, -row.sigma * w}}}});
    m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {row.tau * w, 0.0}}}});
  }
  contact::JointSet joint;
  joint.name = "joint";
  joint.friction_angle = 60.0;           // [deg]
  joint.cohesion = 1e4;                  // [MPa]: the joint cannot fail below kStop tau,
  joint.tensile_strength = 1e4;          // [MPa]  so a diverging scheme shows its own growth
  joint.normal_stiffness = kNormalStiffness;
  joint.shear_stiffness = k;
  joint.law = laws::LawRegistry::builtin().create("kelvin", {{"E2", kE2}, {"eta2", kEta2}});
  contact::ContactSettings settings = core::contact_settings_for(m);
  settings.scheme = scheme;
  contact::ContactSystem contacts({joint}, settings);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(m, adapter);
  DdaRun run;
  models::GrowthWatch watch;
  double scale = relaxation ? k * delta : 0.0;  // stress the growth is relative to [MPa]
  for (int n = 1; n <= kDdaSteps; ++n) {
    engine.step();
    const models::JointForces f = models::joint_forces(contacts);
    if (!relaxation && n == 1) scale = f.largest_stress;
    if (relaxation)
      run.end_error = std::abs(f.shear_force / f.length / (k * delta) / relaxation_closed_form(y, engine.time()) - 1.0);
    if (watch.diverged(n, kDdaSteps, f, scale, kStop)) break;
  }
  run.growth = watch.growth;
  run.diverged_at = watch.diverged_at;
  run.amplification = watch.amplification;
  return run;
}

std::string dda_cell(const DdaRun& r) {
  char buf[64];
  if (r.diverged_at)
    std::snprintf(buf, sizeof buf, "> 1e3 (diverged, step %d)", r.diverged_at);
  else
    std::snprintf(buf, sizeof buf, "%.6g", r.growth);
  return buf;
}

/// The spot-check table (Markdown) for scripts/accuracy-report.sh.
int print_dda_table() {
  struct Point {
    double x, y;
    const char* what;
  };
  const double l10 = lagged_limit(10.0), l100 = lagged_limit(100.0);
  const Point points[] = {{1e3, 0.1, "k <= E2, huge step"},
                          {1e3, 1.0, "k = E2, huge step"},
                          {0.5 * l10, 10.0, "0.5 x lagged limit"},
                          {2.0 * l10, 10.0, "2 x lagged limit"},
                          {0.5 * l100, 100.0, "0.5 x lagged limit"},
                          {2.0 * l100, 100.0, "2 x lagged limit"},
                          {1e3, 1e3, "corner of the map"}};
  const laws::Scheme schemes[] = {laws::Scheme::lagged, laws::Scheme::implicit,
                                  laws::Scheme::exponential_linear};
  std::printf("DDA spot-check: two-block scene, kelvin joint (E2 = %g MPa/mm, eta2 = %g MPa h/mm, "
              "shear_stiffness k), %d steps per run; growth > 1 = unstable; a run is stopped when "
              "its growth exceeds 1e3. Relaxation: A held at tau/k; growth = largest contact shear "
              "force in steps 101-200 / k delta l. Creep: the seed's constant loads; growth = largest "
              "contact shear force in steps 101-200 / the largest of step 1. Law-level: the map's "
              "growth (laws::solve_series_force). End error: relaxation force at the end against the "
              "closed form. Per step: a diverging relaxation's joint shear force, last step / the one before, against "
              "the law-level amplification |1 - b (k + E2)/E2|, b = 1 - exp(-dt E2/eta2).\n\n",
              kE2, kEta2, kDdaSteps);
  std::printf("| point | dt E2/eta2 | k/E2 | scheme | DDA growth, relaxation | DDA growth, creep "
              "| law-level growth | relaxation end error | per step, DDA / law | agree |\n"
              "|---|---:|---:|---|---:|---:|---:|---:|---:|---|\n");
  int n = 0, agreeing = 0, total = 0;
  for (const Point& p : points) {
    ++n;
    for (laws::Scheme s : schemes) {
      const double law = growth(s, p.x, p.y);
      const DdaRun relax = dda_run(true, s, p.x, p.y), creep = dda_run(false, s, p.x, p.y);
      const bool law_stable = law <= 1.0 + 1e-12;
      const bool agree = (relax.growth <= 1.0 + 1e-9) == law_stable &&
                         (creep.growth <= 1.0 + 1e-9) == law_stable;
      agreeing += agree;
      ++total;
      char end[32];
      if (relax.diverged_at) std::snprintf(end, sizeof end, "-");
      else std::snprintf(end, sizeof end, "%.1e", relax.end_error);
      char step[48];
      if (relax.diverged_at)  // lagged amplification (docs/notes/step-controls.md, "Stability map")
        std::snprintf(step, sizeof step, "%.5g / %.5g", relax.amplification,
                      std::abs(1.0 + std::expm1(-p.x) * (p.y + 1.0)));
      else std::snprintf(step, sizeof step, "-");
      char lawcell[32];
      std::snprintf(lawcell, sizeof lawcell, std::isfinite(law) ? "%.6g" : "inf (overflow)", law);
      std::printf("| P%d (%s) | %.4g | %g | %s | %s | %s | %s | %s | %s | %s |\n", n, p.what, p.x,
                  p.y, std::string(laws::scheme_name(s)).c_str(), dda_cell(relax).c_str(),
                  dda_cell(creep).c_str(), lawcell, end, step, agree ? "yes" : "no");
    }
  }
  std::printf("\nStable/unstable verdicts of DDA (both variants) and the law-level map agree in %d of "
              "%d runs.\n",
              agreeing, total);
  return 0;  // a benchmark prints, never asserts (the test does)
}

}  // namespace

// ---- Norton map (--power) ----
int print_power_table() {
  constexpr double kE1 = 26.87, kTauRef = 0.2, kA = 0.2 / 34807.72;  // MPa/mm, MPa, mm/h
  const double ns[] = {1, 2, 3, 5, 10, 20};
  const double ratios[] = {0.01, 0.1, 1, 10, 100};
  const double steps[] = {1e-3, 1e-2, 0.1, 0.5, 1, 2, 10, 100, 1e3, 1e4, 1e5, 1e6};
  const laws::Scheme schemes[] = {laws::Scheme::lagged, laws::Scheme::implicit,
                                  laws::Scheme::exponential_linear};
  int stable[3] = {0, 0, 0}, monotone[3] = {0, 0, 0}, total = 0, lagged_as_predicted = 0;
  int lagged_unstable_below = 0;  // unstable although below the predicted limit
  double worst_stable[3] = {0, 0, 0};
  for (double n : ns) {
    const auto law = laws::LawRegistry::builtin().create(
        "power-law", {{"E1", kE1}, {"A", kA}, {"tau_ref", kTauRef}, {"n", n}});
    for (double x : ratios)
      for (double st : steps) {
        const double tau0 = x * kTauRef, delta = tau0 / kE1;
        const double t0 = tau0 / (kE1 * kA * std::pow(x, n));
        ++total;
        for (int s = 0; s < 3; ++s) {
          const laws::StepConstants ks = law->step_constants(st * t0, schemes[s]);
          laws::RheologyState q, next;
          double force = tau0, worst = 0.0;
          bool mono = true;
          for (int i = 1; i <= 200; ++i) {
            const double f = laws::solve_series_force(*law, ks, q, kE1, delta, force);
            law->advance(ks, q, force, f, next);
            if (!std::isfinite(f) || std::abs(f) > 1e6 * tau0) { worst = INFINITY; break; }
            if (f > force * (1 + 1e-12) || f < 0.0) mono = false;
            q = next;
            force = f;
            if (i > 100) worst = std::max(worst, std::abs(f));
          }
          const double g = worst / tau0;
          const bool ok = g <= 1.0 + 1e-12;
          stable[s] += ok;
          monotone[s] += ok && mono;
          if (ok) worst_stable[s] = std::max(worst_stable[s], g);
          if (s == 0 && ok == (st < 2.0 / n)) ++lagged_as_predicted;
          if (s == 0 && !ok && st < 2.0 / n) ++lagged_unstable_below;
        }
      }
  }
  std::printf("Norton map (power-law): n = 1, 2, 3, 5, 10, 20; tau0/tau_ref = 0.01 ... 100; "
              "dt/t0 = 1e-3 ... 1e6 (%d points), 200 steps of relaxation per point, Newton per step.\n\n",
              total);
  std::printf("| scheme | stable points | of them monotone | largest growth among the stable |\n"
              "|---|---:|---:|---:|\n");
  for (int s = 0; s < 3; ++s)
    std::printf("| %s | %d / %d | %d | %.4f |\n", std::string(laws::scheme_name(schemes[s])).c_str(),
                stable[s], total, monotone[s], worst_stable[s]);
  std::printf("\nLagged: stable exactly where predicted (dt < 2 t0 / n) at %d of %d points; "
              "unstable below the limit at %d (the limit is sufficient); the others are stable "
              "at or above it (growth 1 at the limit for n = 1; for n > 1 the stress falls to "
              "where the tangent is smaller).\n",
              lagged_as_predicted, total, lagged_unstable_below);
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 2 && std::string(argv[1]) == "--dda") return print_dda_table();
  if (argc == 2 && std::string(argv[1]) == "--power") return print_power_table();
  FILE* csv = nullptr;
  if (argc == 3 && std::string(argv[1]) == "--csv") {
    csv = std::fopen(argv[2], "w");
    if (!csv) {
      std::fprintf(stderr, "stability_map: cannot write %s\n", argv[2]);
      return 2;
    }
    std::fprintf(csv, "scheme,dt_E2_over_eta2,k_over_E2,growth\n");
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: stability_map [--csv FILE | --dda | --power]\n");
    return 2;
  }
  const laws::Scheme schemes[] = {laws::Scheme::lagged, laws::Scheme::implicit,
                                  laws::Scheme::exponential_linear};
  // Map: dt E2/eta2 and k/E2 from 1e-2 to 1e3, 4 points per decade.
  int stable[3] = {0, 0, 0}, total = 0, lagged_as_predicted = 0;
  double worst_stable[3] = {0, 0, 0};
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const double x = std::pow(10.0, -2.0 + 0.25 * i), y = std::pow(10.0, -2.0 + 0.25 * j);
      ++total;
      for (int s = 0; s < 3; ++s) {
        const double g = growth(schemes[s], x, y);
        if (csv)
          std::fprintf(csv, "%s,%.6g,%.6g,%.6g\n", std::string(laws::scheme_name(schemes[s])).c_str(),
                       x, y, std::isfinite(g) ? g : 1e300);
        const bool ok = g <= 1.0 + 1e-12;
        stable[s] += ok;
        if (ok) worst_stable[s] = std::max(worst_stable[s], g);
        if (s == 0 && ok == (y <= 1.0 || x < -std::log(1.0 - 2.0 / (y + 1.0)))) ++lagged_as_predicted;
      }
    }
  std::printf("Map: dt E2/eta2 and k/E2 each from 1e-2 to 1e3 (21 x 21 = %d points), "
              "200 steps of relaxation per point.\n\n",
              total);
  std::printf("| scheme | stable points | largest growth among them |\n|---|---:|---:|\n");
  for (int s = 0; s < 3; ++s)
    std::printf("| %s | %d / %d | %.4f |\n", std::string(laws::scheme_name(schemes[s])).c_str(),
                stable[s], total, worst_stable[s]);
  std::printf("\nLagged: stable exactly where predicted (k <= E2, or dt E2/eta2 < -ln(1 - 2 E2/(k + E2))) "
              "at %d of %d points.\n",
              lagged_as_predicted, total);
  if (csv) std::fclose(csv);
  return 0;
}
