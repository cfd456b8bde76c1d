// A number written with its unit ("2600 kg/m^3", "84.5 kN/m", "-9.81 m/s^2") read into
// the scene's units (quantity.hpp; yaml_reader.hpp, quantity()): the one place the scene
// reader converts, through rheodda::units (UDUNITS-2). A bare number never needs it: it
// is in the scene's units as written.
#include "rheodda/scene/quantity.hpp"

#include <fmt/format.h>

#include <cmath>

#include "rheodda/units/units.hpp"
#include "yaml_reader.hpp"

namespace rheodda::scene {

namespace {

/// The dimension as the messages name it: the declaration's words and, where they are
/// not already so, in force, length and time.
std::string dimension_text(const std::string& dimension, const std::string& unit) {
  std::string words;
  try {
    words = units::dimension_words(unit);
  } catch (const units::UnitError&) {
    return dimension;
  }
  return words == dimension ? dimension : fmt::format("{} = {}", dimension, words);
}

GivenQuantity convert(const std::string& text, const std::string& dimension, const Units& su) {
  const std::optional<units::Quantity> q = units::split_quantity(text);
  if (!q) throw QuantityError(fmt::format("'{}' is not a number (or a number and its unit)", text));
  const units::Base base{.length = su.length, .force = su.force, .time = su.time};
  const bool none = dimension.empty() || dimension == "-" || dimension == "–";
  const std::string target = units::unit_of(none ? "-" : dimension, base);
  GivenQuantity g{.key = {}, .where = {}, .text = text, .value = q->value, .unit = target};
  if (q->unit.empty()) return g;
  if (!units::known(target))
    throw QuantityError(fmt::format("'{}': this value takes a plain number in {} (the scene's units {}, {}, {} are "
                                    "not all units UDUNITS-2 knows, so nothing can be converted into them)",
                                    text, target, su.length, su.force, su.time));
  if (!units::known(q->unit))
    throw QuantityError(fmt::format("'{}': unknown unit '{}' (write units as UDUNITS-2 reads them: m, mm, kN, MPa, "
                                    "GPa, kg/m^3, m/s^2, s, ms, h, d, deg, MPa*h/mm)",
                                    text, q->unit));
  // A 2D scene's forces are per unit thickness: "84.5 kN/m" is explicit, "84.5 kN" is read
  // as per unit thickness of the scene's length.
  const std::string per_thickness = dimension == "force" ? units::unit_of("force/length", base) : "";
  if (!per_thickness.empty() && units::convertible(q->unit, per_thickness)) {
    g.value = units::convert(q->value, q->unit, per_thickness);
    g.unit = per_thickness;
  } else if (units::convertible(q->unit, target)) {
    g.value = units::convert(q->value, q->unit, target);
    g.per_thickness = !per_thickness.empty();
  } else {
    const std::string takes =
        none ? std::string("is dimensionless")
             : fmt::format("takes {} ({} in this scene's units{})", dimension_text(dimension, target), target,
                           per_thickness.empty() ? "" : fmt::format(", or {} per unit thickness", per_thickness));
    throw QuantityError(fmt::format("'{}' has the wrong dimension: {} is {}, this key {}", text, q->unit,
                                    units::dimension_words(q->unit), takes));
  }
  if (!std::isfinite(g.value)) throw QuantityError(fmt::format("'{}' is not finite in the scene's units", text));
  return g;
}

}  // namespace

GivenQuantity to_scene_units(const std::string& text, const std::string& dimension, const Units& u) {
  try {
    return convert(text, dimension, u);
  } catch (const units::UnitError& e) {  // e.g. no unit database: named at the value all the same
    throw QuantityError(fmt::format("'{}': {}", text, e.what()));
  }
}

double scene_number(const std::string& text, const std::string& dimension, const Units& u) {
  return to_scene_units(text, dimension, u).value;
}

namespace detail {

double quantity(const Ctx& ctx, const YAML::Node& n, const std::string& key, const std::string& text,
                const std::string& dimension) {
  const std::optional<units::Quantity> q = units::split_quantity(text);
  if (!q || q->unit.empty()) ctx.fail(n, key, fmt::format("'{}' is not a number", text));
  if (!ctx.units)
    ctx.fail(n, key, fmt::format("'{}': a value with a unit needs the scene's `units:` to convert into; give a number", text));
  GivenQuantity g;
  try {
    g = to_scene_units(text, dimension, *ctx.units);
  } catch (const QuantityError& e) {
    ctx.fail(n, key, e.what());
  }
  g.key = key;
  g.where = location(n);
  if (ctx.given) ctx.given->push_back(g);
  return g.value;
}

}  // namespace detail

}  // namespace rheodda::scene
