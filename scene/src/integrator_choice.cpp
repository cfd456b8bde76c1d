// `integrator: automatic` (integrator_choice.hpp; docs/reference/explicit-step.md, "Automatic
// choice"). The estimated CPU per dynamic step of either integrator, fitted to the running-bond
// wall measured in docs/notes/explicit-step.md ("The brick wall"):
//   explicit: n_c (contacts + blocks) t_c,  n_c = ceil(dt / h) cycles of the stable cycle h
//             on the initial state, t_c = 27 ns per contact update per cycle (the wall's
//             25-29 ns at 410 and 1 620 blocks)                                          (1)
//   implicit: s a n^2,  s = 11 solves per step (the wall's 10-12 open-close iterates),
//             a = 8.7e-9 s per block^2 for a factorisation and solve (the wall's 0.0167,
//             0.2506 and 3.0-4.5 CPU s per 1 ms step at 410, 1 620 and 6 440 blocks:
//             n^2 within 5 % at the first two)                                           (2)
// The explicit step is taken where (1) < (2); on the wall that is from about 1 000 blocks
// (measured: the implicit step cheaper at 410, the explicit one at 1 620).
#include "rheodda/scene/integrator_choice.hpp"

#include <fmt/format.h>

#include <cmath>
#include <exception>

#include "rheodda/core/integrator.hpp"
#include "rheodda/scene/assemble.hpp"
#include "rheodda/scene/build.hpp"

namespace rheodda::scene {

namespace {

constexpr double kContactUpdateSeconds = 27e-9;  ///< t_c of (1) [s]
constexpr double kImplicitSolves = 11.0;          ///< s of (2) [-]
constexpr double kSolveSecondsPerBlock2 = 8.7e-9; ///< a of (2) [s]

/// Why the explicit step cannot take the scene's dynamic steps, or "" (the engine's and the
/// loader's refusals of `integrator: explicit`, read_analysis.cpp).
std::string explicit_refusal(const Analysis& a) {
  if (!a.has_dynamic_steps()) return "a static analysis without a dynamic settling stage has no dynamic step";
  if (a.step_tolerance > 0.0) return "step doubling (step_tolerance) estimates the implicit step's error";
  if (a.time_integration == TimeIntegration::trapezoidal) return "time_integration chooses the implicit step's scheme";
  return "";
}

}  // namespace

IntegratorChoice choose_integrator(const SceneDescription& s) {
  IntegratorChoice out;
  if (s.analysis.integrator != core::Integrator::automatic) {
    out.integrator = s.analysis.integrator;
    out.reason = "given";
    return out;
  }
  if (const std::string no = explicit_refusal(s.analysis); !no.empty()) {
    out.integrator = core::Integrator::implicit;
    out.reason = "automatic: implicit, since " + no;
    return out;
  }
  // A probe: the scene with the explicit step, its stable cycle on the initial state and the
  // contacts of its first step.
  // A scene the engine refuses under the explicit step (a dynamic analysis that carries no
  // velocity, dynamic_ratio 0) takes the implicit one; what is wrong with it otherwise, the
  // implicit build says.
  SceneDescription probe = s;
  probe.analysis.integrator = core::Integrator::explicit_step;
  BuiltScene built;
  AssembledScene a;
  core::Engine::StableCycle c;
  try {
    built = build_scene(probe);
    a = assemble_scene(probe, built);
    c = a.engine->stable_cycle();
  } catch (const std::exception& e) {
    out.integrator = core::Integrator::implicit;
    out.reason = fmt::format("automatic: implicit, since the explicit step refuses the scene ({})", e.what());
    return out;
  }
  const bool staged = s.analysis.type != AnalysisType::dynamic_analysis;  // the dynamic steps are the stages'
  const double dt = staged ? s.analysis.settle.dt : s.analysis.dt;
  const double blocks = a.engine->block_count();
  out.implicit_seconds = kImplicitSolves * kSolveSecondsPerBlock2 * blocks * blocks;  // (2)
  if (c.block < 0) {
    out.integrator = core::Integrator::implicit;
    out.reason = "automatic: implicit, since nothing stiff holds a block at the start (no cycle to estimate by)";
    return out;
  }
  try {
    a.engine->step();
  } catch (const std::exception& e) {
    out.integrator = core::Integrator::implicit;
    out.reason = fmt::format("automatic: implicit, since the explicit step's first step failed ({})", e.what());
    return out;
  }
  const double contacts = static_cast<double>(a.contacts->contacts().size());
  const double cycles = std::ceil(dt / c.cycle - 1e-9);
  out.explicit_seconds = cycles * (contacts + blocks) * kContactUpdateSeconds;  // (1)
  out.integrator =
      out.explicit_seconds < out.implicit_seconds ? core::Integrator::explicit_step : core::Integrator::implicit;
  out.reason = fmt::format(
      "automatic: {}, estimated CPU per dynamic step: explicit {:.3g} s ({:g} cycles x ({:g} contacts + {:g} blocks) x "
      "{:g} ns), implicit {:.3g} s ({:g} solves x {:g} ns x {:g} blocks^2)",
      core::integrator_entry(out.integrator).word, out.explicit_seconds, cycles, contacts,
      blocks, kContactUpdateSeconds * 1e9, out.implicit_seconds, kImplicitSolves, kSolveSecondsPerBlock2 * 1e9, blocks);
  return out;
}

}  // namespace rheodda::scene
