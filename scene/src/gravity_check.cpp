// Gravity in the scene's units checked against the Earth's (gravity_check.hpp): a scene in
// days whose gravity is written as 9.81 moves its blocks 7.5e9 times too slowly under
// their weight, and nothing else would say so.
#include "gravity_check.hpp"

#include <fmt/format.h>

#include <cmath>

#include "rheodda/units/units.hpp"

namespace rheodda::scene::detail {

std::optional<std::string> gravity_warning(const SceneDescription& s) {
  const Analysis& a = s.analysis;
  const double g = std::hypot(a.gravity[0], a.gravity[1]);
  if (g == 0.0 || a.accept_other_gravity) return std::nullopt;
  const Units& u = s.units;
  const std::string unit = units::unit_of("length/time^2", {u.length, u.force, u.time});
  constexpr double kEarth = 9.81;  // m/s^2, within kTolerance
  constexpr double kTolerance = 0.02;
  double expected = 0.0;
  try {
    if (!units::convertible("m/s^2", unit))
      return fmt::format("gravity not checked against 9.81 m/s^2: the scene's units {} and {} are not units UDUNITS-2 "
                         "knows (`analysis.accept_other_gravity: true` if its magnitude {:g} is meant)",
                         u.length, u.time, g);
    expected = units::convert(kEarth, "m/s^2", unit);
  } catch (const units::UnitError& e) {  // no unit database: say so, the scene still runs
    return fmt::format("gravity not checked against 9.81 m/s^2: {}", e.what());
  }
  if (std::abs(g - expected) <= kTolerance * expected) return std::nullopt;
  return fmt::format("analysis.gravity: its magnitude {:g} {} is not the Earth's: 9.81 m/s^2 is {:g} {} in the "
                     "scene's units ({:.3g} times the gravity given); write it so, or with its unit "
                     "(`gravity: [0, -9.81 m/s^2]`), or give `analysis.accept_other_gravity: true` for a deliberate "
                     "other gravity",
                     g, unit, expected, unit, expected / g);
}

}  // namespace rheodda::scene::detail
