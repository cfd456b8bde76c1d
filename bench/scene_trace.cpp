// The open-close iteration of a scene, step by step: what each iterate changed
// and, on request, every contact's state and forces after each iterate.
//
// Sample runs:
//   build/bench/scene_trace examples/sliding-block.yaml --steps 20
//   build/bench/scene_trace scene.yaml --from 40 --to 45 --contacts --block 1
//       # steps 40-45: the spring energy contacts start each with beyond what they
//       # stored (by cause, and the largest contact's id), each iterate's changes,
//       # then per contact: id, vertex block/vertex, edge block/edge, state, N,
//       # shear force, penetration, length, tributary length, locking point (its
//       # ratio along the edge); --block B adds block B's vertices at each step's start
//   build/bench/scene_trace scene.yaml --dt 1e-4 --duration 0.5 --summary
//       # only the totals: steps, cuts, solves per step, changes by kind
//   build/bench/scene_trace scene.yaml --restore saved.state --steps 2 --contacts
//       # from a state rheodda.Simulation.save wrote for this scene file (the
//       # Python API steps to where a run goes wrong; the trace goes on from there),
//       # or from a run's checkpoint (OUTDIR/checkpoint-K.state)
//   build/bench/scene_trace variant.yaml --restore OUT/checkpoint-0.state --state-scene scene.yaml --cycles
//       # the same, the state written for scene.yaml, traced on a variant of it whose
//       # settings differ (its integrator, its step controls); the blocks must be the same.
//       # --cycles: per accepted step its cycles, largest displacement, kinetic energy
//       # (whether within a dynamic stage) and, for a step in cycles, the fastest block
//   build/bench/scene_trace scene.yaml --duration 1e-4 --diagnose
//       # why attempts were cut, by class (docs/notes/rock-mass-steps.md): iterates
//       # that still changed states (and of their changes the 2-cycles, at corners),
//       # singular solves, attempts that settled but were redone (motion beyond the
//       # step limit, a mechanism, a wider contact search); and the spring energy
//       # contacts started steps with beyond what they stored, by cause
//
// Runs the scene as `rheodda run` does (same model, joint sets and contact
// settings) without writing outputs. A diagnostic tool: it asserts nothing.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/saved_state.hpp"

using namespace rheodda;

namespace {

class Tracer final : public core::ContactModel {
 public:
  Tracer(core::ContactAdapter& inner, contact::ContactSystem& sys) : inner_(inner), sys_(sys) {}
  int from = 0, to = 1 << 30;
  std::vector<int> shown_blocks;  ///< --block B: its vertices at each traced step's start
  bool contacts = false, quiet = false;

