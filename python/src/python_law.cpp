// PythonLaw, the base class of laws written in Python (docs/guide/python.md, "A law
// written in Python"): its C++ side and the pybind11 trampoline that sends each step
// function to the Python subclass, checking what the subclass returns.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>

#include "laws.hpp"

namespace rheodda::python {

PythonLaw::PythonLaw(std::string name, laws::ParameterValues parameters, int internal_count,
                     std::optional<double> instantaneous_stiffness, bool linear)
    : name_(std::move(name)),
      parameters_(std::move(parameters)),
      internal_count_(internal_count),
      e1_(instantaneous_stiffness),
      linear_(linear) {
  if (internal_count_ < 1 || internal_count_ > laws::kMaxInternal)
    throw laws::LawError("internal_count", "PythonLaw '" + name_ + "': internal_count must be in 1.." +
                                               std::to_string(laws::kMaxInternal));
  if (e1_ && !(*e1_ > 0.0 && std::isfinite(*e1_)))
    throw laws::LawError("instantaneous_stiffness",
                         "PythonLaw '" + name_ + "': instantaneous_stiffness must be > 0 (force/length) or None");
}

laws::StepConstants PythonLaw::step_constants(double dt, laws::Scheme scheme) const {
  laws::StepConstants k;
  k.dt = dt;
  k.scheme = scheme;
  return k;
}

laws::Linearization PythonLaw::linearize(const laws::StepConstants&, const laws::RheologyState&, double,
                                         double) const {
  throw std::logic_error("PythonLaw '" + name_ + "': linearize(k, q, force_start, force_end_guess) is not defined");
}

double PythonLaw::advance(const laws::StepConstants&, const laws::RheologyState&, double, double,
                          laws::RheologyState&) const {
  throw std::logic_error("PythonLaw '" + name_ + "': advance(k, q, force_start, force_end) is not defined");
}

double PythonLaw::creep_closed_form(double, double) const { return std::numeric_limits<double>::quiet_NaN(); }

namespace {

py::tuple state_tuple(const laws::RheologyState& s) { return py::make_tuple(s.q[0], s.q[1], s.q[2], s.q[3]); }

// What the Python methods return, checked at every call (docs/guide/python.md, "When a
// Python law returns a bad value"): a value that is not a finite number, a
// tuple of the wrong length or a wrong type raises rheodda.PythonLawError
// naming the law, the method, the value and what was expected.
std::string short_repr(const py::handle& v) {
  // On one line: a newline and the indentation after it (numpy's repr of a 2-d array) become a space.
  std::string r;
  bool skip = false;
  for (char ch : py::repr(v).cast<std::string>()) {
    if (ch == '\n') {
      r += ' ';
      skip = true;
    } else if (!(skip && ch == ' ')) {
      r += ch;
      skip = false;
    }
  }
  if (r.size() > 200) r = r.substr(0, 197) + "...";
  return r;
}

/// `item` as a finite float, or PythonLawError about `whole` (what `method` returned).
/// A numpy array of one element or more dimensions is not a number (numpy's float() would
/// take one of shape (1,) or (1, 1)): refused as a list of that shape is (float([x]) fails);
/// a numpy scalar or an array of shape () is a number.
double finite_number(const std::string& law, const char* method, const py::handle& item, const py::handle& whole,
                     const std::string& expected) {
  if (py::isinstance<py::str>(item) || py::isinstance<py::bytes>(item) || py::isinstance<py::bool_>(item) ||
      item.is_none() || (py::isinstance<py::array>(item) && py::reinterpret_borrow<py::array>(item).ndim() > 0))
    raise_python_law_error(law, method, short_repr(whole), expected);
  double x = 0.0;
  try {
    x = py::float_(py::reinterpret_borrow<py::object>(item)).cast<double>();
  } catch (py::error_already_set&) {
    raise_python_law_error(law, method, short_repr(whole), expected);
  }
  if (!std::isfinite(x)) raise_python_law_error(law, method, short_repr(whole), expected);
  return x;
}

/// `v` as a sequence (not a text) of `n` items, or PythonLawError.
py::sequence sized(const std::string& law, const char* method, const py::object& v, std::size_t n,
                   const std::string& expected) {
  if (py::isinstance<py::str>(v) || !py::isinstance<py::sequence>(v) || py::len(v) != n)
    raise_python_law_error(law, method, short_repr(v), expected);
  return v.cast<py::sequence>();
}

/// The trampoline: each virtual step function goes to the Python override.
class PyPythonLaw : public PythonLaw {
 public:
  using PythonLaw::PythonLaw;

