// The parts of `rheodda check`'s description (describe.hpp) that have a file of
// their own: the analysis's settings, the values given with a unit and what the rock
// mass's cut gave. Internal to scene/; not installed.
#pragma once

#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene::detail {

/// The `analysis:` lines: every declared key with its value, then what they add up
/// to (the solver, the time step control, a settling stage, outputs, run guards).
std::string describe_analysis(const SceneDescription& s);

/// The values the file gave with a unit of their own, each in the scene's units and as
/// written ("" when there are none): describe_quantities.cpp.
std::string describe_given_quantities(const SceneDescription& s);

/// The `rock mass` lines: the blocks the cut gave, their size distribution, the
/// joint sets drawn and the joint length per joint set.
std::string describe_rock_mass(const SceneDescription& s, const RockMassDescription& r);

}  // namespace rheodda::scene::detail
