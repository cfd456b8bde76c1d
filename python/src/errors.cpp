// C++ errors -> Python exceptions carrying the message the command line prints
// after "rheodda: error: " (apps/main.cpp prints e.what()).
//
//   rheodda.Error (ValueError)      bad input of any kind; subclasses:
//     rheodda.SceneError            scene::SceneError: .file .line .column .key .message
//     rheodda.LawError              laws::LawError: .key
//     rheodda.DataError             fit::DataError: .file .line .column
//     rheodda.FitError              fit::FitError: .law
//     rheodda.ModelError            core::ModelError: .key
//     rheodda.PythonLawError        a law written in Python returned a bad value: .law .method .value .expected
//                                   .contact (inside a run: the contact's id, else None) .step .time
//   rheodda.RunError (RuntimeError) a run that failed (no convergence after max_cuts ...)
#include <rheodda/core/model.hpp>
#include <rheodda/fit/creep_data.hpp>
#include <rheodda/fit/fit.hpp>
#include <fmt/format.h>
#include <rheodda/laws/accurate_curve.hpp>
#include <rheodda/laws/call_site.hpp>
#include <rheodda/laws/parameters.hpp>
#include <rheodda/scene/error.hpp>

#include "common.hpp"

namespace rheodda::python {

using namespace pybind11::literals;  // "key"_a = value: an exception's attributes

namespace {

// The exception types live as long as the module (pybind11 keeps the module alive).
PyObject* error_type = nullptr;
PyObject* scene_error_type = nullptr;
PyObject* law_error_type = nullptr;
PyObject* data_error_type = nullptr;
PyObject* fit_error_type = nullptr;
PyObject* model_error_type = nullptr;
PyObject* python_law_error_type = nullptr;

PyObject* new_type(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string("rheodda.") + name;
  PyObject* t = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!t) throw py::error_already_set();
  m.attr(name) = py::reinterpret_borrow<py::object>(t);
  return t;
}

/// Raises `type(message)` with the given attributes set on the instance.
void raise(PyObject* type, const char* message, const py::dict& attributes) {
  py::object instance = py::reinterpret_borrow<py::object>(type)(message);
  for (auto item : attributes) py::setattr(instance, item.first, item.second);
  PyErr_SetObject(type, instance.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
  error_type = new_type(m, "Error", PyExc_ValueError,
                        "Bad input (scene, law parameters, data, model); the message is the one "
                        "`rheodda` prints after 'rheodda: error: '.");
  scene_error_type = new_type(m, "SceneError", error_type,
                              "A scene (or study) the loader refuses: .file .line .column .key .message");
  law_error_type = new_type(m, "LawError", error_type, "Bad law name or parameters: .key");
  data_error_type = new_type(m, "DataError", error_type, "Bad creep data (CSV): .file .line .column");
  fit_error_type = new_type(m, "FitError", error_type, "A law the data cannot constrain: .law");
  model_error_type = new_type(m, "ModelError", error_type, "A model the engine refuses: .key");
  python_law_error_type = new_type(
      m, "PythonLawError", error_type,
      "A method of a law written in Python returned a value that is not finite, of the wrong type or shape: "
      ".law .method .value (its repr) .expected; inside a run also .contact (its id) and .step, .time (the "
      "step it was computed for and its start time); None elsewhere");
  PyObject* run_error = new_type(m, "RunError", PyExc_RuntimeError,
                                 "A run that failed (e.g. a step that does not converge after max_cuts cuts)");

  static PyObject* run_error_type = run_error;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      raise(error_type, e.what(), py::dict());
    } catch (const RunFailure& e) {
      raise(run_error_type, e.what(), py::dict());
    } catch (const laws::CurveError& e) {  // a law curve that cannot hold its tolerance
      raise(run_error_type, e.what(), py::dict());
    } catch (const scene::SceneError& e) {
      raise(scene_error_type, e.what(),
            py::dict("file"_a = e.file(), "line"_a = e.line(), "column"_a = e.column(), "key"_a = e.key(),
                     "message"_a = e.message()));
    } catch (const laws::LawError& e) {
      raise(law_error_type, e.what(), py::dict("key"_a = e.key()));
    } catch (const fit::DataError& e) {
      raise(data_error_type, e.what(), py::dict("file"_a = e.file(), "line"_a = e.line(), "column"_a = e.column()));
    } catch (const fit::FitError& e) {
      raise(fit_error_type, e.what(), py::dict("law"_a = e.law()));
    } catch (const core::ModelError& e) {
      raise(model_error_type, e.what(), py::dict("key"_a = e.key()));
    }
  });
}

void raise_python_law_error(const std::string& law, const std::string& method, const std::string& value,
                            const std::string& expected) {
  std::string message = "PythonLaw '" + law + "': " + method + " returned " + value + "; expected " + expected;
  // Inside a run the contact layer has set the contact it calls the law for (laws/call_site.hpp).
  const laws::CallSite& at = laws::current_call_site();
  py::object contact = py::none();
  if (at.contact >= 0) {
    message += fmt::format(", at contact {} (vertex {} of block {} on edge {} of block {}, joint set {})", at.contact,
                           at.vertex, at.vertex_block, at.edge, at.edge_block, at.joint_set);
    contact = py::int_(at.contact);
  }
  raise(python_law_error_type, message.c_str(),
        py::dict("law"_a = law, "method"_a = method, "value"_a = value, "expected"_a = expected,
                 "contact"_a = contact, "step"_a = py::none(), "time"_a = py::none()));
  throw py::error_already_set();
}

void locate_python_law_error(py::error_already_set& e, long step, double time, const std::string& time_unit) {
  if (!python_law_error_type || !e.matches(python_law_error_type)) return;
  const py::object v = e.value();
  const std::string message = py::str(v).cast<std::string>() + fmt::format(", in step {} (from t = {:g} {})", step,
                                                                           time, time_unit);
  py::setattr(v, "args", py::make_tuple(message));
  py::setattr(v, "step", py::int_(step));
  py::setattr(v, "time", py::float_(time));
}

}  // namespace rheodda::python