  laws::StepConstants step_constants(double dt, laws::Scheme scheme) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const PythonLaw*>(this), "step_constants")) {
      const py::object r = f(dt, std::string(laws::scheme_name(scheme)));
      if (!py::isinstance<laws::StepConstants>(r))
        raise_python_law_error(law(), "step_constants", short_repr(r), "a rheodda.StepConstants");
      return r.cast<laws::StepConstants>();
    }
    return PythonLaw::step_constants(dt, scheme);
  }
  laws::Linearization linearize(const laws::StepConstants& k, const laws::RheologyState& old, double fs,
                                double fe) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const PythonLaw*>(this), "linearize")) {
      static const std::string expected = "a tuple (h, c) of two finite numbers: h [length], c [length/force]";
      const py::object r = f(k, state_tuple(old), fs, fe);
      const py::sequence hc = sized(law(), "linearize", r, 2, expected);
      return {finite_number(law(), "linearize", hc[0], r, expected),
              finite_number(law(), "linearize", hc[1], r, expected)};
    }
    return PythonLaw::linearize(k, old, fs, fe);
  }
  double advance(const laws::StepConstants& k, const laws::RheologyState& old, double fs, double fe,
                 laws::RheologyState& next) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const PythonLaw*>(this), "advance")) {
      const std::size_t n = static_cast<std::size_t>(internal_count());
      const std::string expected = "a tuple (delta_creep, q_new): a finite number [length] and a sequence of "
                                   "internal_count = " + std::to_string(n) + " finite numbers [length]";
      const py::object r = f(k, state_tuple(old), fs, fe);
      const py::sequence pair = sized(law(), "advance", r, 2, expected);
      const double dd = finite_number(law(), "advance", pair[0], r, expected);
      const py::object q = pair[1];
      if (py::isinstance<py::str>(q) || !py::isinstance<py::sequence>(q) || py::len(q) != n)
        raise_python_law_error(law(), "advance", short_repr(r), expected);
      const py::sequence qs = q.cast<py::sequence>();
      next = laws::RheologyState{};
      for (std::size_t i = 0; i < n; ++i) next.q[i] = finite_number(law(), "advance", qs[i], r, expected);
      return dd;
    }
    return PythonLaw::advance(k, old, fs, fe, next);
  }
  double creep_closed_form(double force, double t) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const PythonLaw*>(this), "creep_closed_form")) {
      const py::object r = f(force, t);
      return finite_number(law(), "creep_closed_form", r, r, "a finite number [length]");
    }
    return PythonLaw::creep_closed_form(force, t);
  }
  std::optional<double> relaxation_modulus(double t) const override {
    py::gil_scoped_acquire gil;
    if (py::function f = py::get_override(static_cast<const PythonLaw*>(this), "relaxation_modulus")) {
      const py::object r = f(t);
      if (r.is_none()) return std::nullopt;
      return finite_number(law(), "relaxation_modulus", r, r, "a finite number [force/length] or None");
    }
    return PythonLaw::relaxation_modulus(t);
  }

 private:
  std::string law() const { return std::string(name()); }
};

}  // namespace

void bind_python_law(py::module_& m) {
  using laws::ContactRheology;
  py::class_<PythonLaw, ContactRheology, PyPythonLaw, std::shared_ptr<PythonLaw>>(
      m, "PythonLaw",
      "Base class of a law written in Python. Subclass it, call PythonLaw.__init__(self, name, parameters, "
      "internal_count, instantaneous_stiffness, linear) and define linearize(k, q, force_start, "
      "force_end_guess) -> (h, c) and advance(k, q, force_start, force_end) -> (delta_creep, q_new); "
      "optionally step_constants(dt, scheme) -> StepConstants, creep_closed_form(force, t), "
      "relaxation_modulus(t).")
      .def(py::init([](std::string name, const py::dict& parameters, int internal_count,
                       std::optional<double> e1, bool linear) {
             return std::make_shared<PyPythonLaw>(std::move(name), parameter_values(parameters), internal_count, e1,
                                                  linear);
           }),
           py::arg("name"), py::arg("parameters") = py::dict(), py::arg("internal_count") = 1,
           py::arg("instantaneous_stiffness") = py::none(), py::arg("linear") = true)
      .def("__repr__",
           [](const py::object& self) {
             return fmt::format("<PythonLaw '{}' ({}) {}>", self.cast<const PythonLaw&>().name(),
                                py::str(py::type::of(self).attr("__qualname__")).cast<std::string>(),
                                py::repr(self.attr("parameters")).cast<std::string>());
           })
      // The declared parameters, each read from the instance's attribute of that name when it has
      // one: a change of self.eta1 shows here (the names and the others as given to __init__).
      .def_property_readonly(
          "parameters",
          [](const py::object& self) {
            py::dict d;
            for (const auto& [k, v] : self.cast<const PythonLaw&>().parameters()) {
              const py::object now = py::getattr(self, k.c_str(), py::none());
              d[py::str(k)] = now.is_none() ? py::cast(v) : py::float_(now);
            }
            return d;
          },
          "The parameters by name: the instance's attribute of that name where it has one (so changes "
          "show), else the value given to __init__ [the law's units]");
}

}  // namespace rheodda::python
