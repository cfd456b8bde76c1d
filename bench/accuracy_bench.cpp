// Speed-accuracy trade of the creep schemes: error against the closed form vs
// wall time, per scheme and time step (docs/notes/step-controls.md).
//
// Cases (units MPa, mm, h; Burgers joints of the seed's Table 1, all four rows):
//   creep      the seed's two-block shear creep test (Section 4) run by the DDA
//              engine: constant tau from t = 0, 0-200 h; reference eqs. 20-21.
//   staged     the same DDA model under a staged shear load with unloading:
//              tau from 0 h, ramp to 2 tau over 80-85.5 h, ramp to 0 over
//              140-143.3 h, 0-200 h; reference the Boltzmann superposition of
//              eqs. 20-21 (staged_exact). Fixed steps run as given (they need
//              not end on the ramp ends; adaptive steps do).
//   relaxation the law in series with its spring E1 (laws::solve_series_force,
//              no DDA: the two-block scene cannot hold a displacement), displacement
//              1e-3 mm held from t = 0, 0-200 h; reference G(t) (laws::exact_force).
//   adaptive   the staged DDA case with Settings::creep_tolerance instead of a
//              fixed step (default scheme), for several tolerances.
// Error: largest |x - x_exact| over all steps and rows divided by the largest
// |x_exact| of the row (relative to the peak). Wall time: sum over the four rows.
//
// Usage: accuracy_bench [--csv FILE]   (prints a Markdown table; FILE gets
//        case,scheme,dt,tolerance,steps,wall_s,error for scripts/accuracy-report.sh)
//        accuracy_bench --toppling SCENE [T_END]   fixed steps vs creep_tolerance and
//        step_tolerance (step doubling) on a
//        scene (examples/goodman-toppling-creep.yaml; T_END in the scene's time unit,
//        default 100), from a settled state shared by all runs (toppling() below)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/laws/history.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/seed_table1.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/loader.hpp"
#include "two_block.hpp"  // tests/models

using namespace rheodda;

namespace {

using Row = laws::SeedTable1Row;
constexpr const auto& kTable1 = laws::kSeedTable1;
constexpr double kEnd = 200.0;               // [h]
constexpr double kStage2 = 80.0, kStage3 = 140.0;  // ramp starts [h]
constexpr double kRamp2 = 85.5, kRamp3 = 143.3;    // ramp ends [h]
constexpr double kWidth = 100.0;             // block side [mm]

std::shared_ptr<const laws::ContactRheology> burgers(const Row& r) {
  return laws::LawRegistry::builtin().create(
      "burgers", {{"E1", r.E1}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}});
}

/// Joint displacement under the staged shear stress with ramps: tau from 0 h,
/// ramp to 2 tau over 80-85.5 h, ramp to 0 over 140-143.3 h [mm]. Boltzmann
/// superposition of the Burgers creep compliance (the seed's eqs. 20-21)
/// J(u) = 1/E1 + (1 - exp(-E2 u/eta2))/E2 + u/eta1: the step tau J(t) plus, per
/// ramp of slope s from a to b, s (I(t - a) - I(t - b)), I(u) = int_0^max(u,0) J.
double staged_exact(double tau, double E1, double E2, double eta1, double eta2, double t) {
  auto J = [&](double u) { return 1 / E1 + (1 - std::exp(-E2 * u / eta2)) / E2 + u / eta1; };
  auto I = [&](double u) {
    u = std::max(u, 0.0);
    return u / E1 + u / E2 - eta2 / (E2 * E2) * (1 - std::exp(-E2 * u / eta2)) + u * u / (2 * eta1);
  };
  const double s = tau / (kRamp2 - kStage2), s3 = -2 * tau / (kRamp3 - kStage3);
  return tau * J(t) + s * (I(t - kStage2) - I(t - kRamp2)) + s3 * (I(t - kStage3) - I(t - kRamp3));
}

