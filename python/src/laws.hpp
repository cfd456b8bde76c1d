// The law part of the module: the bound law classes (laws.cpp), the law-alone curves
// (law_curves.cpp) and the Python-written law (PythonLaw, subclassed in Python through
// a pybind11 trampoline: python_law.cpp).
#pragma once

#include <rheodda/laws/contact_rheology.hpp>
#include <rheodda/laws/history.hpp>

#include <limits>
#include <optional>
#include <string>

#include "common.hpp"

namespace rheodda::python {

/// A law whose step functions are written in Python (docs/guide/python.md, "A law
/// written in Python"). The C++ side stores what the host asks once (name,
/// parameters, slots, E1, linearity); the trampoline PyPythonLaw sends
/// step_constants, linearize, advance, creep_closed_form and
/// relaxation_modulus to the Python subclass, taking the GIL for each call.
class PythonLaw : public laws::ContactRheology {
 public:
  PythonLaw(std::string name, laws::ParameterValues parameters, int internal_count,
            std::optional<double> instantaneous_stiffness, bool linear);

  std::string_view name() const override { return name_; }
  const laws::ParameterValues& parameters() const override { return parameters_; }
  int internal_count() const override { return internal_count_; }
  std::optional<double> instantaneous_stiffness() const override { return e1_; }
  bool is_linear() const override { return linear_; }

  /// Default: {dt, scheme} and no element constants (the Python methods then
  /// compute what they need from k.dt).
  laws::StepConstants step_constants(double dt, laws::Scheme scheme) const override;
  laws::Linearization linearize(const laws::StepConstants& k, const laws::RheologyState& old,
                                double force_start, double force_end_guess) const override;
  double advance(const laws::StepConstants& k, const laws::RheologyState& old, double force_start,
                 double force_end, laws::RheologyState& next) const override;
  /// Default: NaN (no closed form given).
  double creep_closed_form(double force, double t) const override;

 private:
  std::string name_;
  laws::ParameterValues parameters_;
  int internal_count_;
  std::optional<double> e1_;
  bool linear_;
};

/// A staged history from a Python value: a number (constant from t = 0), a
/// text "T:V[,T:V...]" or a sequence of (t, value) pairs. `what` names it in errors.
laws::StagedHistory staged_history(const py::object& value, const char* what);

/// Law parameters from a dict {name: number}; a LawError naming the key that is not a number.
laws::ParameterValues parameter_values(const py::dict& d);

/// A scheme from its name ("lagged", "implicit", "exponential-linear"); LawError otherwise.
laws::Scheme scheme_from(const std::string& name);

}  // namespace rheodda::python
