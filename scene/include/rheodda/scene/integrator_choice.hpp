// `integrator: automatic` (docs/reference/explicit-step.md, "Automatic choice"): the scene's
// dynamic steps taken by the step whose estimated cost per step is lower, the explicit one's
// from its cycles and contacts on the scene's initial state, the implicit one's from its
// block count.
#pragma once

#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// The integrator a scene's dynamic steps take, and why.
struct IntegratorChoice {
  core::Integrator integrator = core::Integrator::implicit;  ///< one with a trial of its own, never automatic
  std::string reason;           ///< one sentence: the given word, or the estimate and its figures
  double explicit_seconds = 0.0;  ///< the explicit step's estimated CPU per dynamic step [s]; 0: not estimated
  double implicit_seconds = 0.0;  ///< the implicit step's estimated CPU per dynamic step [s]; 0: not estimated
};

/// The scene's `integrator` where it names one; under `automatic`, the cheaper by the estimate
/// (a probe of the scene built with the explicit step takes one step to count its contacts).
IntegratorChoice choose_integrator(const SceneDescription& scene);

}  // namespace rheodda::scene
