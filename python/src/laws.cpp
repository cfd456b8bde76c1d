// Laws from Python: the registry (names, parameters with units), building a law
// from a dict, its closed forms, single steps and the law-alone curves of
// `rheodda law curve` (laws::integrate_curve), and PythonLaw, the base class of
// laws written in Python.
#include "laws.hpp"

#include <rheodda/laws/accurate_curve.hpp>
#include <rheodda/laws/registry.hpp>

#include <fmt/format.h>

#include <cmath>
#include <optional>

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

laws::RheologyState state_from(const py::object& q, const char* what) {
  laws::RheologyState s;
  const auto v = q.cast<std::vector<double>>();
  if (v.size() > static_cast<std::size_t>(laws::kMaxInternal))
    throw laws::LawError(what, std::string(what) + ": at most " + std::to_string(laws::kMaxInternal) +
                                   " internal displacements, got " + std::to_string(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.q[i] = v[i];
  return s;
}

// What the Python methods return, checked at every call (docs/guide/python.md, "When a
// Python law returns a bad value"): a value that is not a finite number, a
// tuple of the wrong length or a wrong type raises rheodda.PythonLawError
// naming the law, the method, the value and what was expected.
std::string short_repr(const py::handle& v) {
  std::string r = py::repr(v).cast<std::string>();
  if (r.size() > 200) r = r.substr(0, 197) + "...";
  return r;
}

/// `item` as a finite float, or PythonLawError about `whole` (what `method` returned).
double finite_number(const std::string& law, const char* method, const py::handle& item, const py::handle& whole,
                     const std::string& expected) {
  if (py::isinstance<py::str>(item) || py::isinstance<py::bytes>(item) || py::isinstance<py::bool_>(item) ||
      item.is_none())
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

/// f applied to every element of t (any shape), as a new array of that shape.
template <class F>
py::array_t<double> map_array(const py::array_t<double, py::array::c_style | py::array::forcecast>& t, F f) {
  py::array_t<double> r(t.request().shape);
  const double* in = t.data();
  double* out = r.mutable_data();
  for (py::ssize_t i = 0; i < t.size(); ++i) out[i] = f(in[i]);
  return r;
}

/// f of a number as a float, or of every element of an array-like as an array.
template <class F>
py::object map_object(const py::object& t, F f) {
  if (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t)) return py::float_(f(t.cast<double>()));
  return map_array(t.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(), f);
}

/// f(a, b) over numpy's broadcast of a and b (any shapes that broadcast): a
/// float when both are numbers, else an array of the broadcast shape.
template <class F>
py::object map_broadcast(const py::object& a, const py::object& b, F f) {
  const auto is_number = [](const py::object& x) {
    return py::isinstance<py::float_>(x) || py::isinstance<py::int_>(x);
  };
  if (is_number(a) && is_number(b)) return py::float_(f(a.cast<double>(), b.cast<double>()));
  const py::module_ np = py::module_::import("numpy");
  const py::tuple ab = np.attr("broadcast_arrays")(np.attr("asarray")(a, py::arg("dtype") = "float64"),
                                                   np.attr("asarray")(b, py::arg("dtype") = "float64"));
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Array x = ab[0].cast<Array>(), y = ab[1].cast<Array>();  // contiguous copies of the broadcast views
  py::array_t<double> r(x.request().shape);
  double* out = r.mutable_data();
  for (py::ssize_t i = 0; i < x.size(); ++i) out[i] = f(x.data()[i], y.data()[i]);
  return r;
}

py::dict curve_dict(const std::vector<laws::CurveSample>& samples, const char* exact_name) {
  std::vector<double> t, f, d, x;
  for (const auto& s : samples) {
    t.push_back(s.t);
    f.push_back(s.force);
    d.push_back(s.displacement);
    x.push_back(s.exact ? *s.exact : std::numeric_limits<double>::quiet_NaN());
  }
  py::dict r;
  r["t"] = to_numpy(t);
  r["force"] = to_numpy(f);
  r["displacement"] = to_numpy(d);
  r[exact_name] = to_numpy(x);
  return r;
}

}  // namespace

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
            py::array_t<double> qn(laws::kMaxInternal);
            std::copy(next.q.begin(), next.q.end(), qn.mutable_data());
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
  // The law alone, as `rheodda law curve`: with a tolerance, substepped until it holds
  // it (laws/accurate_curve.hpp; rheodda.RunError when it cannot); without, one step of
  // the scheme per dt, and a RunError rather than NaN or infinity when the scheme fails.
  const auto curve = [](const ContactRheology& law, laws::Control control, const laws::StagedHistory& h,
                        double t_end, double dt, const std::string& scheme, const std::optional<double>& tolerance) {
    std::vector<laws::CurveSample> s;
    {
      py::gil_scoped_release release;
      if (tolerance)
        s = laws::integrate_curve_accurate(law, control, h, t_end, dt, scheme_from(scheme), {*tolerance}).samples;
      else
        s = laws::integrate_curve(law, control, h, t_end, dt, scheme_from(scheme));
    }
    if (const std::size_t k = laws::first_non_finite(s); k < s.size())
      throw laws::CurveError(fmt::format("the {} scheme at dt = {:g} gives a {} that is not a finite number at t = {:g}; "
                                         "pass tolerance= (e.g. 1e-6) to substep until the curve is accurate",
                                         scheme, dt, std::isfinite(s[k].force) ? "displacement" : "force", s[k].t));
    return curve_dict(s, "exact");
  };
  m.def(
      "creep_curve",
      [curve](const ContactRheology& law, const py::object& force, double t_end, double dt, const std::string& scheme,
              const std::optional<double>& tolerance) {
        return curve(law, laws::Control::force, staged_history(force, "force"), t_end, dt, scheme, tolerance);
      },
      py::arg("law"), py::arg("force"), py::arg("t_end"), py::arg("dt"), py::arg("scheme") = "implicit",
      py::arg("tolerance") = py::none(),
      "The law alone under a staged force (shear stress) from t = 0 to t_end with step dt "
      "(`rheodda law curve --force`): dict of numpy arrays t, force, displacement (total: F/E1 + creep) and "
      "exact (the closed form; NaN where the law has none). tolerance: each dt in substeps of the scheme until "
      "one step and two half steps agree to it (as the command does; docs/reference/laws.md); None: one step per dt");
  m.def(
      "relaxation_curve",
      [curve](const ContactRheology& law, const py::object& displacement, double t_end, double dt,
              const std::string& scheme, const std::optional<double>& tolerance) {
        return curve(law, laws::Control::displacement, staged_history(displacement, "displacement"), t_end, dt, scheme,
                     tolerance);
      },
      py::arg("law"), py::arg("displacement"), py::arg("t_end"), py::arg("dt"), py::arg("scheme") = "implicit",
      py::arg("tolerance") = py::none(),
      "The law alone under a staged displacement (`rheodda law curve --displacement`): dict of numpy arrays "
      "t, force, displacement and exact (the closed-form force; NaN where none); tolerance as for creep_curve");
  m.def(
      "exact_displacement",
      [](const ContactRheology& law, const py::object& force, const py::array_t<double, py::array::c_style | py::array::forcecast>& t) {
        const auto h = staged_history(force, "force");
        return map_array(t, [&](double time) {
          const auto d = laws::exact_displacement(law, h, time);
          return d ? *d : std::numeric_limits<double>::quiet_NaN();
        });
      },
      py::arg("law"), py::arg("force"), py::arg("t"),
      "Exact total displacement [length] at times t [time] (an array of any shape; the result has it) under a "
      "staged force [force/length, shear stress] (Boltzmann superposition, the seed's eqs. 4-6); NaN where the "
      "law has no exact response");
  m.def(
      "exact_force",
      [](const ContactRheology& law, const py::object& displacement, const py::array_t<double, py::array::c_style | py::array::forcecast>& t) {
        const auto h = staged_history(displacement, "displacement");
        return map_array(t, [&](double time) {
          const auto f = laws::exact_force(law, h, time);
          return f ? *f : std::numeric_limits<double>::quiet_NaN();
        });
      },
      py::arg("law"), py::arg("displacement"), py::arg("t"),
      "Exact force [force/length, shear stress] at times t [time] (an array of any shape) under a staged "
      "displacement [length]; NaN where the law has no closed form");
  m.def(
      "law_step",
      [](const ContactRheology& law, const py::object& q, double dt, double force_start, double force_end,
         const std::string& scheme) {
        const laws::StepConstants k = law.step_constants(dt, scheme_from(scheme));
        laws::RheologyState next;
        const double dd = law.advance(k, state_from(q, "q"), force_start, force_end, next);
        py::array_t<double> qn(laws::kMaxInternal);
        std::copy(next.q.begin(), next.q.end(), qn.mutable_data());
        return py::make_tuple(dd, qn);
      },
      py::arg("law"), py::arg("q"), py::arg("dt"), py::arg("force_start"), py::arg("force_end"),
      py::arg("scheme") = "implicit",
      "One step of dt [time] of the law alone from internal displacements q [length], the force going from "
      "force_start to force_end [force/length, shear stress]: (Delta d_c [length], q_new [length])");
}

}  // namespace rheodda::python
