// Quantities with units: "2600 kg/m^3", "20 GPa", "100 d", "3.48e4 MPa*h/mm". The one
// place that parses unit strings and converts between them, by UDUNITS-2 (its default
// unit database; no table of factors here). The scene file, the study file, the command
// line, `rheodda fit` and `rheodda forecast` read quantities through it
// (docs/reference/scene-format.md, "Units").
//
// A scene states its units as three labels (length, force, time); every key declares its
// dimension in those words ("stress", "mass/length³", "stress*time/length", ...).
// unit_of() writes such a dimension with the scene's labels, convert() takes a value from
// the unit it was written in to that one, and refuses, naming both dimensions, a unit of
// another dimension.
//
// UDUNITS-2 is not thread-safe; every call here holds one lock, and its unit system is
// read once, on first use.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rheodda::units {

/// A unit UDUNITS-2 does not know, or a conversion between units of different dimensions.
class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A number as written with its unit: "2600 kg/m^3" is {2600, "kg/m^3"}.
struct Quantity {
  double value = 0.0;
  std::string unit;  ///< the text after the number, trimmed; "" when none is written
};

/// "2600 kg/m^3" -> {2600, "kg/m^3"}; "2600" -> {2600, ""}; nullopt when the text does not
/// start with a finite number (a sign, digits, a point, an exponent) or the number is not
/// followed by a space or the end (so that "1e5x" is no quantity). The unit is not checked.
std::optional<Quantity> split_quantity(std::string_view text);

/// Base units by their labels: a scene's `units: {length: m, force: N, time: d}`, or a
/// laboratory fit's stress, length and time (`--units "MPa, mm, h"`: `stress` given,
/// `force` empty).
struct Base {
  std::string length, force, time;
  std::string stress{};  ///< empty: force/length^2
};

/// The unit of `dimension`, written in the declarations' words (length, force, time,
/// stress = force/length² (or `base.stress`), mass = force·time²/length, deg, with *, /,
/// ^n, ², ³ and ·;
/// "–" or "-" for none), spelled with `base`'s labels for UDUNITS-2:
/// "stress*time/length" in {mm, N, h} is "N/mm^2*h/mm" (read left to right, as UDUNITS-2
/// does: (N/mm^2)*h/mm), "length/stress" is "mm/(N/mm^2)"; none is "1". A label of more
/// than one word is put in parentheses.
std::string unit_of(std::string_view dimension, const Base& base);

/// Whether UDUNITS-2 knows `unit` ("kg/m^3", "MPa*h/mm", "d"; also "deg", the arc degree).
bool known(const std::string& unit);

/// Whether a value in `from` can be converted to `to` (both known, the same dimension).
bool convertible(const std::string& from, const std::string& to);

/// `value` in `from` expressed in `to`. Throws UnitError when either is unknown
/// ("unknown unit 'kgg'") or their dimensions differ (the message names both, in words:
/// "kg/m^2 is force*time^2/length^3, not force*time^2/length^4").
double convert(double value, const std::string& from, const std::string& to);

/// The dimension of a known unit in words of force, length and time (and angle, current,
/// temperature, amount, luminosity where they appear): "MPa*h/mm" is
/// "force*time/length^3", "kg/m^3" is "force*time^2/length^4", "1" is "dimensionless".
/// Throws UnitError for an unknown unit.
std::string dimension_words(const std::string& unit);

}  // namespace rheodda::units
