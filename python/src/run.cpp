// `rheodda run` and `rheodda study` from Python.
//
// Ctrl-C. The run goes on a worker thread with the GIL released; the calling
// (main) thread wakes every 50 ms, takes the GIL and asks Python whether a
// signal arrived (PyErr_CheckSignals). On Ctrl-C it sets RunOptions::stop, the
// run stops after its current step exactly as `rheodda run` does on SIGINT
// (files consistent, checkpoint.json written, resumable with resume=True), and
// KeyboardInterrupt is raised once the worker has finished.
#include <cmath>
#include <rheodda/scene/run.hpp>
#include <rheodda/study/study.hpp>

#include <chrono>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "common.hpp"
#include "scene.hpp"

namespace rheodda::python {
namespace {

/// Runs `work` on a worker thread while the caller watches for Ctrl-C; `stop` is
/// set when one arrives. Rethrows the work's exception; raises KeyboardInterrupt after a stop.
template <class Work>
void run_interruptible(Work work, volatile std::sig_atomic_t& stop) {
  std::exception_ptr error;
  std::optional<py::error_already_set> interrupt;
  {
    py::gil_scoped_release release;
    std::mutex mutex;
    std::condition_variable cv;
    bool done = false;
    std::thread worker([&] {
      try {
        work();
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      done = true;
      cv.notify_one();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while (!done) {
      if (cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
      if (interrupt) continue;  // asked to stop; waiting for the step to end
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          interrupt.emplace();  // fetches KeyboardInterrupt (or whatever the handler raised)
          stop = 1;
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (error) std::rethrow_exception(error);
  if (interrupt) throw std::move(*interrupt);
}

}  // namespace

void bind_run(py::module_& m) {
  m.def(
      "run",
      [](const Scene& s, const std::string& out_dir, bool resume, bool progress) {
        volatile std::sig_atomic_t stop = 0;
        scene::RunOptions o;
        o.out_dir = out_dir;
        o.resume = resume;
        o.progress = progress;
        o.stop = &stop;
        scene::RunResult r;
        run_interruptible(
            [&] {
              try {
                r = scene::run_scene(s.description, s.text, o);
              } catch (const scene::SceneError&) {
                throw;
              } catch (const std::invalid_argument& e) {  // --resume refused
                throw InputError(e.what());
              } catch (const std::runtime_error& e) {  // "run failed at t = ..."
                throw RunFailure(e.what());
              }
            },
            stop);
        py::dict d;
        d["status"] = r.status == scene::RunStatus::completed ? "completed" : "interrupted";
        d["steps"] = r.steps;
        d["cuts"] = r.cuts;
        d["redone"] = r.redone;
        d["extrapolated"] = r.extrapolated;
        d["max_penetration"] = r.max_penetration;
        d["time"] = r.time;
        d["frames"] = r.frames;
        d["wall_seconds"] = r.wall_seconds;
        d["resumed_from_step"] = r.resumed_from_step;
        d["steps_computed"] = r.steps_computed;
        d["warnings"] = r.warnings;
        // summary.json's static_mechanism (docs/reference/engine.md, "Mechanisms in static analysis"); None if dynamic.
        if (r.mechanism.static_analysis) {
          py::dict m;
          m["inertia_share"] = r.mechanism.inertia_share;
          m["steps"] = r.mechanism.steps;
          m["first_time"] = std::isnan(r.mechanism.first_time) ? py::object(py::none())
                                                                : py::object(py::float_(r.mechanism.first_time));
          m["last_time"] = std::isnan(r.mechanism.last_time) ? py::object(py::none())
                                                              : py::object(py::float_(r.mechanism.last_time));
          // The start of each collapse stage (docs/reference/engine.md, "Collapse stages").
          m["collapse_stages"] = r.mechanism.collapse_stages;
          d["static_mechanism"] = m;
        } else {
          d["static_mechanism"] = py::none();
        }
        d["out_dir"] = out_dir;
        return d;
      },
      py::arg("scene"), py::arg("out_dir"), py::arg("resume") = false, py::arg("progress") = false,
      "`rheodda run SCENE -o OUT_DIR [--resume]`: history.csv, contacts.csv, ParaView frames, summary.json. "
      "Ctrl-C stops it after the current step (resumable) and raises KeyboardInterrupt.");

  m.def(
      "_run_study",
      [](const std::string& path, const std::string& out_dir, int jobs, bool plot, const std::string& binary) {
        study::StudyDescription st = study::load_study(path);
        study::StudyOptions o;
        o.out_dir = out_dir;
        o.jobs = jobs;
        o.plot = plot;
        o.rheodda_binary = binary;
        std::vector<study::CaseResult> cases;
        {
          py::gil_scoped_release release;
          cases = study::run_study(st, o);
        }
        py::list r;
        for (const auto& c : cases) {
          py::dict d;
          d["name"] = c.name;
          d["status"] = c.status;
          d["message"] = c.message;
          d["exit_code"] = c.exit_code;
          d["steps"] = c.steps;
          d["wall_seconds"] = c.wall_seconds;
          d["inertia_share"] = c.inertia_share ? py::object(py::float_(*c.inertia_share)) : py::object(py::none());
          const auto n_out = static_cast<py::ssize_t>(st.outputs.size());
          const auto n_t = static_cast<py::ssize_t>(st.times.size());
          py::array_t<double> v({n_out, n_t});
          auto w = v.mutable_unchecked<2>();
          for (py::ssize_t i = 0; i < n_out; ++i)
            for (py::ssize_t j = 0; j < n_t; ++j) {
              const auto idx = static_cast<std::size_t>(i * n_t + j);
              w(i, j) = idx < c.values.size() && c.values[idx] ? *c.values[idx] : std::nan("");
            }
          d["values"] = v;
          r.append(d);
        }
        return py::make_tuple(r, st.outputs, st.times);
      },
      py::arg("path"), py::arg("out_dir"), py::arg("jobs"), py::arg("plot"), py::arg("rheodda_binary"));

  m.attr("_build_rheodda_binary") = RHEODDA_BUILD_BINARY;
}

}  // namespace rheodda::python
