// Fitting laws to creep curves from Python (laws/fit: fit::fit_law, fit::fit_all,
// the CSV reader of `rheodda fit`). The result object is fit::FitResult as it is;
// the covariance of the values and the YAML block are derived in Python
// (python/rheodda/__init__.py) from its public fields.
#include <rheodda/fit/creep_data.hpp>
#include <rheodda/fit/fit.hpp>
#include <rheodda/fit/profile.hpp>
#include <rheodda/laws/registry.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <optional>
#include <sstream>

#include "laws.hpp"

namespace rheodda::python {
namespace {

/// def_readonly(name, field) for each (name, field) pair: the library's fields as they are.
template <class C, class... T>
void readonly_fields(py::class_<C>& c, std::pair<const char*, T C::*>... fields) {
  (c.def_readonly(fields.first, fields.second), ...);
}

fit::CreepData data_from_arrays(const std::vector<double>& t, const std::vector<double>& d,
                                const py::object& stress, const std::string& source,
                                const std::optional<std::vector<double>>& sigma) {
  // Through the CSV parser, so arrays get the very checks (and messages) a file gets.
  if (t.size() != d.size())
    throw fit::DataError(source, 0, "displacement",
                         "t has " + std::to_string(t.size()) + " values, displacement " + std::to_string(d.size()));
  if (sigma && sigma->size() != t.size())
    throw fit::DataError(source, 0, "sigma",
                         "t has " + std::to_string(t.size()) + " values, sigma " + std::to_string(sigma->size()));
  std::string text = sigma ? "t,displacement,sigma\n" : "t,displacement\n";
  char buf[64];
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g,", t[i]);
    text += buf;
    std::snprintf(buf, sizeof buf, sigma ? "%.17g," : "%.17g\n", d[i]);
    text += buf;
    if (sigma) {
      std::snprintf(buf, sizeof buf, "%.17g\n", (*sigma)[i]);
      text += buf;
    }
  }
  fit::CsvOptions o;
  if (sigma) o.sigma_column = "sigma";
  o.stress = staged_history(stress, "stress");
  std::istringstream in(text);
  return fit::parse_creep_csv(in, source, o);
}

// `settings`: {name: {"value": float or None, "vary": bool, "min": float, "max": float, "expr": str}}
// as rheodda.fit builds it from params= (python/rheodda/__init__.py).
fit::FitOptions options_from(int restarts, int max_iterations, const py::dict& settings, bool scale_covariance) {
  fit::FitOptions o;
  o.restarts = restarts;
  o.max_iterations = max_iterations;
  o.scale_covariance = scale_covariance;
  for (const auto& [key, item] : settings) {
    const auto d = item.cast<py::dict>();
    fit::ParameterSetting p;
    if (!d["value"].is_none()) p.value = d["value"].cast<double>();
    p.vary = d["vary"].cast<bool>();
    p.min = d["min"].cast<double>();
    p.max = d["max"].cast<double>();
    if (d.contains("expr") && !d["expr"].is_none()) p.expr = d["expr"].cast<std::string>();
    o.parameters[key.cast<std::string>()] = p;
  }
  return o;
}

}  // namespace

