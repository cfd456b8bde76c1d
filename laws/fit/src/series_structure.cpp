// The law as a spring plus creep elements, in terms of its parameters
// (series_structure.hpp): probe_structure.
#include "series_structure.hpp"

#include <exception>
#include <memory>

namespace rheodda::fit::detail {

// Builds the law once with distinct probe values and matches each constant of
// its spring and elements to the parameter that carries it; this gives the
// analytic model (and its Jacobian) for any registered SeriesLaw. nullopt if
// the law is not a SeriesLaw whose constants are its parameters one to one.
std::optional<SeriesStructure> probe_structure(const laws::LawInfo& info) {
  const std::size_t np = info.parameters.size();
  laws::ParameterValues probe;
  std::vector<double> values(np);
  for (std::size_t k = 0; k < np; ++k) {
    values[k] = 1.5 + 0.75 * static_cast<double>(k);
    probe[info.parameters[k].name] = values[k];
  }
  std::unique_ptr<laws::ContactRheology> law;
  try {
    law = info.make(laws::validate_parameters(info.name, info.parameters, probe));
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const auto* series = dynamic_cast<const laws::SeriesLaw*>(law.get());
  if (!series) return std::nullopt;
  std::vector<int> used(np, 0);
  bool ok = true;
  auto index_of = [&](double v) {
    for (std::size_t k = 0; k < np; ++k)
      if (values[k] == v) {
        ++used[k];
        return static_cast<int>(k);
      }
    ok = false;
    return -1;
  };
  SeriesStructure s;
  if (const auto e1 = series->instantaneous_stiffness()) s.spring = index_of(*e1);
  for (const auto& el : series->elements()) {
    Element e;
    e.kind = el.kind;
    e.eta = index_of(el.eta);
    if (el.kind == Kind::kelvin) e.E = index_of(el.E);
    if (el.kind == Kind::bingham) e.threshold = index_of(el.threshold);
    s.elements.push_back(e);
  }
  if (!ok || s.elements.size() > 8) return std::nullopt;  // evaluate_series holds 8 elements
  for (int u : used)
    if (u != 1) return std::nullopt;
  return s;
}

}  // namespace rheodda::fit::detail
