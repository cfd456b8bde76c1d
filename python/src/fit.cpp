// Fitting laws to creep curves from Python (laws/fit: fit::fit_law, fit::fit_all,
// the CSV reader of `rheodda fit`). The result object is fit::FitResult as it is;
// the covariance of the values and the YAML block are derived in Python
// (python/rheodda/__init__.py) from its public fields.
#include <rheodda/fit/creep_data.hpp>
#include <rheodda/fit/fit.hpp>
#include <rheodda/laws/registry.hpp>

#include <cstdio>
#include <sstream>

#include "laws.hpp"

namespace rheodda::python {
namespace {

fit::CreepData data_from_arrays(const std::vector<double>& t, const std::vector<double>& d,
                                const py::object& stress, const std::string& source) {
  // Through the CSV parser, so arrays get the very checks (and messages) a file gets.
  if (t.size() != d.size())
    throw fit::DataError(source, 0, "displacement",
                         "t has " + std::to_string(t.size()) + " values, displacement " + std::to_string(d.size()));
  std::string text = "t,displacement\n";
  char buf[64];
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g,", t[i]);
    text += buf;
    std::snprintf(buf, sizeof buf, "%.17g\n", d[i]);
    text += buf;
  }
  fit::CsvOptions o;
  o.stress = staged_history(stress, "stress");
  std::istringstream in(text);
  return fit::parse_creep_csv(in, source, o);
}

fit::FitOptions options_from(int restarts, int max_iterations) {
  fit::FitOptions o;
  o.restarts = restarts;
  o.max_iterations = max_iterations;
  return o;
}

}  // namespace

