// A number in a scene's units from text that may carry its unit ("100 d", "2600 kg/m^3"):
// the scene file's values (the loader), and the numbers the command line and a study
// file give for a scene (`check --until`, `forecast --by`, a study's `times`). A bare
// number is in the scene's units, kept exactly; a unit is converted from by rheodda::units
// (UDUNITS-2). docs/reference/scene-format.md, "Values with units".
#pragma once

#include <stdexcept>
#include <string>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// A value that cannot be read in the scene's units: not a number, an unknown unit, a
/// unit of another dimension (the message names both), labels UDUNITS-2 does not know.
class QuantityError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// "VALUE UNIT" of `dimension` (the key declarations' words: "time", "stress",
/// "mass/length^3", "length/time^2", "" for none) in the scene's units `u`; `key` and
/// `where` are left empty. A force ("force") may be given per length (per unit
/// thickness, explicit) or as a bare force (read per unit thickness of the scene's length:
/// per_thickness). Throws QuantityError.
GivenQuantity to_scene_units(const std::string& text, const std::string& dimension, const Units& u);

/// `text` as a number of `dimension` in the scene's units: a bare number as written, a
/// number with its unit converted (to_scene_units). Throws QuantityError.
double scene_number(const std::string& text, const std::string& dimension, const Units& u);

}  // namespace rheodda::scene
