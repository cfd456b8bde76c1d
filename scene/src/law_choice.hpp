// What a fitted law carries into a scene (`unidentified`, `tested_stress`,
// `tested_duration` of a joint set's law; docs/guide/fitting.md, "What a fitted law
// carries into a scene") and the warnings `check` and `run` give from it. Internal to
// scene/; not installed.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene::detail {

/// Before a run (`check`, and `run` through scene_warnings): per joint set, the law's
/// parameters the data do not determine and what their value decides; a run longer than
/// the longest test, with the factor.
std::vector<std::string> law_choice_warnings(const SceneDescription& s);

/// Whether some joint set's law gives something law_stress_warnings compares the
/// contacts' shear stresses with (`tested_stress`, or an unidentified threshold [stress]).
bool law_stresses_checked(const SceneDescription& s);

/// During a run, at time `time` [time], described by `when` ("at the end of settling"):
/// per joint set, the shear stresses |shear_force| / tributary_length [stress] of its locked
/// contacts with a law, against the law's `tested_stress` (the share outside, the factors)
/// and against each unidentified threshold (the share below, which does not flow).
std::vector<std::string> law_stress_warnings(const SceneDescription& s, std::span<const contact::Contact> contacts,
                                             double time, const std::string& when);

}  // namespace rheodda::scene::detail
