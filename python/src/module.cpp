// The extension module rheodda._rheodda; the package rheodda (python/rheodda/__init__.py)
// re-exports it and adds the pure-Python helpers (pandas conversion, dict scenes).
#include "common.hpp"

PYBIND11_MODULE(_rheodda, m) {
  m.doc() = "rheodda: creep of jointed rock (contact rheology laws in a DDA engine); docs/guide/python.md";
  m.attr("__version__") = "0.1.0";
  rheodda::python::bind_errors(m);
  rheodda::python::bind_laws(m);
  rheodda::python::bind_python_law(m);
  rheodda::python::bind_law_curves(m);
  rheodda::python::bind_fit(m);
  rheodda::python::bind_scene(m);
  rheodda::python::bind_simulation(m);
  rheodda::python::bind_run(m);
  rheodda::python::bind_units(m);
}
