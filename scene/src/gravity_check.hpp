// The check that a scene's gravity is the Earth's in the scene's units (scene_warnings,
// build.cpp). Internal to scene/; not installed.
#pragma once

#include <optional>
#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene::detail {

/// A warning when |gravity| is not 9.81 m/s^2 within 2 % in the scene's units, naming
/// the value expected there (e.g. 7.32313e+10 m/d^2 in a scene whose time is days);
/// none for a gravity of 0, under `accept_other_gravity`, or when the scene's unit
/// labels are not units UDUNITS-2 knows (then the warning says it could not check).
std::optional<std::string> gravity_warning(const SceneDescription& s);

}  // namespace rheodda::scene::detail
