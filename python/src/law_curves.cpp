// The law alone from Python, as `rheodda law curve` (docs/guide/python.md): the creep
// and relaxation curves (laws::integrate_curve), the exact responses to a staged
// history (Boltzmann superposition, laws/history.hpp) and one step of a law.
#include <rheodda/laws/accurate_curve.hpp>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>

#include "law_arrays.hpp"
#include "laws.hpp"

namespace rheodda::python {

namespace {

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

/// Binds `name`(law, <what>, t): `exact` (laws::exact_displacement or laws::exact_force) at
/// every time of t [time] (any shape; the result has it) under the staged history <what>;
/// NaN where the law has no exact response.
template <class Exact>
void def_exact(py::module_& m, const char* name, const char* what, Exact exact, const char* doc) {
  m.def(
      name,
      [what, exact](const laws::ContactRheology& law, const py::object& staged, const DoubleArray& t) {
        const laws::StagedHistory h = staged_history(staged, what);
        return map_array(t, [&](double time) {
          return exact(law, h, time).value_or(std::numeric_limits<double>::quiet_NaN());
        });
      },
      py::arg("law"), py::arg(what), py::arg("t"), doc);
}

}  // namespace

void bind_law_curves(py::module_& m) {
  using laws::ContactRheology;
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
  def_exact(m, "exact_displacement", "force", &laws::exact_displacement,
            "Exact total displacement [length] at times t [time] (an array of any shape; the result has it) under "
            "a staged force [force/length, shear stress] (Boltzmann superposition, the seed's eqs. 4-6); NaN where "
            "the law has no exact response");
  def_exact(m, "exact_force", "displacement", &laws::exact_force,
            "Exact force [force/length, shear stress] at times t [time] (an array of any shape) under a staged "
            "displacement [length]; NaN where the law has no closed form");
  m.def(
      "law_step",
      [](const ContactRheology& law, const py::object& q, double dt, double force_start, double force_end,
         const std::string& scheme) {
        const laws::StepConstants k = law.step_constants(dt, scheme_from(scheme));
        laws::RheologyState next;
        const double dd = law.advance(k, state_from(q, "q"), force_start, force_end, next);
        return py::make_tuple(dd, q_array(next));
      },
      py::arg("law"), py::arg("q"), py::arg("dt"), py::arg("force_start"), py::arg("force_end"),
      py::arg("scheme") = "implicit",
      "One step of dt [time] of the law alone from internal displacements q [length], the force going from "
      "force_start to force_end [force/length, shear stress]: (Delta d_c [length], q_new [length])");
}

}  // namespace rheodda::python