  bool on() const { return !quiet && step_ >= from && step_ <= to; }
  /// Cut (or redone) attempts by why (--diagnose).
  struct Diagnosis {
    int cycling = 0;       ///< the last iterate's changes were mostly 2-cycles
    int unsettled = 0;     ///< the last iterate still changed states, mostly not undoing
    int singular = 0;      ///< a solve found the matrix not positive definite
    int redone = 0;        ///< the iteration settled, the step was redone all the same
    long cycled = 0, cycled_corners = 0, changes = 0;  ///< over the last iterates of cut attempts
    contact::DetectionStats::Restart restart_new, restart_edge, restart_kind, restart_same;  ///< accepted steps
  } diagnosis;
  void begin_step(std::span<const contact::BlockView> b, const core::StepContext& ctx) override {
    step_ = ctx.step;
    checked_ = false;
    inner_.begin_step(b, ctx);
    if (on()) {
      std::printf("step %d t %.6g dt %.3g (search distance %.3g):", ctx.step, ctx.time, ctx.dt,
                  sys_.stats().search_distance);
      for (const int sb : shown_blocks)
        if (sb >= 0 && sb < static_cast<int>(b.size())) {
          std::printf(" block %d:", sb);
          for (const auto& v : b[sb].vertices) std::printf(" (%.9g, %.9g)", v.x(), v.y());
        }
      // The spring energy contacts start with beyond what they stored, by cause, and its
      // largest contact (docs/notes/rock-mass-steps.md).
      const contact::DetectionStats& st = sys_.stats();
      for (const auto& [name, r] : {std::pair{"new", st.restart_new}, std::pair{"edge", st.restart_edge},
                                    std::pair{"kind", st.restart_kind}, std::pair{"same", st.restart_same}})
        if (r.contacts > 0)
          std::printf(" restart %s %d / %.3g (largest #%llu %.3g)", name, r.contacts, r.energy,
                      static_cast<unsigned long long>(r.largest_id), r.largest);
    }
  }
  void assemble(std::span<const contact::BlockView> b, contact::SystemSink& s) override {
    inner_.assemble(b, s);
  }
  core::ContactCheck check(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    const core::ContactCheck r = inner_.check(b, D);
    checked_ = true;
    last_ = r;
    if (on()) {
      const auto& k = r.changes;
      std::printf(" [c%d o%d s%d l%d r%d y%d]", k.closed, k.opened, k.slipped, k.stuck, k.refinements, k.cycled);
      if (contacts) {
        std::printf("\n");
        for (const auto& c : sys_.trial_contacts())
          std::printf("   #%llu v%d.%d e%d.%d %-7s N %.6g F %.6g pen %.4g len %.3g lt %.3g lock %.6g\n",
                      static_cast<unsigned long long>(c.id), c.key.vblock, c.key.vertex, c.key.eblock,
                      c.key.edge, contact::contact_state_name(c.state), c.normal_force, c.shear_force,
                      c.penetration, c.length, c.tributary_length, c.locking_ratio);
      }
    }
    return r;
  }
  void end_step(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    const contact::DetectionStats& st = sys_.stats();
    auto add = [](contact::DetectionStats::Restart& to, const contact::DetectionStats::Restart& r) {
      to.contacts += r.contacts;
      to.energy += r.energy;
    };
    add(diagnosis.restart_new, st.restart_new);
    add(diagnosis.restart_edge, st.restart_edge);
    add(diagnosis.restart_kind, st.restart_kind);
    add(diagnosis.restart_same, st.restart_same);
    inner_.end_step(b, D);
    if (on()) {
      std::printf(" ok\n");
      if (contacts)
        for (const auto& c : sys_.contacts())
          std::printf("   end #%llu %-7s N %.6g F %.6g pen %.4g shear %.6g\n",
                      static_cast<unsigned long long>(c.id), contact::contact_state_name(c.state),
                      c.normal_force, c.shear_force, c.penetration, c.shear_displacement);
    }
  }
  void abandon_step() override {
    if (on()) std::printf(" cut\n");
    if (!checked_) {
      ++diagnosis.singular;
    } else if (last_.state_changes == 0) {
      ++diagnosis.redone;
    } else {
      const auto& k = last_.changes;
      const int changes = k.closed + k.opened + k.slipped + k.stuck;
      (2 * k.cycled >= changes && changes > 0 ? diagnosis.cycling : diagnosis.unsettled) += 1;
      diagnosis.cycled += k.cycled;
      diagnosis.cycled_corners += k.cycled_corners;
      diagnosis.changes += changes;
    }
    inner_.abandon_step();
  }
  bool retract_step() override { return inner_.retract_step(); }
  // The explicit step's cycles, passed through (--cycles).
  bool begin_cycles(std::span<const contact::BlockView> b, int threads) override {
    return inner_.begin_cycles(b, threads);
  }
  void cycle_stiffness(std::vector<core::Mat6>& K) const override { inner_.cycle_stiffness(K); }
  void cycle_damping(double tau, std::vector<core::Mat6>& C) override { inner_.cycle_damping(tau, C); }
  void cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double h, Eigen::VectorXd& f) override {
    inner_.cycle_forces(D, V, h, f);
  }
  int cycle_relinearize(const Eigen::VectorXd& D) override { return inner_.cycle_relinearize(D); }
  core::ContactCheck end_cycles(std::span<const contact::BlockView> b, const Eigen::VectorXd& D,
                                const Eigen::VectorXd& V) override {
    return inner_.end_cycles(b, D, V);
  }
  double creep_error_estimate() const override { return inner_.creep_error_estimate(); }
  int creep_state_changes() const override { return inner_.creep_state_changes(); }
  double time_to_failure() const override { return inner_.time_to_failure(); }
  core::ContactEnergy energy() const override { return inner_.energy(); }
  bool contact_forces(const Eigen::VectorXd& D, Eigen::VectorXd& f) const override {
    return inner_.contact_forces(D, f);
  }

