// Shared declarations of the Python module's translation units (docs/guide/python.md).
//
// The binding is thin on purpose: every call goes to the library function the
// command line uses (laws::LawRegistry, laws::integrate_curve, fit::fit_law,
// scene::parse_scene/build_scene/run_scene, core::Engine), so a result or an
// error message is the one `rheodda` gives.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace rheodda::python {

namespace py = pybind11;

void bind_errors(py::module_& m);
void bind_laws(py::module_& m);
void bind_python_law(py::module_& m);  // after bind_laws: PythonLaw derives from Law
void bind_law_curves(py::module_& m);
void bind_fit(py::module_& m);
void bind_scene(py::module_& m);
void bind_simulation(py::module_& m);
void bind_run(py::module_& m);
void bind_units(py::module_& m);

/// A 1-D numpy array holding a copy of `v`.
inline py::array_t<double> to_numpy(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

/// A 1-D numpy array of ints holding a copy of `v`.
inline py::array_t<long> to_numpy(const std::vector<long>& v) {
  py::array_t<long> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

/// `a` made read-only: a property computed from the state (a fresh copy at each
/// read) refuses writes instead of dropping them silently (docs/guide/python.md,
/// "numpy conventions").
template <class Array>
Array read_only(Array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// A 1-D numpy array of str (numpy's unicode dtype) holding `v`.
inline py::array str_array(const std::vector<std::string>& v) {
  return py::module_::import("numpy").attr("array")(py::cast(v), py::arg("dtype") = "str");
}

/// Raises rheodda.PythonLawError (errors.cpp) for a value a method of a law
/// written in Python returned: `value` its repr, `expected` what it should be.
[[noreturn]] void raise_python_law_error(const std::string& law, const std::string& method,
                                         const std::string& value, const std::string& expected);
/// A PythonLawError raised inside the step `step` (as history's `step` column counts it) from
/// time `time` [time_unit]: its message and attributes get them (errors.cpp); any other error unchanged.
void locate_python_law_error(py::error_already_set& e, long step, double time, const std::string& time_unit);

/// Raises the pending Python error (KeyboardInterrupt after Ctrl-C) if a signal
/// handler raised one; call with the GIL held, between steps.
inline void check_signals() {
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

}  // namespace rheodda::python

namespace rheodda::python {

/// Bad input found by the binding itself (an unknown setting, a load index out
/// of range ...): becomes rheodda.Error.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run that failed: becomes rheodda.RunError (RuntimeError).
class RunFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rheodda::python
