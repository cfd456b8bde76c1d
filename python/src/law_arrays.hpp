// numpy values of the law bindings (laws.cpp, law_curves.cpp): a law's function of one
// number over an array of any shape (numpy's broadcasting for two), and a law's
// internal displacements q to and from Python.
#pragma once

#include <rheodda/laws/contact_rheology.hpp>

#include <algorithm>

#include "common.hpp"

namespace rheodda::python {

/// A float64 array in C order from any array-like (numpy converts it: forcecast).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// f applied to every element of t (any shape), as a new array of that shape.
template <class F>
inline py::array_t<double> map_array(const DoubleArray& t, F f) {
  py::array_t<double> r(t.request().shape);
  const double* in = t.data();
  double* out = r.mutable_data();
  for (py::ssize_t i = 0; i < t.size(); ++i) out[i] = f(in[i]);
  return r;
}

/// f of a number as a float, or of every element of an array-like as an array.
template <class F>
inline py::object map_object(const py::object& t, F f) {
  if (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t)) return py::float_(f(t.cast<double>()));
  return map_array(t.cast<DoubleArray>(), f);
}

/// f(a, b) over numpy's broadcast of a and b (any shapes that broadcast): a
/// float when both are numbers, else an array of the broadcast shape.
template <class F>
inline py::object map_broadcast(const py::object& a, const py::object& b, F f) {
  const auto is_number = [](const py::object& x) {
    return py::isinstance<py::float_>(x) || py::isinstance<py::int_>(x);
  };
  if (is_number(a) && is_number(b)) return py::float_(f(a.cast<double>(), b.cast<double>()));
  const py::module_ np = py::module_::import("numpy");
  const py::tuple ab = np.attr("broadcast_arrays")(np.attr("asarray")(a, py::arg("dtype") = "float64"),
                                                   np.attr("asarray")(b, py::arg("dtype") = "float64"));
  const DoubleArray x = ab[0].cast<DoubleArray>(), y = ab[1].cast<DoubleArray>();  // contiguous copies of the broadcast views
  py::array_t<double> r(x.request().shape);
  double* out = r.mutable_data();
  for (py::ssize_t i = 0; i < x.size(); ++i) out[i] = f(x.data()[i], y.data()[i]);
  return r;
}

/// The internal displacements q of a state as a numpy array of kMaxInternal entries [length].
inline py::array_t<double> q_array(const laws::RheologyState& s) {
  py::array_t<double> q(laws::kMaxInternal);
  std::copy(s.q.begin(), s.q.end(), q.mutable_data());
  return q;
}

/// A state from q, a sequence of at most kMaxInternal internal displacements [length]; a
/// LawError naming `what` otherwise (laws.cpp).
laws::RheologyState state_from(const py::object& q, const char* what);

}  // namespace rheodda::python
