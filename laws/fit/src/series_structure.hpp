// Internal to rheodda_fit: a registered law seen as a spring plus creep
// elements in series, each constant tied to the parameter that carries it
// (found by fit.cpp's probe_structure). Shared by the nonlinear fit (fit.cpp)
// and the variable-projection search for its starts (varpro.cpp).
#pragma once

#include <vector>

#include "rheodda/laws/series_law.hpp"

namespace rheodda::fit::detail {

using Kind = laws::CreepElement::Kind;

/// One creep element, by parameter index (-1 where the element has no such constant).
struct Element {
  Kind kind = Kind::dashpot;
  int E = -1, eta = -1, threshold = -1;
};

struct SeriesStructure {
  int spring = -1;  ///< parameter index of E1, -1 without instantaneous spring
  std::vector<Element> elements;
};

}  // namespace rheodda::fit::detail