/// Block A (100 x 100 mm) on block B (fixed); normal load sigma w and shear load
/// tau(t) w on A at the joint line (bench/shear_creep_table1.cpp). `staged`:
/// tau, ramp to 2 tau over kStage2-kRamp2, ramp to 0 over kStage3-kRamp3.
core::Model scene(const Row& r, double dt, bool staged, double tolerance) {
  const double w = kWidth;
  core::Model m = models::two_block_model(w, dt);  // tests/models/two_block.hpp
  m.settings.creep_tolerance = tolerance;
  m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {0.0, -r.sigma * w}}}});
  std::vector<core::LoadSample> shear{{0.0, {r.tau * w, 0.0}}};
  if (staged) {
    shear = {{0.0, {r.tau * w, 0.0}},          {kStage2, {r.tau * w, 0.0}},
             {kRamp2, {2 * r.tau * w, 0.0}}, {kStage3, {2 * r.tau * w, 0.0}},
             {kRamp3, {0.0, 0.0}}};
  }
  m.point_loads.push_back({1, {0.5 * w, 0.0}, shear});
  return m;
}

using models::joint_shear;  // mean over A's base contacts [mm]

struct Result {
  long steps = 0;
  double wall = 0.0;   ///< [s]
  double error = 0.0;  ///< relative to the peak of the reference [-]
  bool failed = false;
};

/// One DDA run of the two-block test over 0-kEnd.
Result run_dda(const Row& r, double dt, bool staged, std::optional<laws::Scheme> scheme,
               double tolerance) {
  const auto law = burgers(r);
  const core::Model m = scene(r, dt, staged, tolerance);
  models::SeedJointRun run(m, law, scheme);  // tests/models/two_block.hpp
  auto& [contacts, adapter, engine] = run;
  double worst = 0.0, peak = 0.0;
  engine.add_observer([&](const core::Engine& e, const core::StepReport&) {
    const double exact = staged ? staged_exact(r.tau, r.E1, r.E2, r.eta1, r.eta2, e.time())
                                : law->displacement_closed_form(r.tau, e.time());
    peak = std::max(peak, std::abs(exact));
    worst = std::max(worst, std::abs(joint_shear(contacts) - exact));
  });
  Result res;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    engine.run_until(kEnd);
  } catch (const std::exception&) {
    res.failed = true;
  }
  res.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.steps = engine.step_count();
  res.error = res.failed || !std::isfinite(worst) ? INFINITY : worst / peak;
  return res;
}

/// Relaxation of the law in series with its spring E1, displacement held from t = 0.
Result run_relaxation(const Row& r, double dt, laws::Scheme scheme) {
  const auto law = burgers(r);
  const double delta = 1e-3;  // [mm]
  const laws::StagedHistory held({{0.0, delta}});
  Result res;
  const auto t0 = std::chrono::steady_clock::now();
  // The first step starts from rest (load applied at t = 0+): implicit constants,
  // as the contact layer does for a contact that closes (docs/reference/rheology-in-dda.md).
  const laws::StepConstants first = law->step_constants(dt, laws::Scheme::implicit);
  const laws::StepConstants k = law->step_constants(dt, scheme);
  laws::RheologyState q, next;
  double force = 0.0, worst = 0.0;
  const long n = std::lround(kEnd / dt);
  std::vector<double> forces(n);
  for (long i = 0; i < n; ++i) {
    const laws::StepConstants& ks = i == 0 ? first : k;
    const double f = laws::solve_series_force(*law, ks, q, r.E1, delta, force);
    law->advance(ks, q, force, f, next);
    q = next;
    force = f;
    forces[i] = f;
  }
  res.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (long i = 0; i < n; ++i)
    worst = std::max(worst, std::abs(forces[i] - *laws::exact_force(*law, held, static_cast<double>(i + 1) * dt)));
  res.steps = n;
  res.error = std::isfinite(worst) ? worst / (r.E1 * delta) : INFINITY;
  return res;
}