void bind_fit(py::module_& m) {
  py::class_<fit::CreepData>(m, "CreepData", "A creep curve ready to fit (fit/creep_data.hpp)")
      .def_readonly("source", &fit::CreepData::source)
      .def_property_readonly("t", [](const fit::CreepData& d) { return to_numpy(d.t); })
      .def_property_readonly("displacement", [](const fit::CreepData& d) { return to_numpy(d.displacement); })
      .def_property_readonly("stress",
                             [](const fit::CreepData& d) {
                               std::vector<std::pair<double, double>> s;
                               for (const auto& st : d.history.stages()) s.emplace_back(st.t, st.value);
                               return s;
                             })
      .def_readonly("time_column", &fit::CreepData::time_column)
      .def_readonly("displacement_column", &fit::CreepData::displacement_column)
      .def_readonly("stress_column", &fit::CreepData::stress_column);

  py::class_<fit::ParameterEstimate>(m, "ParameterEstimate")
      .def_readonly("name", &fit::ParameterEstimate::name)
      .def_readonly("unit", &fit::ParameterEstimate::unit)
      .def_readonly("value", &fit::ParameterEstimate::value)
      .def_readonly("std_error", &fit::ParameterEstimate::std_error)
      .def_readonly("identifiable", &fit::ParameterEstimate::identifiable)
      .def_readonly("reason", &fit::ParameterEstimate::reason)
      .def("__repr__", [](const fit::ParameterEstimate& p) {
        return "<" + p.name + " = " + py::repr(py::float_(p.value)).cast<std::string>() + " +- " +
               py::repr(py::float_(p.std_error)).cast<std::string>() + " " + p.unit +
               (p.identifiable ? "" : " (not identifiable)") + ">";
      });

  py::class_<fit::FixedCombination>(m, "FixedCombination",
                                    "A combination of parameters the data fix although some of its parts are "
                                    "not identifiable (docs/guide/fitting.md, \"Identifiability\")")
      .def_readonly("expression", &fit::FixedCombination::expression)
      .def_readonly("unit", &fit::FixedCombination::unit)
      .def_readonly("value", &fit::FixedCombination::value)
      .def_readonly("std_error", &fit::FixedCombination::std_error)
      .def_readonly("parameters", &fit::FixedCombination::parameters)
      .def("__repr__", [](const fit::FixedCombination& c) {
        return "<" + c.expression + " = " + py::repr(py::float_(c.value)).cast<std::string>() + " +- " +
               py::repr(py::float_(c.std_error)).cast<std::string>() + " " + c.unit + ">";
      });

  py::class_<fit::FitResult>(m, "_FitResult")
      .def_readonly("law", &fit::FitResult::law)
      .def_readonly("parameters", &fit::FitResult::parameters)
      .def_property_readonly("correlation",
                             [](const fit::FitResult& r) {
                               const auto n = static_cast<py::ssize_t>(r.parameters.size());
                               py::array_t<double> a({n, n});
                               std::copy(r.correlation.begin(), r.correlation.end(), a.mutable_data());
                               return a;
                             })
      .def_readonly("points", &fit::FitResult::points)
      .def_readonly("rss", &fit::FitResult::rss)
      .def_readonly("r2", &fit::FitResult::r2)
      .def_readonly("rmse", &fit::FitResult::rmse)
      .def_readonly("aic", &fit::FitResult::aic)
      .def_readonly("bic", &fit::FitResult::bic)
      .def_readonly("iterations", &fit::FitResult::iterations)
      .def_readonly("starts", &fit::FitResult::starts)
      .def_readonly("starts_agreeing", &fit::FitResult::starts_agreeing)
      .def_readonly("converged", &fit::FitResult::converged)
      .def_readonly("structured_starts", &fit::FitResult::structured_starts)
      .def_readonly("minimum_certain", &fit::FitResult::minimum_certain)
      .def_readonly("minimum_note", &fit::FitResult::minimum_note)
      .def_property_readonly("singular_values", [](const fit::FitResult& r) { return to_numpy(r.singular_values); })
      .def_readonly("combinations", &fit::FitResult::combinations)
      .def_readonly("warnings", &fit::FitResult::warnings)
      .def_property_readonly("fitted", [](const fit::FitResult& r) { return to_numpy(r.fitted); });

  m.def(
      "read_creep_csv",
      [](const std::string& path, const std::string& time_column, const std::string& displacement_column,
         const std::string& stress_column, const py::object& stress) {
        fit::CsvOptions o;
        o.time_column = time_column;
        o.displacement_column = displacement_column;
        o.stress_column = stress_column;
        if (!stress.is_none()) o.stress = staged_history(stress, "--stress");
        return fit::read_creep_csv(path, o);
      },
      py::arg("path"), py::arg("time_column") = "t", py::arg("displacement_column") = "displacement",
      py::arg("stress_column") = "", py::arg("stress") = py::none(),
      "Reads a creep curve CSV as `rheodda fit` does (docs/guide/fitting.md); raises rheodda.DataError");
  m.def(
      "creep_data",
      [](const std::vector<double>& t, const std::vector<double>& displacement, const py::object& stress,
         const std::string& source) { return data_from_arrays(t, displacement, stress, source); },
      py::arg("t"), py::arg("displacement"), py::arg("stress"), py::arg("source") = "<arrays>",
      "A creep curve from arrays: t [time], total displacement [length], stress: a number, "
      "'T:V[,T:V...]' or (t, value) pairs [stress]");
  m.def(
      "_fit_law",
      [](const std::string& law, const fit::CreepData& data, int restarts, int max_iterations) {
        const laws::LawInfo& info = laws::LawRegistry::builtin().get(law);
        py::gil_scoped_release release;
        return fit::fit_law(info, data, options_from(restarts, max_iterations));
      },
      py::arg("law"), py::arg("data"), py::arg("restarts") = 4, py::arg("max_iterations") = 500);
  m.def(
      "_fit_all",
      [](const fit::CreepData& data, const std::string& rank_by, int restarts, int max_iterations) {
        if (rank_by != "aic" && rank_by != "bic")
          throw laws::LawError("rank_by", "rank_by: '" + rank_by + "' is not one of aic, bic");
        std::vector<std::string> skipped;
        std::vector<fit::FitResult> r;
        {
          py::gil_scoped_release release;
          r = fit::fit_all(laws::LawRegistry::builtin(), data, rank_by == "aic" ? fit::Criterion::aic : fit::Criterion::bic,
                           skipped, options_from(restarts, max_iterations));
        }
        return py::make_tuple(r, skipped);
      },
      py::arg("data"), py::arg("rank_by") = "bic", py::arg("restarts") = 4, py::arg("max_iterations") = 500);
}

}  // namespace rheodda::python
