// Internal to rheodda_fit: a registered law seen as a spring plus creep
// elements in series, each constant tied to the parameter that carries it
// (found by probe_structure, series_structure.cpp). Shared by the residuals of
// the nonlinear fit (residuals.cpp), its starts (starts.cpp), identifiability
// (identifiability.cpp) and the variable-projection search for its starts (varpro.cpp).
#pragma once

#include <optional>
#include <vector>

#include "rheodda/laws/registry.hpp"
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

/// The law's spring and elements matched to its parameters; nullopt if the law
/// is not a SeriesLaw whose constants are its parameters one to one.
std::optional<SeriesStructure> probe_structure(const laws::LawInfo& info);

}  // namespace rheodda::fit::detail