void bind_fit(py::module_& m) {
  py::class_<fit::CreepData>(m, "CreepData", "A creep curve ready to fit (fit/creep_data.hpp)")
      .def_readonly("source", &fit::CreepData::source, "the file name (or '<arrays>') used in messages")
      .def_property_readonly("t", [](const fit::CreepData& d) { return read_only(to_numpy(d.t)); },
                             "times of the points [time] (read-only)")
      .def_property_readonly("displacement",
                             [](const fit::CreepData& d) { return read_only(to_numpy(d.displacement)); },
                             "total shear displacement of the points [length] (read-only)")
      .def_property_readonly("stress",
                             [](const fit::CreepData& d) {
                               const auto& st = d.history.stages();
                               py::array_t<double> a({static_cast<py::ssize_t>(st.size()), py::ssize_t{2}});
                               auto w = a.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < st.size(); ++i) {
                                 w(i, 0) = st[i].t;
                                 w(i, 1) = st[i].value;
                               }
                               return read_only(a);
                             },
                             "the stress stages as rows (t [time], shear stress [stress]), shape (stages, 2) "
                             "(read-only)")
      .def_readonly("time_column", &fit::CreepData::time_column, "the CSV column read as time")
      .def_readonly("displacement_column", &fit::CreepData::displacement_column,
                    "the CSV column read as shear displacement")
      .def_readonly("stress_column", &fit::CreepData::stress_column,
                    "the CSV column read as shear stress ('' when the stress was given for the file)")
      .def_readonly("sigma_column", &fit::CreepData::sigma_column,
                    "the CSV column read as sigma ('' when none)")
      .def_property_readonly("sigma", [](const fit::CreepData& d) -> py::object {
        if (d.sigma.empty()) return py::none();
        return read_only(to_numpy(d.sigma));
      }, "measurement standard deviation of each point [length], None when not given (read-only)")
      .def("_with_sigma", [](const fit::CreepData& d, const std::vector<double>& sigma) {
        if (sigma.size() != d.t.size())
          throw fit::DataError(d.source, 0, "sigma", "the data have " + std::to_string(d.t.size()) +
                                                         " points, sigma " + std::to_string(sigma.size()) + " values");
        fit::CreepData out = d;
        out.sigma = sigma;
        return out;
      })
      .def("__len__", [](const fit::CreepData& d) { return d.t.size(); }, "the number of points")
      .def("__repr__", [](const fit::CreepData& d) {
        return fmt::format("<CreepData {}: {} points, {} stage{}, t from {:g} to {:g}{}>", d.source, d.t.size(),
                           d.stages.size(), d.stages.size() == 1 ? "" : "s", d.t.empty() ? 0.0 : d.t.front(),
                           d.t.empty() ? 0.0 : d.t.back(), d.sigma.empty() ? "" : ", with sigma");
      });

  py::class_<fit::ParameterEstimate>(m, "ParameterEstimate", "One fitted parameter (fit/fit.hpp)")
      .def_readonly("name", &fit::ParameterEstimate::name, "registry name, e.g. 'eta1'")
      .def_readonly("unit", &fit::ParameterEstimate::unit, "registry dimension, e.g. 'stress*time/length'")
      .def_readonly("value", &fit::ParameterEstimate::value, "the fitted value [unit]")
      .def_readonly("std_error", &fit::ParameterEstimate::std_error,
                    "standard error by the delta method [unit]; 0 when not identifiable, fixed or on a bound")
      .def_readonly("identifiable", &fit::ParameterEstimate::identifiable,
                    "False when the data do not fix it (docs/guide/fitting.md, 'Identifiability')")
      .def_readonly("reason", &fit::ParameterEstimate::reason, "why it is not identifiable; '' if it is")
      .def_readonly("vary", &fit::ParameterEstimate::vary, "False: held at its given value (params vary=False)")
      .def_readonly("at_bound", &fit::ParameterEstimate::at_bound,
                    "'min' or 'max' when the fit ended on that bound, else ''")
      .def_readonly("min", &fit::ParameterEstimate::min, "lower bound of the fit [unit] (0: none)")
      .def_readonly("max", &fit::ParameterEstimate::max, "upper bound of the fit [unit] (inf: none)")
      .def_readonly("expr", &fit::ParameterEstimate::expr,
                    "the expression of the other parameters that gives it (params expr=); '' if none")
      .def("__repr__", [](const fit::ParameterEstimate& p) {
        return "<" + p.name + " = " + py::repr(py::float_(p.value)).cast<std::string>() + " +- " +
               py::repr(py::float_(p.std_error)).cast<std::string>() + " " + p.unit +
               (p.identifiable ? "" : " (not identifiable)") + ">";
      });

  py::class_<fit::FixedCombination>(m, "FixedCombination",
                                    "A combination of parameters the data fix although some of its parts are "
                                    "not identifiable (docs/guide/fitting.md, \"Identifiability\")")
      .def_readonly("expression", &fit::FixedCombination::expression, "e.g. '(0.232 - Fs)/eta3'")
      .def_readonly("unit", &fit::FixedCombination::unit, "its dimension, e.g. 'length/time'")
      .def_readonly("value", &fit::FixedCombination::value, "its value [unit]")
      .def_readonly("std_error", &fit::FixedCombination::std_error, "its standard error [unit]")
      .def_readonly("parameters", &fit::FixedCombination::parameters, "the parameters it involves")
      .def("__repr__", [](const fit::FixedCombination& c) {
        return "<" + c.expression + " = " + py::repr(py::float_(c.value)).cast<std::string>() + " +- " +
               py::repr(py::float_(c.std_error)).cast<std::string>() + " " + c.unit + ">";
      });

  using R = fit::FitResult;
  py::class_<R> result(m, "_FitResult", "fit::FitResult as the library returns it; rheodda.FitResult wraps it");
  readonly_fields(result, std::pair{"law", &R::law}, std::pair{"parameters", &R::parameters},
                  std::pair{"points", &R::points}, std::pair{"rss", &R::rss},
                  std::pair{"chi_square", &R::chi_square}, std::pair{"reduced_chi_square", &R::reduced_chi_square},
                  std::pair{"varying", &R::varying}, std::pair{"weighted", &R::weighted},
                  std::pair{"scale_covariance", &R::scale_covariance}, std::pair{"r2", &R::r2},
                  std::pair{"rmse", &R::rmse}, std::pair{"aic", &R::aic}, std::pair{"bic", &R::bic},
                  std::pair{"iterations", &R::iterations}, std::pair{"starts", &R::starts},
                  std::pair{"starts_agreeing", &R::starts_agreeing}, std::pair{"converged", &R::converged},
                  std::pair{"optimality", &R::optimality},
                  std::pair{"structured_starts", &R::structured_starts},
                  std::pair{"minimum_certain", &R::minimum_certain}, std::pair{"minimum_note", &R::minimum_note},
                  std::pair{"combinations", &R::combinations}, std::pair{"warnings", &R::warnings});
  result
      .def_property_readonly("correlation",
                             [](const R& r) {
                               const auto n = static_cast<py::ssize_t>(r.parameters.size());
                               py::array_t<double> a({n, n});
                               std::copy(r.correlation.begin(), r.correlation.end(), a.mutable_data());
                               return a;
                             })
      .def_property_readonly("start_minima", [](const R& r) { return to_numpy(r.start_minima); })
      .def_property_readonly("singular_values", [](const R& r) { return to_numpy(r.singular_values); })
      .def_property_readonly("fitted", [](const R& r) { return to_numpy(r.fitted); });

  m.def(
      "read_creep_csv",
      [](const std::string& path, const std::string& time_column, const std::string& displacement_column,
         const std::string& stress_column, const py::object& stress, const std::string& sigma_column) {
        fit::CsvOptions o;
        o.time_column = time_column;
        o.displacement_column = displacement_column;
        o.stress_column = stress_column;
        o.sigma_column = sigma_column;
        if (!stress.is_none()) o.stress = staged_history(stress, "--stress");
        return fit::read_creep_csv(path, o);
      },
      py::arg("path"), py::arg("time_column") = "t", py::arg("displacement_column") = "displacement",
      py::arg("stress_column") = "", py::arg("stress") = py::none(), py::arg("sigma_column") = "",
      "Reads a creep curve CSV as `rheodda fit` does (docs/guide/fitting.md); raises rheodda.DataError");
  m.def(
      "creep_data",
      [](const std::vector<double>& t, const std::vector<double>& displacement, const py::object& stress,
         const std::string& source, const std::optional<std::vector<double>>& sigma) {
        return data_from_arrays(t, displacement, stress, source, sigma);
      },
      py::arg("t"), py::arg("displacement"), py::arg("stress"), py::arg("source") = "<arrays>",
      py::arg("sigma") = py::none(),
      "A creep curve from arrays: t [time], total displacement [length], stress: a number, "
      "'T:V[,T:V...]' or (t, value) pairs [stress]; sigma: each point's measurement standard "
      "deviation [length] (optional)");
  m.def(
      "_fit_law",
      [](const std::string& law, const fit::CreepData& data, int restarts, int max_iterations,
         const py::dict& settings, bool scale_covariance) {
        const laws::LawInfo& info = laws::LawRegistry::builtin().get(law);
        const auto options = options_from(restarts, max_iterations, settings, scale_covariance);
        py::gil_scoped_release release;
        return fit::fit_law(info, data, options);
      },
      py::arg("law"), py::arg("data"), py::arg("restarts") = 4, py::arg("max_iterations") = 500,
      py::arg("settings") = py::dict(), py::arg("scale_covariance") = true);
  m.def(
      "_profile",
      [](const std::string& law, const fit::CreepData& data, int restarts, int max_iterations,
         const py::dict& settings, bool scale_covariance, const fit::FitResult& best,
         const std::vector<double>& sigmas, const std::vector<std::string>& names) {
        const laws::LawInfo& info = laws::LawRegistry::builtin().get(law);
        const auto options = options_from(restarts, max_iterations, settings, scale_covariance);
        std::vector<fit::ProfileInterval> r;
        {
          py::gil_scoped_release release;
          r = fit::profile_intervals(info, data, options, best, sigmas, names);
        }
        py::list out;
        for (const auto& pi : r) {
          py::list levels;
          for (const auto& l : pi.levels)
            levels.append(py::dict(py::arg("sigma") = l.sigma, py::arg("probability") = l.probability,
                                   py::arg("chi_square") = l.chi_square, py::arg("lower") = l.lower,
                                   py::arg("upper") = l.upper, py::arg("lower_found") = l.lower_found,
                                   py::arg("upper_found") = l.upper_found));
          out.append(py::dict(py::arg("name") = pi.name, py::arg("value") = pi.value, py::arg("levels") = levels,
                              py::arg("fits") = pi.fits));
        }
        return out;
      },
      py::arg("law"), py::arg("data"), py::arg("restarts"), py::arg("max_iterations"), py::arg("settings"),
      py::arg("scale_covariance"), py::arg("best"), py::arg("sigmas"), py::arg("names"));
  // The choice of a law (laws/fit/src/model_choice.cpp): _fitting.py's model_weights, yaml.
  m.def("_model_weights", &fit::model_weights, py::arg("criterion"),
        "w_i = exp(-Delta_i/2) / sum_j exp(-Delta_j/2) of criterion values (Akaike weights on AIC; "
        "Burnham & Anderson 2002)");
  m.def("_unidentified", &fit::unidentified_parameters, py::arg("result"),
        "the names of the parameters the fit leaves undetermined");
  m.def(
      "_tested_range",
      [](const fit::CreepData& d) {
        const fit::TestedRange r = fit::tested_range(d);
        return py::make_tuple(r.stress_min, r.stress_max, r.duration);
      },
      py::arg("data"), "(lowest, highest) |stress| of the loading stages [stress], the test's duration [time]");
  m.def(
      "_fit_all",
      [](const fit::CreepData& data, const std::string& rank_by, int restarts, int max_iterations,
         const py::dict& settings, bool scale_covariance) {
        if (rank_by != "aic" && rank_by != "bic")
          throw laws::LawError("rank_by", "rank_by: '" + rank_by + "' is not one of aic, bic");
        std::vector<std::string> skipped;
        std::vector<fit::FitResult> r;
        const auto options = options_from(restarts, max_iterations, settings, scale_covariance);
        {
          py::gil_scoped_release release;
          r = fit::fit_all(laws::LawRegistry::builtin(), data, rank_by == "aic" ? fit::Criterion::aic : fit::Criterion::bic,
                           skipped, options);
        }
        return py::make_tuple(r, skipped);
      },
      py::arg("data"), py::arg("rank_by") = "bic", py::arg("restarts") = 4, py::arg("max_iterations") = 500,
      py::arg("settings") = py::dict(), py::arg("scale_covariance") = true);
}

}  // namespace rheodda::python