std::string fmt_error(double e) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", e);
  return buf;
}

// ---- The toppling model (docs/notes/step-controls.md, "The toppling model") ----
// Every run starts from one settled state: the scene's settling stage
// (analysis.settle), or, for a scene without one, fixed steps of
// kSettleStep up to kSettleEnd with max_displacement_ratio =
// kSettleMaxDisplacementRatio: the columns' settling under gravity applied at
// once (a quasi-static collapse whose path, in static DDA, depends on the step:
// taken once, in small steps, it is the same for all runs). From there each run
// creeps to T_END with its own fixed step or creep_tolerance, with the scene's
// max_displacement_ratio; error = largest |u - u_ref| of the measurement points
// at T_END / largest u_ref, u_ref from a fixed step kFine.
constexpr double kSettleStep = 1e-4, kSettleEnd = 0.01;  // [d]
constexpr double kSettleMaxDisplacementRatio = 0.0005;  // [-] (docs/guide/toppling-study.md)
constexpr double kFine = 1.0 / 1024;  // reference step [d]; a run at 2 kFine checks it

struct Settled {
  core::EngineState engine;
  contact::ContactSystem contacts;
  long steps = 0;
  double step = 0.0, end = 0.0;          ///< the settling's steps and end [d]
  double max_displacement_ratio = 0.0;  ///< the settling's max_displacement_ratio [-]
};

/// The scene's own settling stage (`analysis.settle`) when it has one, else the
/// constants above.
Settled settle(const scene::BuiltScene& built) {
  core::Model m = built.model;
  m.settings.creep_tolerance = 0.0;
  m.settings.step_tolerance = 0.0;
  const bool own = m.settings.settle.until > 0.0;
  const double end = own ? m.settings.settle.until : kSettleEnd;
  if (!own) {
    m.settings.max_displacement_ratio = kSettleMaxDisplacementRatio;
    m.settings.dt = kSettleStep;
  }
  contact::ContactSystem contacts(built.joint_sets, built.contact_settings);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(m, adapter);
  engine.run_until(end);
  return Settled{engine.save(), contacts, engine.step_count(), own ? m.settings.settle.dt : kSettleStep, end,
                 own ? m.settings.settle.max_displacement_ratio : kSettleMaxDisplacementRatio};
}

struct CreepRun {
  Result r;
  long cuts = 0, rejections = 0, extrapolated = 0;
  std::vector<double> u;  ///< final |u| of every measurement point [m]
};

/// How a creep run steps: a fixed dt (both tolerances 0), adaptive creep
/// stepping (creep_tolerance) or step doubling (step_tolerance) from a first step dt.
struct Control {
  double dt = 1.0;              ///< [d]
  double creep_tolerance = 0.0; ///< [m]
  double step_tolerance = 0.0;  ///< [m]
  bool restart_on_contact_change = false;
  bool extrapolation = true;    ///< under step_tolerance
};

/// Creep from the settled state to t_end [d]. Wall time: the least of `repeats` runs.
CreepRun run_creep(const scene::BuiltScene& built, const Settled& from, const Control& ctl,
                   double t_end, int repeats = 3) {
  CreepRun out;
  out.r.wall = INFINITY;
  for (int rep = 0; rep < repeats; ++rep) {
    core::Model m = built.model;
    m.settings.dt = ctl.dt;
    m.settings.creep_tolerance = ctl.creep_tolerance;
    m.settings.creep_restart_on_contact_change = ctl.restart_on_contact_change;
    m.settings.step_tolerance = ctl.step_tolerance;
    m.settings.step_extrapolation = ctl.extrapolation;
    contact::ContactSystem contacts = from.contacts;
    core::ContactAdapter adapter(contacts);
    core::Engine engine(m, adapter);
    core::EngineState st = from.engine;
    st.next_dt = ctl.dt;
    engine.restore(st);
    const int first = engine.step_count();
    bool failed = false;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      engine.run_until(t_end);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "dt %g tolerances %g %g: %s\n", ctl.dt, ctl.creep_tolerance,
                   ctl.step_tolerance, e.what());
      failed = true;
    }
    out.r.wall = std::min(
        out.r.wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    out.r.failed = failed;
    out.r.steps = engine.step_count() - first;
    out.cuts = out.rejections = out.extrapolated = 0;
    for (const auto& r : engine.reports())
      out.cuts += r.cuts, out.rejections += r.rejections, out.extrapolated += r.extrapolated;
    out.u.clear();
    for (const auto& samples : engine.measurements())
      out.u.push_back(samples.back().displacement.norm());
  }
  return out;
}

