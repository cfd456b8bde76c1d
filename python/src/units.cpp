// Quantities with units from Python (rheodda::units, UDUNITS-2): a dimension spelled with
// unit labels and a value converted between units; rheodda.fit(..., units=) and
// FitResult.scene_yaml() write a fitted law in a scene's units with them (_fitting.py).
#include <rheodda/units/units.hpp>

#include "common.hpp"

namespace rheodda::python {

void bind_units(py::module_& m) {
  m.def(
      "_unit_of",
      [](const std::string& dimension, const std::string& length, const std::string& force, const std::string& time,
         const std::string& stress) {
        return units::unit_of(dimension, {.length = length, .force = force, .time = time, .stress = stress});
      },
      py::arg("dimension"), py::arg("length"), py::arg("force"), py::arg("time"), py::arg("stress") = "",
      "The unit of a dimension ('stress*time/length') spelled with unit labels (rheodda::units::unit_of).");
  m.def(
      "_convert",
      [](double value, const std::string& from, const std::string& to) {
        try {
          return units::convert(value, from, to);
        } catch (const units::UnitError& e) {
          throw InputError(e.what());
        }
      },
      py::arg("value"), py::arg("from_unit"), py::arg("to_unit"),
      "value in from_unit expressed in to_unit (UDUNITS-2); rheodda.Error for an unknown unit or another dimension.");
}

}  // namespace rheodda::python
