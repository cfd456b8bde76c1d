// The engine a scene runs on, assembled in one place for `rheodda run`
// (run.cpp) and the Python module (python/src/simulation.cpp): the contact
// system on the built joint sets, the adapter the engine sees it through, and
// the engine on the built model. What the contact layer or the engine refuses
// becomes a SceneError at the scene's entry it comes from.
#pragma once

#include <memory>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// The three parts, each held by pointer so that they stay where the others
/// point at them (the adapter refers to the contacts, the engine to the adapter).
struct AssembledScene {
  std::unique_ptr<contact::ContactSystem> contacts;
  std::unique_ptr<core::ContactAdapter> adapter;  ///< on *contacts
  std::unique_ptr<core::Engine> engine;           ///< on built.model and *adapter
};

/// Assembles `built` (build_scene of `scene`, its joint sets' laws possibly
/// replaced). Throws SceneError: a joint set the contact layer refuses
/// (contact::JointSetError says which, as data) points at that joint set, else at
/// the analysis; a model the engine refuses points at the block or material its
/// error names (core::ModelError::entry), else at the analysis.
AssembledScene assemble_scene(const SceneDescription& scene, const BuiltScene& built);

}  // namespace rheodda::scene
