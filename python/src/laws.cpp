// Laws from Python: the registry (names, parameters with units), building a law
// from a dict, and the Law class (its closed forms over numpy arrays, single
// steps). A law written in Python (PythonLaw) is in python_law.cpp, the law-alone
// curves of `rheodda law curve` in law_curves.cpp.
#include "laws.hpp"

#include <rheodda/laws/registry.hpp>

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "law_arrays.hpp"

namespace rheodda::python {

namespace {

py::dict law_info(const laws::LawInfo& info) {
  py::dict d;
  d["name"] = info.name;
  d["summary"] = info.summary;
  d["equation"] = info.equation;
  py::list ps;
  for (const auto& p : info.parameters) {
    py::dict e;
    e["name"] = p.name;
    e["unit"] = p.unit;
    e["meaning"] = p.meaning;
    e["min"] = p.min;
    e["min_exclusive"] = p.min_exclusive;
    e["max"] = p.max;
    e["default"] = p.default_value ? py::cast(*p.default_value) : py::none();
    e["range"] = p.range_text();
    ps.append(e);
  }
  d["parameters"] = ps;
  return d;
}

}  // namespace

laws::RheologyState state_from(const py::object& q, const char* what) {
  laws::RheologyState s;
  const auto v = q.cast<std::vector<double>>();
  if (v.size() > static_cast<std::size_t>(laws::kMaxInternal))
    throw laws::LawError(what, std::string(what) + ": at most " + std::to_string(laws::kMaxInternal) +
                                   " internal displacements, got " + std::to_string(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.q[i] = v[i];
  return s;
}

laws::ParameterValues parameter_values(const py::dict& d) {
  laws::ParameterValues v;
  for (auto item : d) {
    const auto key = item.first.cast<std::string>();
    try {
      v[key] = item.second.cast<double>();
    } catch (const py::cast_error&) {
      throw laws::LawError(key, key + ": '" + py::str(item.second).cast<std::string>() + "' is not a number");
    }
  }
  return v;
}


laws::StagedHistory staged_history(const py::object& value, const char* what) {
  if (py::isinstance<py::str>(value)) return laws::StagedHistory::parse(value.cast<std::string>(), what);
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value))
    return laws::StagedHistory({{0.0, value.cast<double>()}});
  std::vector<laws::StagedHistory::Stage> stages;
  try {
    for (const auto& p : value.cast<std::vector<std::pair<double, double>>>()) stages.push_back({p.first, p.second});
  } catch (const py::cast_error&) {
    throw laws::LawError(what, std::string(what) +
                                   ": expected a number, a text 'T:V[,T:V...]' or a list of (t, value) pairs");
  }
  return laws::StagedHistory(std::move(stages));
}

laws::Scheme scheme_from(const std::string& name) { return laws::parse_scheme(name); }

void bind_laws(py::module_& m) {
  using laws::ContactRheology;

  py::class_<laws::UnitStepConstants>(m, "UnitStepConstants",
                                      "Constants of one creep element for one step (laws/contact_rheology.hpp, eq. 2)")
      .def(py::init<>())
      .def_readwrite("b", &laws::UnitStepConstants::b, "1 - exp(-dt E/eta) of a Kelvin element [-]")
      .def_readwrite("phi", &laws::UnitStepConstants::phi, "1 - b/r, r = dt E/eta: weight of the force ramp [-]")
      .def_readwrite("dt_over_eta", &laws::UnitStepConstants::dt_over_eta,
                     "dt/eta of the element's dashpot [length/force]")
      .def_readwrite("per_q", &laws::UnitStepConstants::per_q,
                     "coefficient of the old q in Delta q = per_q q + per_start g(F_s) + per_end g(F_e) [-]")
      .def_readwrite("per_start", &laws::UnitStepConstants::per_start,
                     "coefficient of g(F_s), the step's start force [length/force]")
      .def_readwrite("per_end", &laws::UnitStepConstants::per_end,
                     "coefficient of g(F_e), the step's end force [length/force]")
      .def_readwrite("threshold", &laws::UnitStepConstants::threshold,
                     "the Bingham element's threshold Fs [force/length, stress]")
      .def_readwrite("bingham", &laws::UnitStepConstants::bingham, "the element is a Bingham (threshold) dashpot")
      .def("__repr__", [](const laws::UnitStepConstants& u) {
        return fmt::format("<UnitStepConstants b {:g} phi {:g} dt_over_eta {:g} per_q {:g} per_start {:g} per_end {:g}"
                           "{}>",
                           u.b, u.phi, u.dt_over_eta, u.per_q, u.per_start, u.per_end,
                           u.bingham ? fmt::format(" threshold {:g}", u.threshold) : std::string());
      });

  py::class_<laws::StepConstants>(m, "StepConstants",
                                  "What a law computes once per step size and scheme: dt [time], scheme, and "
                                  "up to 4 element constants (unit)")
      .def(py::init([](double dt, const std::string& scheme) {
             laws::StepConstants k;
             k.dt = dt;
             k.scheme = scheme_from(scheme);
             return k;
           }),
           py::arg("dt") = 0.0, py::arg("scheme") = "implicit")
      .def_readwrite("dt", &laws::StepConstants::dt, "the step size [time]")
      .def_property(
          "scheme", [](const laws::StepConstants& k) { return std::string(laws::scheme_name(k.scheme)); },
          [](laws::StepConstants& k, const std::string& s) { k.scheme = scheme_from(s); },
          "the scheme: 'lagged', 'implicit' or 'exponential-linear'")
      .def_readwrite("count", &laws::StepConstants::count, "number of element constants in unit [-]")
      .def_property(
          "unit",
          [](const laws::StepConstants& k) {
            return std::vector<laws::UnitStepConstants>(k.unit.begin(), k.unit.end());
          },
          [](laws::StepConstants& k, const std::vector<laws::UnitStepConstants>& u) {
            if (u.size() > k.unit.size())
              throw laws::LawError("unit", "StepConstants.unit: at most " + std::to_string(k.unit.size()) +
                                               " elements");
            k.unit = {};
            std::copy(u.begin(), u.end(), k.unit.begin());
            k.count = static_cast<int>(u.size());
          },
          "the element constants (UnitStepConstants), at most 4; setting them sets count")
      .def("__repr__", [](const laws::StepConstants& k) {
        return fmt::format("<StepConstants dt {:g} scheme '{}' with {} element constant{}>", k.dt,
                           laws::scheme_name(k.scheme), k.count, k.count == 1 ? "" : "s");
      });

  py::class_<ContactRheology, std::shared_ptr<ContactRheology>>(
      m, "Law",
      "A contact rheology law (laws/contact_rheology.hpp): parameters per unit joint area; force = shear "
      "stress, displacement = shear displacement. Build one with rheodda.law(name, {param: value}).")
      .def_property_readonly("name", [](const ContactRheology& l) { return std::string(l.name()); },
                             "the law's registry name, e.g. 'burgers'")
      // pickle and copy: a built-in law is its name and parameters, made again by rheodda.law.
      // A law written in Python is its subclass's to pickle (define __reduce__ there).
      .def("__reduce__",
           [](const py::object& self) {
             if (!self.get_type().is(py::type::of<ContactRheology>()))
               throw py::type_error(fmt::format(
                   "cannot pickle the law written in Python '{}' ({}): define __reduce__ in its class",
                   self.cast<const ContactRheology&>().name(),
                   py::str(self.get_type().attr("__qualname__")).cast<std::string>()));
             const auto& l = self.cast<const ContactRheology&>();
             py::dict p;
             for (const auto& [k, v] : l.parameters()) p[py::str(k)] = v;
             return py::make_tuple(py::module_::import("rheodda._scripting").attr("_make_law"),
                                   py::make_tuple(std::string(l.name()), p));
           })
      .def_property_readonly(
          "parameters",
          [](const ContactRheology& l) {
            return std::map<std::string, double>(l.parameters().begin(), l.parameters().end());
          },
          "the parameters by name [their units: rheodda.law_info(name)['parameters']]")
      .def_property_readonly("internal_count", &ContactRheology::internal_count,
                             "number of internal displacements q the law keeps per contact (1..4)")
      .def_property_readonly("instantaneous_stiffness", &ContactRheology::instantaneous_stiffness,
                             "E1, the instantaneous shear stiffness [force/length per length], or None")
      .def_property_readonly("is_linear", &ContactRheology::is_linear,
                             "True when the creep increment is affine in the force (not 'nonlinear')")
      .def_property_readonly(
          "linearity",
          [](const ContactRheology& l) {
            switch (l.linearity()) {
              case laws::Linearity::affine: return std::string("affine");
              case laws::Linearity::piecewise_affine: return std::string("piecewise-affine");
              case laws::Linearity::nonlinear: return std::string("nonlinear");
            }
            return std::string("?");
          },
          "'affine', 'piecewise-affine' or 'nonlinear' (linearize returns the tangent; docs/reference/laws.md)")
      .def(
          "failure_time",
          [](const ContactRheology& l, const py::object& force) {
            return map_object(force, [&](double f) {
              const auto t = l.failure_time(f);
              return t ? *t : std::numeric_limits<double>::infinity();
            });
          },
          py::arg("force"),
          "Failure time under a constant force [force/length, shear stress] from an intact state [time] "
          "(damage laws: t_f = t_r (tau_ref/|F|)^r); inf for laws that do not fail. force: a number or an "
          "array (the result has its shape)")
      .def_property_readonly("linear_limit", &ContactRheology::linear_limit,
                             "the force below which the law is linear [force/length, stress]; inf for linear laws")
      .def("creep_closed_form",
           [](const ContactRheology& l, const py::object& force, const py::object& t) {
             return map_broadcast(force, t, [&](double f, double x) { return l.creep_closed_form(f, x); });
           },
           py::arg("force"), py::arg("t"),
           "Closed-form creep displacement [length] (without the instantaneous spring) at time t [time] under a "
           "constant force F [force/length, shear stress] from t = 0. force and t: numbers or arrays that "
           "broadcast together (numpy rules); the result has the broadcast shape, a float for two numbers")
      .def("displacement_closed_form",
           [](const ContactRheology& l, const py::object& force, const py::object& t) {
             return map_broadcast(force, t, [&](double f, double x) { return l.displacement_closed_form(f, x); });
           },
           py::arg("force"), py::arg("t"),
           "F/E1 + creep_closed_form(F, t) [length]; force [force/length] and t [time] broadcast as in "
           "creep_closed_form")
      .def("relaxation_modulus",
           [](const ContactRheology& l, const py::object& t) {
             return map_object(t, [&](double x) {
               const auto g = l.relaxation_modulus(x);
               return g ? *g : std::numeric_limits<double>::quiet_NaN();
             });
           },
           py::arg("t"),
           "Relaxation modulus G(t) [force/length per length of displacement] at times t [time] (a number or "
           "an array of any shape); NaN where the law has no closed form")
      .def(
          "step_constants",
          [](const ContactRheology& l, double dt, const std::string& scheme) {
            return l.step_constants(dt, scheme_from(scheme));
          },
          py::arg("dt"), py::arg("scheme") = "implicit",
          "The law's constants for a step of dt [time] under a scheme (a StepConstants)")
      .def(
          "linearize",
          [](const ContactRheology& l, const laws::StepConstants& k, const py::object& q, double fs, double fe,
             double damage) {
            laws::RheologyState st = state_from(q, "q");
            st.damage = damage;
            const laws::Linearization lin = l.linearize(k, st, fs, fe);
            return py::make_tuple(lin.h, lin.c);
          },
          py::arg("k"), py::arg("q"), py::arg("force_start"), py::arg("force_end_guess"), py::arg("damage") = 0.0,
          "Affine form of the step's creep increment: (h [length], c [length/force]), Delta d_c = h + c F_e "
          "(the tangent at force_end_guess for a nonlinear law); damage: the damage D of a damage law [-]")
      .def(
          "advance",
          [](const ContactRheology& l, const laws::StepConstants& k, const py::object& q, double fs, double fe,
             double damage) -> py::tuple {
            laws::RheologyState st = state_from(q, "q"), next;
            st.damage = damage;
            const double dd = l.advance(k, st, fs, fe, next);
            const py::array_t<double> qn = q_array(next);
            // A damage law also returns its new damage, which the next step needs.
            if (l.failure_time(1.0)) return py::make_tuple(dd, qn, next.damage);
            return py::make_tuple(dd, qn);
          },
          py::arg("k"), py::arg("q"), py::arg("force_start"), py::arg("force_end"), py::arg("damage") = 0.0,
          "One step from state q (internal displacements [length]): (Delta d_c [length], q_new as a numpy "
          "array); a damage law (damage-burgers) takes its damage D and returns (Delta d_c, q_new, D_new), "
          "D_new = 1 at failure")
      .def("__repr__", [](const ContactRheology& l) {
        std::string s = "rheodda.law('" + std::string(l.name()) + "', {";
        bool first = true;
        for (const auto& [k, v] : l.parameters()) {
          s += (first ? "'" : ", '") + k + "': " + py::repr(py::float_(v)).cast<std::string>();
          first = false;
        }
        return s + "})";
      });

  m.def(
      "laws",
      [] {
        py::list r;
        for (const auto& info : laws::LawRegistry::builtin().laws()) r.append(law_info(info));
        return r;
      },
      "The built-in laws (`rheodda law list`): name, summary, equation, parameters (name, unit, meaning, "
      "range, default)");
  m.def(
      "law",
      [](const std::string& name, const py::object& parameters, const py::kwargs& kw) {
        py::dict d;
        if (!parameters.is_none()) d = py::dict(parameters);
        for (auto item : kw) d[item.first] = item.second;
        return std::shared_ptr<ContactRheology>(laws::LawRegistry::builtin().create(name, parameter_values(d)));
      },
      py::arg("name"), py::arg("parameters") = py::none(),
      "Builds a registered law from its parameters (a dict and/or keywords), validated as in a scene; "
      "raises rheodda.LawError with the message of `rheodda law curve`");
}

}  // namespace rheodda::python