 private:
  core::ContactAdapter& inner_;
  contact::ContactSystem& sys_;
  int step_ = 0;
  bool checked_ = false;       ///< a check since the attempt's begin_step
  core::ContactCheck last_;    ///< the last check
};

}  // namespace

int trace(int argc, char** argv);

int main(int argc, char** argv) {
  const char* usage =
      "usage: scene_trace SCENE.yaml [--steps N] [--from S] [--to S] [--contacts] "
      "[--dt DT] [--duration T] [--summary] [--diagnose] [--cycles] [--block B]... [--restore STATE [--state-scene SCENE.yaml]]\n";
  if (argc >= 2 && (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))) {
    std::printf("%s", usage);
    return 0;
  }
  if (argc < 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "%s", usage);
    return 2;
  }
  try {
    return trace(argc, argv);
  } catch (const std::exception& e) {  // a refused scene (file:line:column: key: message) or a failed step
    std::fprintf(stderr, "scene_trace: %s\n", e.what());
    return 1;
  }
}

int trace(int argc, char** argv) {
  int steps = -1;
  double dt = 0.0, duration = 0.0;
  bool summary = false, diagnose = false, cycles = false;
  std::string restore, state_scene = argv[1];
  scene::SceneDescription sd = scene::load_scene(argv[1]);
  scene::BuiltScene built = scene::build_scene(sd);
  contact::ContactSystem sys(built.joint_sets, built.contact_settings);
  core::ContactAdapter adapter(sys);
  Tracer tracer(adapter, sys);
  for (int k = 2; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--steps") && k + 1 < argc) steps = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--from") && k + 1 < argc) tracer.from = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--to") && k + 1 < argc) tracer.to = std::atoi(argv[++k]);
    else if (!std::strcmp(argv[k], "--contacts")) tracer.contacts = true;
    else if (!std::strcmp(argv[k], "--block") && k + 1 < argc) tracer.shown_blocks.push_back(std::atoi(argv[++k]));
    else if (!std::strcmp(argv[k], "--dt") && k + 1 < argc) dt = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--duration") && k + 1 < argc) duration = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--summary")) summary = true;
    else if (!std::strcmp(argv[k], "--diagnose")) diagnose = summary = true;
    else if (!std::strcmp(argv[k], "--cycles")) cycles = summary = true;
    else if (!std::strcmp(argv[k], "--restore") && k + 1 < argc) restore = argv[++k];
    else if (!std::strcmp(argv[k], "--state-scene") && k + 1 < argc) state_scene = argv[++k];
    else {
      std::fprintf(stderr, "scene_trace: unknown option '%s'\n", argv[k]);
      return 2;
    }
  }
  tracer.quiet = summary;
  if (dt > 0.0) built.model.settings.dt = dt;
  core::Engine engine(built.model, tracer);
  if (!restore.empty()) {
    // Simulation.save's bytes: one header line (JSON), then the snapshot of the engine and
    // the contacts (python/src/simulation_state.cpp), keyed to the scene file's text.
    auto read = [](const std::string& path) {
      std::ifstream in(path, std::ios::binary);
      if (!in) throw std::runtime_error("cannot open " + path);
      std::ostringstream ss;
      ss << in.rdbuf();
      return ss.str();
    };
    // A run's checkpoint (OUTDIR/checkpoint-K.state) is the snapshot itself, without that line.
    const std::string bytes = read(restore);
    const auto eol = bytes.find('\n');
    if (eol == std::string::npos) throw std::runtime_error(restore + ": not a saved simulation");
    const bool checkpoint = bytes.compare(0, 16, "{\"rheodda_state\"") == 0;
    const scene::EngineSnapshot snap =
        scene::decode_snapshot(checkpoint ? bytes : bytes.substr(eol + 1), restore, read(state_scene));
    engine.restore(snap.engine);
    sys.restore(snap.contacts);
  }
  auto last = std::chrono::steady_clock::now();
  if (cycles)
    engine.add_observer([&](const core::Engine& e, const core::StepReport& r) {
      const auto now = std::chrono::steady_clock::now();
      std::printf("step %d t %.6g dt %.3g cuts %d: %d cycles of %.3g (block %d), %zu contacts, largest displacement "
                  "%.3g, kinetic energy %.4g%s, %.3f s\n",
                  r.step, r.time, r.dt, r.cuts, r.cycles, r.cycle_dt, r.stable_block, sys.contacts().size(),
                  r.max_displacement, e.energy().stored.kinetic, e.in_stage() ? " (in a stage)" : "",
                  std::chrono::duration<double>(now - last).count());
      if (r.cycles > 0) {  // the fastest block: where a stage's motion is
        int fast = -1;
        double speed = 0.0;
        for (int b = 0; b < e.block_count(); ++b)
          if (const double v = e.velocity(b).head<2>().norm(); v > speed) speed = v, fast = b;
        if (fast >= 0)
          std::printf("  fastest block %d at (%.4g, %.4g): %.3g per unit time\n", fast, e.centroid(fast).x(),
                      e.centroid(fast).y(), speed);
      }
      last = now;
    });
  if (steps >= 0)
    engine.run(steps);
  else
    engine.run_until(duration > 0.0 ? duration : sd.analysis.duration);
  core::ContactChanges ch;
  int cuts = 0;
  for (const auto& r : engine.reports()) ch += r.changes, cuts += r.cuts;
  const double n = static_cast<double>(engine.step_count());
  std::printf("# %d steps to t = %.6g, %d cuts, %.2f solves per step; changes per step: closed %.2f "
              "opened %.2f slipped %.2f stuck %.2f refinements %.2f\n",
              engine.step_count(), engine.time(), cuts,
              static_cast<double>(engine.solver_stats().solves) / n, ch.closed / n, ch.opened / n,
              ch.slipped / n, ch.stuck / n, ch.refinements / n);
  if (diagnose) {
    const auto& d = tracer.diagnosis;
    const auto& e = engine.energy().total;
    std::printf("# cut or redone attempts: %d still changing states (%d of them mostly 2-cycles), %d singular "
                "solves, %d settled and redone (motion beyond the step limit, a mechanism, a wider search)\n",
                d.cycling + d.unsettled, d.cycling, d.singular, d.redone);
    std::printf("# their last iterates: %ld changes, %ld of them 2-cycles, %ld of those at corners "
                "(vertex-vertex)\n", d.changes, d.cycled, d.cycled_corners);
    std::printf("# 2-cycles in all iterates: %d, at corners %d\n", ch.cycled, ch.cycled_corners);
    std::printf("# spring energy at step starts beyond what the records stored [force x length]: new contacts "
                "%d / %.4g, moved edge %d / %.4g, changed kind %d / %.4g, same %d / %.4g; work of gravity and "
                "loads %.4g, energy residual %.3g (relative, largest %.3g)\n",
                d.restart_new.contacts, d.restart_new.energy, d.restart_edge.contacts, d.restart_edge.energy,
                d.restart_kind.contacts, d.restart_kind.energy, d.restart_same.contacts, d.restart_same.energy,
                e.work_gravity + e.work_loads, engine.energy().relative_residual(),
                engine.energy().max_relative_residual);
  }
  for (std::size_t k = 0; k < engine.measurements().size(); ++k) {
    const auto& m = engine.measurements()[k].back();
    std::printf("# measurement %zu: displacement (%.9g, %.9g)\n", k, m.displacement.x(),
                m.displacement.y());
  }
  return 0;
}
