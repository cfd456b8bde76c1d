// `rheodda check`'s lines on the values the file gave with a unit of their own: each in
// the scene's units beside the text it was written as (describe_parts.hpp).
#include <fmt/format.h>

#include "describe_parts.hpp"
#include "rheodda/scene/describe.hpp"

namespace rheodda::scene::detail {

std::string describe_given_quantities(const SceneDescription& s) {
  if (s.given_quantities.empty()) return {};
  std::string out = fmt::format("values given with a unit ({}), in the scene's units:\n", s.given_quantities.size());
  for (const GivenQuantity& g : s.given_quantities)
    out += fmt::format("  {} {}{} (given as {} at line {}{})\n", g.key, exact_number(g.value),
                       g.unit == "1" ? "" : " " + g.unit, g.text, g.where.line,
                       g.per_thickness ? fmt::format("; a 2D scene's forces are per unit thickness: read as per {} of "
                                                     "thickness, write {}/{} to say so",
                                                     s.units.length, g.text, s.units.length)
                                       : "");
  return out;
}

}  // namespace rheodda::scene::detail
