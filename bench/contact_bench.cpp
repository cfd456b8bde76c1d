// Contacts: the running-bond brick wall.
//
// Sample runs:
//   build/bench/contact_bench                      # N = 1e2, 1e3, 1e4 blocks
//   build/bench/contact_bench --max-blocks 100000  # adds N = 1e5
//   build/bench/contact_bench --detect-only --max-blocks 100000  # detection alone
//   build/bench/contact_bench --solver cholmod     # one solver (default automatic:
//                                                  # cholmod below 2 000 blocks, amg above)
//   build/bench/contact_bench --solver amg --tol 1e-8  # iterative stop ||F - K D|| <= tol ||F||
//   build/bench/contact_bench --iterate-tol 0       # the same stop in open-close iterates whose states
//                                                  # still change (default 1e-4; 0: every solve at --tol)
//   build/bench/contact_bench --open-close 20      # open-close iterations before a cut (default 30)
//   build/bench/contact_bench --penalty 10         # contact penalty in units of E (default 40)
//   build/bench/contact_bench --glued              # cohesion and tensile strength so high that every
//                                                  # contact stays locked: one iterate per step, the
//                                                  # linear solver alone
//   build/bench/contact_bench --trace --sizes 32 --steps 5
//                                                  # per iterate: changes by kind and CG iterations
//   build/bench/contact_bench --sizes 32,100x20    # walls to run: N (N x N bricks) or NXxNY
//                                                  # (default 10,32,100,316)
//   build/bench/contact_bench --sizes 20,40 --duration 0.05 --penalty 50 --poisson 0.25
//                                                  # a fixed simulated time (50 ms) instead of a
//                                                  # step count, at the peer's settings (penalty
//                                                  # 50 E, nu 0.25): simulated time, CPU s per
//                                                  # simulated ms, solves per step, cuts
//   build/bench/contact_bench --friction-tolerance 0.1 --force-resolution 1e-2 --max-flips 2
//                                                  # --max-refinements 3: the open-close settings
//                                                  # of contact::ContactSettings (defaults there)
//   build/bench/contact_bench --stick-keeps-force  # ContactSettings::stick_keeps_force
//   build/bench/contact_bench --contact-solver newton --residual-tol 1e-4
//                                                  # the contact solve (Settings::contact_solver)
//                                                  # and its residual tolerance
//
// A wall of NX x NY bricks 0.2 m x 0.1 m in running bond (odd rows start and
// end with a half brick, so the sides are straight) stands on a fixed base
// block; gravity, friction 30 deg on every joint, E = 5 GPa, nu = 0.2 (--poisson),
// density 2600 kg/m^3, dynamic analysis, dt = 1e-3 s, max_displacement_ratio w0 = 1 mm, 50 steps,
// default open-close limit (30) and contact settings. Prints the
// time of contact detection and of a full step (open-close iteration
// included), block-steps per second, the growth exponent of the step time
// between successive sizes, and the largest displacement after 50 steps (the
// wall must stay standing). Asserts nothing.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/contact_solve.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/integrator.hpp"
#include "rheodda/core/solver.hpp"
#include "brick_wall.hpp"  // tests/models

using namespace rheodda;
using core::Vec2;
using Clock = std::chrono::steady_clock;

namespace {

/// The method whose row (core::linear_solvers(), contact_solves(), integrators()) has `word`,
/// as the scene's keys read them; else a message naming the option and the words it takes.
template <class Rows>
auto method_of(const Rows& rows, const std::string& word, const char* option)
    -> std::optional<decltype(rows.front().method)> {
  for (const auto& r : rows)
    if (r.word == word) return r.method;
  std::string words;
  for (const auto& r : rows) words += (words.empty() ? "" : "|") + std::string(r.word);
  std::fprintf(stderr, "contact_bench: unknown %s '%s' (%s)\n", option, word.c_str(), words.c_str());
  return std::nullopt;
}

/// NX x NY running-bond wall on a fixed base (block 0): tests/models/brick_wall.hpp.
core::Model brick_wall(int nx, int ny, double poisson) { return models::running_bond_wall(nx, ny, poisson); }

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// The contact adapter with a trace: per step attempt one line, per open-close
/// iterate the CG iterations of its solve and what the check changed, e.g.
///   step 4 dt 0.001: {68} [c43 o175 s135 l30 r126] {78} [...] ... cut
/// (c closed, o opened, s slipped, l stuck (locked), r friction refinements).
class TracingContacts final : public core::ContactModel {
 public:
  explicit TracingContacts(core::ContactAdapter& inner) : inner_(inner) {}
  const core::Engine* engine = nullptr;  // for the solver's CG count

