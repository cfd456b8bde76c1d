#include "rheodda/laws/automatic_scheme.hpp"

#include "rheodda/laws/series_law.hpp"

namespace rheodda::laws {

Scheme automatic_scheme(const ContactRheology& law, double k, double dt) {
  const auto* series = dynamic_cast<const SeriesLaw*>(&law);
  if (!series) return Scheme::implicit;
  for (const CreepElement& e : series->elements()) {
    const double E = e.kind == CreepElement::Kind::kelvin ? e.E : 0.0;  // a dashpot alone: no spring
    if (dt * (k + E) > 2.0 * e.eta) return Scheme::implicit;
  }
  return Scheme::exponential_linear;
}

}  // namespace rheodda::laws
