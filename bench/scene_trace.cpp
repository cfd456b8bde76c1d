// The open-close iteration of a scene, step by step: what each iterate changed
// and, on request, every contact's state and forces after each iterate.
//
// Sample runs:
//   build/bench/scene_trace examples/sliding-block.yaml --steps 20
//   build/bench/scene_trace scene.yaml --from 40 --to 45 --contacts
//       # steps 40-45: each iterate's changes, then per contact: id, vertex
//       # block/vertex, edge block/edge, state, N, shear force, penetration
//   build/bench/scene_trace scene.yaml --dt 1e-4 --duration 0.5 --summary
//       # only the totals: steps, cuts, solves per step, changes by kind
//
// Runs the scene as `rheodda run` does (same model, joint sets and contact
// settings) without writing outputs. A diagnostic tool: it asserts nothing.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;

namespace {

class Tracer final : public core::ContactModel {
 public:
  Tracer(core::ContactAdapter& inner, contact::ContactSystem& sys) : inner_(inner), sys_(sys) {}
  int from = 0, to = 1 << 30;
  bool contacts = false, quiet = false;

  bool on() const { return !quiet && step_ >= from && step_ <= to; }
  void begin_step(std::span<const contact::BlockView> b, const core::StepContext& ctx) override {
    step_ = ctx.step;
    if (on()) std::printf("step %d t %.6g dt %.3g:", ctx.step, ctx.time, ctx.dt);
    inner_.begin_step(b, ctx);
  }
  void assemble(std::span<const contact::BlockView> b, contact::SystemSink& s) override {
    inner_.assemble(b, s);
  }
  core::ContactCheck check(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
    const core::ContactCheck r = inner_.check(b, D);
    if (on()) {
      const auto& k = r.changes;
      std::printf(" [c%d o%d s%d l%d r%d]", k.closed, k.opened, k.slipped, k.stuck, k.refinements);
      if (contacts) {
        std::printf("\n");
        for (const auto& c : sys_.trial_contacts())
          std::printf("   #%llu v%d.%d e%d.%d %-7s N %.6g F %.6g pen %.4g len %.3g\n",
                      static_cast<unsigned long long>(c.id), c.key.vblock, c.key.vertex, c.key.eblock,
                      c.key.edge, contact::contact_state_name(c.state), c.normal_force, c.shear_force,
                      c.penetration, c.length);
      }
    }
    return r;
  }
  void end_step(std::span<const contact::BlockView> b, const Eigen::VectorXd& D) override {
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
    inner_.abandon_step();
  }

 private:
  core::ContactAdapter& inner_;
  contact::ContactSystem& sys_;
  int step_ = 0;
};

}  // namespace

int trace(int argc, char** argv);

int main(int argc, char** argv) {
  const char* usage =
      "usage: scene_trace SCENE.yaml [--steps N] [--from S] [--to S] [--contacts] "
      "[--dt DT] [--duration T] [--summary]\n";
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
  bool summary = false;
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
    else if (!std::strcmp(argv[k], "--dt") && k + 1 < argc) dt = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--duration") && k + 1 < argc) duration = std::atof(argv[++k]);
    else if (!std::strcmp(argv[k], "--summary")) summary = true;
    else {
      std::fprintf(stderr, "scene_trace: unknown option '%s'\n", argv[k]);
      return 2;
    }
  }
  tracer.quiet = summary;
  if (dt > 0.0) built.model.settings.dt = dt;
  core::Engine engine(built.model, tracer);
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
  for (std::size_t k = 0; k < engine.measurements().size(); ++k) {
    const auto& m = engine.measurements()[k].back();
    std::printf("# measurement %zu: displacement (%.9g, %.9g)\n", k, m.displacement.x(),
                m.displacement.y());
  }
  return 0;
}