  void begin_step(std::span<const contact::BlockView> b, const core::StepContext& ctx) override {
    std::printf("step %d dt %.3g:", ctx.step, ctx.dt);
    inner_.begin_step(b, ctx);
  }
  void assemble(std::span<const contact::BlockView> b, contact::SystemSink& sink) override {
    inner_.assemble(b, sink);
  }
  core::ContactCheck check(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    const core::ContactCheck r = inner_.check(b, D);
    const long cg = engine ? engine->solver_stats().pcg_iterations : 0;
    const auto& k = r.changes;
    std::printf(" {%ld} [c%d o%d s%d l%d r%d]", cg - last_cg_, k.closed, k.opened, k.slipped, k.stuck,
                k.refinements);
    last_cg_ = cg;
    return r;
  }
  void end_step(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    std::printf(" ok\n");
    inner_.end_step(b, D);
  }
  void abandon_step() override {
    std::printf(" cut\n");
    inner_.abandon_step();
  }

 private:
  core::ContactAdapter& inner_;
  long last_cg_ = 0;
};

/// "10,32,100x20" -> {10, 10}, {32, 32}, {100, 20} (NX, NY); empty on bad input.
std::vector<std::pair<int, int>> parse_sizes(const char* text) {
  std::vector<std::pair<int, int>> sizes;
  auto number = [](const char*& p) -> long {
    char* end = nullptr;
    const long v = std::strtol(p, &end, 10);
    if (end == p || v < 1 || v > 100000) return -1;
    p = end;
    return v;
  };
  for (const char* p = text; *p;) {
    const long nx = number(p);
    long ny = nx;
    if (nx > 0 && *p == 'x') ny = number(++p);
    if (nx < 1 || ny < 1 || (*p && *p != ',')) return {};
    sizes.emplace_back(static_cast<int>(nx), static_cast<int>(ny));
    if (*p == ',') ++p;
  }
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  long max_blocks = 10000;
  int steps = 50;
  bool detect_only = false;
  double pcg_tol = 0.0;
  double iterate_tol = -1.0;  // < 0: the engine's default (Settings::solver_iterate_tolerance)
  std::string solver = "automatic";
  int open_close = 0;
  double penalty = 40.0;  // [E]
  bool glued = false, trace = false;
  double poisson = 0.2, duration = 0.0;
  bool stick_keeps_force = false;
  std::string contact_solver = "open-close";
  double residual_tol = -1.0;  // < 0: the engine's default (Settings::contact_residual_tolerance)
  std::string integrator = "implicit";
  int threads = 1;
  double safety = 0.0;  // 0: the engine's default (Settings::explicit_safety)
  double damping = -1.0;  // < 0: the engine's default (Settings::explicit_damping)
  contact::ContactSettings tuned;  // contact iteration settings given on the command line
  bool tuned_any = false;
  std::vector<std::pair<int, int>> sizes{{10, 10}, {32, 32}, {100, 100}, {316, 316}};
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--max-blocks") && k + 1 < argc) max_blocks = std::atol(argv[++k]);
    else if (!std::strcmp(argv[k], "--steps") && k + 1 < argc) steps = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--detect-only")) detect_only = true;
    else if (!std::strcmp(argv[k], "--solver") && k + 1 < argc) solver = argv[++k];
    else if (!std::strcmp(argv[k], "--tol") && k + 1 < argc) pcg_tol = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--iterate-tol") && k + 1 < argc) iterate_tol = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--open-close") && k + 1 < argc) open_close = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--penalty") && k + 1 < argc) penalty = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--glued")) glued = true;
    else if (!std::strcmp(argv[k], "--trace")) trace = true;
    else if (!std::strcmp(argv[k], "--poisson") && k + 1 < argc) poisson = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--duration") && k + 1 < argc) duration = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--friction-tolerance") && k + 1 < argc)
      tuned.friction_tolerance = std::atof(argv[++k]), tuned_any = true;
    else if (!std::strcmp(argv[k], "--force-resolution") && k + 1 < argc)
      tuned.force_resolution = std::atof(argv[++k]), tuned_any = true;
    else if (!std::strcmp(argv[k], "--max-flips") && k + 1 < argc)
      tuned.max_flips = std::atoi(argv[++k]), tuned_any = true;
    else if (!std::strcmp(argv[k], "--max-refinements") && k + 1 < argc)
      tuned.max_refinements = std::atoi(argv[++k]), tuned_any = true;
    else if (!std::strcmp(argv[k], "--stick-keeps-force")) stick_keeps_force = true;
    else if (!std::strcmp(argv[k], "--contact-solver") && k + 1 < argc) contact_solver = argv[++k];
    else if (!std::strcmp(argv[k], "--residual-tol") && k + 1 < argc) residual_tol = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--integrator") && k + 1 < argc) integrator = argv[++k];
    else if (!std::strcmp(argv[k], "--threads") && k + 1 < argc) threads = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--safety") && k + 1 < argc) safety = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--damping") && k + 1 < argc) damping = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--sizes") && k + 1 < argc && !(sizes = parse_sizes(argv[++k])).empty()) {}
    else {
      std::fprintf(stderr,
                   "usage: contact_bench [--max-blocks N] [--steps S] [--detect-only] "
                   "[--solver automatic|cholmod|pcg|amg] [--tol T] [--open-close N] [--penalty F] "
                   "[--glued] [--trace] [--sizes N|NXxNY,...] [--poisson NU] [--duration T] "
                   "[--friction-tolerance F] [--force-resolution F] [--max-flips N] [--max-refinements N] "
                   "[--stick-keeps-force] [--contact-solver open-close|newton] [--residual-tol R] "
                   "[--integrator implicit|explicit] [--threads N] [--safety S] [--damping Z]\n");
      return 2;
    }
  }
  if (!(penalty > 0.0)) {
    std::fprintf(stderr, "contact_bench: --penalty must be > 0 (in units of E)\n");
    return 2;
  }
  const auto solver_kind = method_of(core::linear_solvers(), solver, "--solver");
  const auto contact_solve = method_of(core::contact_solves(), contact_solver, "--contact-solver");
  const auto integrator_method = method_of(core::integrators(), integrator, "--integrator");
  if (!solver_kind || !contact_solve || !integrator_method) return 2;
  contact::JointSet joint;
  joint.name = "mortar";
  joint.friction_angle = 30.0;
  if (glued) joint.cohesion = joint.tensile_strength = 1e12;  // [Pa]: nothing slides or opens

  std::printf("# running-bond brick wall, %d steps, dt = 1e-3 s, g2 w0 = 1 mm (one core), solver %s",
              steps, solver.c_str());
  if (pcg_tol > 0.0) std::printf(", tol %g", pcg_tol);
  if (iterate_tol >= 0.0) std::printf(", iterate tol %g", iterate_tol);
  std::printf(", penalty %g E%s\n", penalty, glued ? ", glued joints" : "");
  std::printf("%8s %6s %6s %8s %10s %10s %10s %10s %14s %8s %6s %5s %8s %8s %12s\n", "blocks", "NX",
              "NY", "contacts", "detect_ms", "step_ms", "solve_ms", "assemb_ms", "block-steps/s",
              "exponent", "iters", "cuts", "analyses", "cg/solve", "max_disp_m");
  double prev_n = 0.0, prev_step = 0.0;
  for (const auto& [nx, ny] : sizes) {
    core::Model model = brick_wall(nx, ny, poisson);
    model.settings.solver = *solver_kind;
    if (pcg_tol > 0.0) model.settings.solver_tolerance = pcg_tol;
    if (iterate_tol >= 0.0) model.settings.solver_iterate_tolerance = iterate_tol;
    if (open_close > 0) model.settings.open_close_limit = open_close;
    model.settings.contact_solver = *contact_solve;
    if (residual_tol > 0.0) model.settings.contact_residual_tolerance = residual_tol;
    model.settings.integrator = *integrator_method;
    model.settings.threads = threads;
    if (safety > 0.0) model.settings.explicit_safety = safety;
    if (damping >= 0.0) model.settings.explicit_damping = damping;
    const double n = static_cast<double>(model.blocks.size() - 1);
    if (n > 1.2 * static_cast<double>(max_blocks)) break;
    contact::ContactSettings cs = core::contact_settings_for(model, penalty);
    if (tuned_any) {
      cs.friction_tolerance = tuned.friction_tolerance;
      cs.force_resolution = tuned.force_resolution;
      cs.max_flips = tuned.max_flips;
      cs.max_refinements = tuned.max_refinements;
    }
    cs.stick_keeps_force = stick_keeps_force;
    contact::ContactSystem contacts({joint}, cs);
    core::ContactAdapter adapter(contacts);
    TracingContacts tracing(adapter);
    core::Engine engine(model, trace ? static_cast<core::ContactModel&>(tracing)
                                     : static_cast<core::ContactModel&>(adapter));
    tracing.engine = &engine;

    // Detection alone, on the initial geometry (begin_step then abandon_step).
    const int reps = n < 5000 ? 20 : 3;
    const auto d0 = Clock::now();
    for (int r = 0; r < reps; ++r) {
      contacts.begin_step(engine.views(), {.max_displacement = engine.allowed_displacement()});
      contacts.abandon_step();
    }
    const double detect = seconds(d0, Clock::now()) / reps;
    if (detect_only) {
      const auto& st = contacts.stats();
      std::printf("%8.0f %6d %6d %8d %10.3f   (candidate pairs %d, search distance %.3g m)\n", n, nx,
                  ny, st.contacts, 1e3 * detect, st.candidate_pairs, st.search_distance);
      std::fflush(stdout);
      continue;
    }

    std::vector<Vec2> c0;
    for (int b = 0; b < engine.block_count(); ++b) c0.push_back(engine.centroid(b));
    const auto s0 = Clock::now();
    const std::clock_t cpu0 = std::clock();
    if (duration > 0.0) {
      // A fixed simulated time: as many steps as the step control takes, up to
      // 20x the nominal count (a wall that cuts dt to nothing stops there).
      const int limit = 20 * static_cast<int>(std::ceil(duration / model.settings.dt));
      while (engine.time() < duration * (1.0 - 1e-12) && engine.step_count() < limit)
        engine.run_until(std::min(duration, engine.time() + model.settings.dt));
      steps = engine.step_count();
    } else {
      engine.run(steps);
    }
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
    const double step_time = seconds(s0, Clock::now()) / steps;
    double max_disp = 0.0, iters = 0.0, solve = 0.0, assembly = 0.0;
    int cuts = 0;
    double sum_disp = 0.0;  // with max_disp at all digits: a check of bit-identical runs
    for (int b = 1; b < engine.block_count(); ++b) {
      const double d = engine.point_displacement(b, c0[b]).norm();
      max_disp = std::max(max_disp, d);
      sum_disp += d;
    }
    for (const auto& r : engine.reports()) {
      iters += r.iterations;
      cuts += r.cuts;
      solve += r.solve_seconds;
      assembly += r.assembly_seconds;
    }
    const double exponent =
        prev_n > 0.0 ? std::log(step_time / prev_step) / std::log(n / prev_n) : std::nan("");
    const auto& ss = engine.solver_stats();
    const double cg_per_solve =
        static_cast<double>(ss.pcg_iterations) / static_cast<double>(std::max(1L, ss.solves));
    std::printf("%8.0f %6d %6d %8zu %10.3f %10.3f %10.3f %10.3f %14.3g %8.2f %6.2f %5d %8ld %8.1f %12.3g\n",
                n, nx, ny, contacts.contacts().size(), 1e3 * detect, 1e3 * step_time,
                1e3 * solve / steps, 1e3 * assembly / steps, n / step_time, exponent,
                iters / steps, cuts, ss.analyses, cg_per_solve, max_disp);
    core::ContactChanges changes;
    for (const auto& r : engine.reports()) changes += r.changes;
    std::printf("#   simulated %.4g s in %d steps, %.3f CPU s: %.4g CPU s per simulated ms, %.2f solves "
                "per step, %d cuts\n",
                engine.time(), steps, cpu, cpu / (1e3 * engine.time()),
                static_cast<double>(ss.solves) / steps, cuts);
    std::printf("#   changes per step (all iterates and attempts): closed %.1f opened %.1f slipped %.1f "
                "stuck %.1f refinements %.1f\n",
                double(changes.closed) / steps, double(changes.opened) / steps,
                double(changes.slipped) / steps, double(changes.stuck) / steps,
                double(changes.refinements) / steps);
    long cycles = 0;
    double contact_cycles = 0.0;
    for (const auto& r : engine.reports()) cycles += r.cycles;
    if (cycles > 0) {
      // Contact updates: every contact of the step at each of its cycles (cycles + 1 force
      // evaluations per step; the contacts of the last step stand for the others).
      contact_cycles = static_cast<double>(contacts.contacts().size()) * static_cast<double>(cycles + steps);
      std::printf("#   explicit: %.1f cycles per step (cycle %.3g s), %d threads: %.1f ns wall per contact "
                  "update, %.1f ns CPU\n",
                  static_cast<double>(cycles) / steps, engine.reports().back().cycle_dt, threads,
                  1e9 * step_time * steps / contact_cycles, 1e9 * cpu / contact_cycles);
      std::printf("#   stable cycle set by block %d\n", engine.reports().back().stable_block);
    }
    std::printf("#   displacements at all digits: largest %.17g m, sum over the blocks %.17g m\n", max_disp,
                sum_disp);
    std::printf("#   wall %.3f s: %.4g wall s per simulated ms\n", step_time * steps,
                step_time * steps / (1e3 * engine.time()));
    std::fflush(stdout);
    prev_n = n;
    prev_step = step_time;
  }
  return 0;
}