/// Fixed steps vs adaptive stepping on the toppling scene, each adaptive run
/// against the best (largest) fixed step that is at least as accurate.
/// Reference: the Richardson extrapolation 2 u(kFine) - u(2 kFine) of the two
/// finest fixed runs (the fixed steps converge at first order, so this removes
/// their leading error; |u(kFine) - u(2 kFine)| bounds what is left to well
/// below it). Fixed steps are also run with the exponential-linear scheme:
/// equal errors show that the error is not the creep integration's
/// (docs/notes/step-controls.md).
int toppling(const std::string& path, double t_end) {
  const scene::BuiltScene built = scene::build_scene(scene::load_scene(path));
  const Settled settled = settle(built);
  const CreepRun fine = run_creep(built, settled, {kFine}, t_end, 1);
  const CreepRun fine2 = run_creep(built, settled, {2 * kFine}, t_end, 1);
  std::vector<double> ref_u(fine.u.size());
  double peak = 0.0, fine_gap = 0.0;
  for (std::size_t k = 0; k < ref_u.size(); ++k) {
    ref_u[k] = 2.0 * fine.u[k] - fine2.u[k];
    peak = std::max(peak, ref_u[k]);
    fine_gap = std::max(fine_gap, std::abs(fine.u[k] - fine2.u[k]));
  }
  auto error = [&](const CreepRun& c) {
    if (c.r.failed) return std::numeric_limits<double>::infinity();
    double e = 0.0;
    for (std::size_t k = 0; k < c.u.size(); ++k) e = std::max(e, std::abs(c.u[k] - ref_u[k]));
    return e / peak;
  };
  std::printf("`%s`, scheme %s, g2 %g; settled by %ld steps of %g d to %g d (g2 %g); creep to "
              "%g d. Reference: 2 u(1/%g d) - u(1/%g d) (Richardson; %ld and %ld fixed steps; "
              "the two differ by %s), u =",
              path.c_str(),
              built.contact_settings.scheme
                  ? std::string(laws::scheme_name(*built.contact_settings.scheme)).c_str()
                  : "default",
              built.model.settings.max_displacement_ratio, settled.steps, settled.step, settled.end,
              settled.max_displacement_ratio, t_end,
              1.0 / kFine, 0.5 / kFine, fine.r.steps, fine2.r.steps,
              fmt_error(fine_gap / peak).c_str());
  for (double v : ref_u) std::printf(" %.6f", v);
  std::printf(" m. Error: largest |u - u_ref| at %g d / %.3g m (fixed 1/%g d: %s). "
              "Wall: least of 3 runs.\n\n",
              t_end, peak, 1.0 / kFine, fmt_error(error(fine)).c_str());
  std::printf("| run | steps | cuts | redone | error | wall [ms] |\n|---|---:|---:|---:|---:|---:|\n");
  struct Fixed {
    double dt;
    CreepRun c;
  };
  std::vector<Fixed> fixed;
  for (double dt : {8.0, 4.0, 2.0, 1.0, 0.5, 0.25, 0.125, 0.0625, 1.0 / 32, 1.0 / 64, 1.0 / 128,
                    1.0 / 256}) {
    fixed.push_back({dt, run_creep(built, settled, {dt}, t_end)});
    const CreepRun& c = fixed.back().c;
    std::printf("| fixed dt = %g d | %ld | %ld | - | %s | %.1f |\n", dt, c.r.steps, c.cuts,
                fmt_error(error(c)).c_str(), 1e3 * c.r.wall);
  }
  // The same fixed steps with the second-order scheme (own settled state: the
  // settling creeps 0.01 d with that scheme too).
  scene::BuiltScene el = built;
  el.contact_settings.scheme = laws::Scheme::exponential_linear;
  const Settled settled_el = settle(el);
  for (double dt : {4.0, 1.0, 0.25, 0.0625}) {
    const CreepRun c = run_creep(el, settled_el, {dt}, t_end);
    std::printf("| fixed dt = %g d, exponential-linear | %ld | %ld | - | %s | %.1f |\n", dt, c.r.steps,
                c.cuts, fmt_error(error(c)).c_str(), 1e3 * c.r.wall);
  }
  // An adaptive run against the largest fixed step at least as accurate.
  auto compare = [&](const CreepRun& c) {
    const double e = error(c);
    const Fixed* best = nullptr;
    for (const Fixed& f : fixed)
      if (error(f.c) <= e) {
        best = &f;
        break;
      }
    char cmp[160];
    if (best)
      std::snprintf(cmp, sizeof cmp, "dt = %g d (%s) | %ld | %.1f | %.2f", best->dt,
                    fmt_error(error(best->c)).c_str(), best->c.r.steps, 1e3 * best->c.r.wall,
                    c.r.wall / best->c.r.wall);
    else
      std::snprintf(cmp, sizeof cmp, "none down to 1/256 d | - | - | -");
    return std::string(cmp);
  };
  std::printf("\n| creep_tolerance [m] | restart on contact change | steps | cuts | redone | error "
              "| wall [ms] | best fixed step as accurate | its steps | its wall [ms] | wall "
              "ratio |\n|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---:|\n");
  for (bool restart : {false, true})
    for (double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      Control ctl{kFine, tol};
      ctl.restart_on_contact_change = restart;
      const CreepRun c = run_creep(built, settled, ctl, t_end);
      std::printf("| %g | %s | %ld | %ld | %ld | %s | %.1f | %s |\n", tol, restart ? "yes" : "no",
                  c.r.steps, c.cuts, c.rejections, fmt_error(error(c)).c_str(), 1e3 * c.r.wall,
                  compare(c).c_str());
    }
  // Step doubling (Settings::step_tolerance): with local extrapolation (the
  // default) and without it.
  std::printf("\n| step_tolerance [m] | extrapolation | steps | extrapolated | cuts | redone | error "
              "| wall [ms] | best fixed step as accurate | its steps | its wall [ms] | wall "
              "ratio |\n|---:|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|\n");
  for (bool extrapolation : {true, false})
    for (double tol : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7}) {
      Control ctl{kFine};
      ctl.step_tolerance = tol;
      ctl.extrapolation = extrapolation;
      const CreepRun c = run_creep(built, settled, ctl, t_end);
      std::printf("| %g | %s | %ld | %ld | %ld | %ld | %s | %.1f | %s |\n", tol,
                  extrapolation ? "on" : "off", c.r.steps, c.extrapolated, c.cuts, c.rejections,
                  fmt_error(error(c)).c_str(), 1e3 * c.r.wall, compare(c).c_str());
    }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress of long runs shows at once
  FILE* csv = nullptr;
  if (argc >= 3 && std::string(argv[1]) == "--toppling")
    return toppling(argv[2], argc >= 4 ? std::stod(argv[3]) : 100.0);
  if (argc == 3 && std::string(argv[1]) == "--csv") {
    csv = std::fopen(argv[2], "w");
    if (!csv) {
      std::fprintf(stderr, "accuracy_bench: cannot write %s\n", argv[2]);
      return 2;
    }
    std::fprintf(csv, "case,scheme,dt,tolerance,steps,wall_s,error\n");
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: accuracy_bench [--csv FILE]\n");
    return 2;
  }
  const double dts[] = {0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20};  // [h]
  const std::optional<laws::Scheme> schemes[] = {laws::Scheme::lagged, laws::Scheme::implicit,
                                                 laws::Scheme::exponential_linear, std::nullopt};
  auto name = [](const std::optional<laws::Scheme>& s) {
    return s ? std::string(laws::scheme_name(*s)) : std::string("default");
  };
  auto emit = [&](const char* cs, const std::string& scheme, double dt, double tol,
                  const Result& r) {
    if (csv)
      std::fprintf(csv, "%s,%s,%g,%g,%ld,%.6g,%.6g\n", cs, scheme.c_str(), dt, tol, r.steps, r.wall,
                   r.error);
  };
  auto cell = [](const Result& r) {
    char buf[64];
    if (r.failed || !std::isfinite(r.error))
      std::snprintf(buf, sizeof buf, "diverged");
    else
      std::snprintf(buf, sizeof buf, "%.1e", r.error);
    return std::string(buf);
  };
  for (const char* cs : {"creep", "staged", "relaxation"}) {
    std::printf("\n**%s** (Table 1 rows 1-4, 0-200 h; error relative to the peak, worst row; "
                "wall time summed over the rows, default scheme)\n\n",
                cs);
    std::printf("| dt [h] | steps | lagged | implicit | exponential-linear | default | wall [ms] |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
    for (double dt : dts) {
      std::string cells[4];
      double wall_default = 0.0;
      long steps = 0;
      for (int k = 0; k < 4; ++k) {
        Result total;
        for (const Row& r : kTable1) {
          Result one;
          if (std::string(cs) == "relaxation")
            one = run_relaxation(r, dt, schemes[k] ? *schemes[k] : laws::Scheme::implicit);
          else
            one = run_dda(r, dt, std::string(cs) == "staged", schemes[k], 0.0);
          total.steps += one.steps;
          total.wall += one.wall;
          total.failed = total.failed || one.failed;
          total.error = std::max(total.error, one.error);
        }
        if (std::string(cs) == "relaxation" && !schemes[k]) {
          cells[k] = "-";  // the law-alone integrator has no automatic scheme
          continue;
        }
        emit(cs, name(schemes[k]), dt, 0.0, total);
        cells[k] = cell(total);
        if (k == 3 || (std::string(cs) == "relaxation" && k == 2)) {
          wall_default = total.wall;
          steps = total.steps / 4;
        }
      }
      std::printf("| %g | %ld | %s | %s | %s | %s | %.1f |\n", dt, steps, cells[0].c_str(),
                  cells[1].c_str(), cells[2].c_str(), cells[3].c_str(), 1e3 * wall_default);
    }
  }
  std::printf("\n**adaptive** (staged case, default scheme, first step 0.01 h, "
              "settings.creep_tolerance)\n\n");
  std::printf("| creep_tolerance [mm] | steps (mean per row) | error | wall [ms] |\n");
  std::printf("|---:|---:|---:|---:|\n");
  for (double tol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
    Result total;
    for (const Row& r : kTable1) {
      const Result one = run_dda(r, 0.01, true, std::nullopt, tol);
      total.steps += one.steps;
      total.wall += one.wall;
      total.failed = total.failed || one.failed;
      total.error = std::max(total.error, one.error);
    }
    emit("adaptive", "default", 0.01, tol, total);
    std::printf("| %g | %ld | %s | %.1f |\n", tol, total.steps / 4, cell(total).c_str(),
                1e3 * total.wall);
  }
  if (csv) std::fclose(csv);
  return 0;
}
