// Scenes from Python: load or parse a scene (the loader of `rheodda check/run`),
// and drive it through the core engine step by step (rheodda.Simulation), with
// a per-step callback that reads the state as numpy arrays and may change
// loads, a joint set's law parameters or the step settings between steps.
//
// How a change between steps is made without touching the engine's interface.
// core::Engine copies its Model at construction and keeps no setters; the
// binding builds a new Engine from the changed Model on the same contact
// system (whose contacts, histories and penalty carry on) and hands it the old
// engine's EngineState (Engine::save/restore: vertices, stresses, velocities,
// time, energy account). A law's parameters live in the contact system's joint
// set (contact::JointSet::law, a shared pointer to an immutable law): the new
// law, built by the registry from the merged parameters, replaces it between
// two steps; ContactSystem::begin_step computes the step constants from it at
// the next step (contact_system.cpp) and reads E1 per contact there too.
#include <rheodda/contact/contact_system.hpp>
#include <rheodda/core/contact_adapter.hpp>
#include <rheodda/core/engine.hpp>
#include <rheodda/laws/registry.hpp>
#include <rheodda/scene/assemble.hpp>
#include <rheodda/scene/build.hpp>
#include <rheodda/scene/describe.hpp>
#include <rheodda/scene/loader.hpp>
#include <rheodda/scene/output.hpp>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "laws.hpp"
#include "scene.hpp"

namespace rheodda::python {
namespace {

/// Thrown by the step observer to leave Engine::run_until between two steps.
struct LeaveRun {};

class Simulation {
 public:
  Simulation(const Scene& s, const py::dict& law_overrides, py::object callback)
      : scene_(s.description), text_(s.text), callback_(std::move(callback)) {
    if (!scene_.stages.empty())  // not applied here: refused, not ignored (docs/reference/stages.md)
      throw std::invalid_argument("a scene with stages runs with `rheodda run`; Simulation does not apply stages yet");
    built_ = scene::build_scene(scene_);
    for (auto item : law_overrides) {
      const auto name = item.first.cast<std::string>();
      const int j = joint_set_index(name);
      keep_alive_.push_back(py::reinterpret_borrow<py::object>(item.second));
      built_.joint_sets[j].law = item.second.cast<std::shared_ptr<laws::ContactRheology>>();
      const laws::ContactRheology& law = *built_.joint_sets[j].law;
      scene_.joint_sets[j].law = scene::LawChoice{std::string(law.name()), law.parameters()};
    }
    scene::AssembledScene assembled = scene::assemble_scene(scene_, built_);
    contacts_ = std::move(assembled.contacts);
    adapter_ = std::move(assembled.adapter);
    engine_ = std::move(assembled.engine);
    observe(*engine_);
    for (std::size_t j = 0; j < scene_.joint_sets.size(); ++j)
      if (scene_.joint_sets[j].record) recorded_.push_back(static_cast<int>(j));
    columns_ = {"time", "step", "dt", "cuts", "iterations"};
    for (const auto& mp : scene_.measurement_points) {
      columns_.push_back(mp.name + ".u");
      columns_.push_back(mp.name + ".v");
    }
    for (int j : recorded_)
      for (const char* c : {".contacts", ".shear_displacement", ".shear_force", ".shear_displacement_magnitude"})
        columns_.push_back(scene_.joint_sets[j].name + c);
    for (const char* c : scene::kHistoryEnergyColumns) columns_.push_back(c);
    history_.assign(columns_.size(), {});
    record(nullptr);
  }

  ~Simulation() {
    // The engine and contacts may call Python laws' destructors: not here (keep_alive_ goes last).
    engine_.reset();
    pending_engine_.reset();
    adapter_.reset();
    contacts_.reset();
  }

  /// Runs until `end_time` or until `max_steps` more steps are accepted, whichever comes first.
  void run(const py::object& self, double end_time, long max_steps) {
    if (failed_) throw RunFailure("the simulation failed earlier (" + failure_ + "); build a new one");
    if (stepping_) throw InputError("step() and run() cannot be called from the step callback");
    long done = 0;
    std::optional<py::error_already_set> python_error;
    std::string failure;
    while (true) {
      adopt_pending();
      if (max_steps >= 0 && done >= max_steps) break;
      const double remaining = end_time - engine_->time();
      if (remaining <= 1e-12 * std::max(1.0, std::abs(end_time))) break;  // as Engine::run_until
      stepping_ = true;
      {
        py::gil_scoped_release release;
        observer_ = [&](const core::StepReport& r) {
          ++done;
          ++steps_;
          record(&r);
          py::gil_scoped_acquire acquire;
          try {
            check_signals();
            if (!callback_.is_none()) callback_(self, r);
          } catch (py::error_already_set& e) {
            python_error = std::move(e);
            throw LeaveRun{};
          }
          if (pending_engine_ || (max_steps >= 0 && done >= max_steps)) throw LeaveRun{};
        };
        try {
          engine_->run_until(end_time);
        } catch (const LeaveRun&) {
        } catch (py::error_already_set& e) {
          // A Python law raised inside a step: the contacts are mid-step.
          py::gil_scoped_acquire acquire;
          failure = "a Python law raised an exception";
          python_error = std::move(e);
        } catch (const std::exception& e) {
          failure = fmt::format("run failed at t = {:g} {} (step {}): {}", engine_->time(), scene_.units.time,
                                engine_->step_count(), e.what());
        }
        observer_ = nullptr;
      }
      stepping_ = false;
      if (!failure.empty()) {
        failed_ = true;
        failure_ = failure;
        if (python_error) throw std::move(*python_error);
        throw RunFailure(failure);
      }
      if (python_error) throw std::move(*python_error);  // the step before is complete: may go on
    }
  }

  // --- reading the state -------------------------------------------------

  double time() const { return engine_->time(); }
  int step_count() const { return engine_->step_count(); }

  py::array_t<double> centroids() const {
    const int n = engine_->block_count();
    py::array_t<double> a({n, 2});
    auto r = a.mutable_unchecked<2>();
    for (int b = 0; b < n; ++b) {
      const core::Vec2 c = engine_->centroid(b);
      r(b, 0) = c.x();
      r(b, 1) = c.y();
    }
    return a;
  }
  py::array_t<double> vertices(int b) const {
    check_block(b);
    const auto v = engine_->vertices(b);
    py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{2}});
    auto r = a.mutable_unchecked<2>();
    for (std::size_t k = 0; k < v.size(); ++k) {
      r(k, 0) = v[k].x();
      r(k, 1) = v[k].y();
    }
    return a;
  }
  template <int N, class Get>
  py::array_t<double> per_block(Get get) const {
    const int n = engine_->block_count();
    py::array_t<double> a({n, N});
    auto r = a.mutable_unchecked<2>();
    for (int b = 0; b < n; ++b) {
      const auto v = get(b);
      for (int i = 0; i < N; ++i) r(b, i) = v[i];
    }
    return a;
  }
  py::array_t<double> velocities() const {
    return per_block<6>([&](int b) { return engine_->velocity(b); });
  }
  py::array_t<double> stresses() const {
    return per_block<3>([&](int b) { return engine_->stress(b); });
  }
  py::array_t<double> point_displacement(int b, double x, double y) const {
    check_block(b);
    const core::Vec2 d = engine_->point_displacement(b, {x, y});
    py::array_t<double> a(2);
    a.mutable_at(0) = d.x();
    a.mutable_at(1) = d.y();
    return a;
  }

  py::dict contacts() const {
    const auto cs = contacts_->contacts();
    const auto states = contacts_->rheology_states();
    const auto incr = contacts_->creep_increments();
    const auto n = static_cast<py::ssize_t>(cs.size());
    std::vector<long> id, js, state, vb, vx, eb, ed;
    std::vector<double> x, y, nf, sf, sd, pen, len, creep, dcreep;
    py::array_t<double> q({n, py::ssize_t{laws::kMaxInternal}});
    auto qr = q.mutable_unchecked<2>();
    std::vector<std::string> state_names, kind_names;
    for (py::ssize_t i = 0; i < n; ++i) {
      const contact::Contact& c = cs[i];
      id.push_back(static_cast<long>(c.id));
      js.push_back(c.joint_set);
      state.push_back(static_cast<long>(c.state));
      state_names.emplace_back(contact::contact_state_name(c.state));
      kind_names.emplace_back(contact::contact_kind_name(c.kind));
      vb.push_back(c.key.vblock);
      vx.push_back(c.key.vertex);
      eb.push_back(c.key.eblock);
      ed.push_back(c.key.edge);
      const core::Vec2 p = engine_->vertices(c.key.vblock)[c.key.vertex];
      x.push_back(p.x());
      y.push_back(p.y());
      nf.push_back(c.normal_force);
      sf.push_back(c.shear_force);
      sd.push_back(c.shear_displacement);
      pen.push_back(c.penetration);
      len.push_back(c.length);
      const laws::RheologyState st = c.rheology >= 0 ? states[c.rheology] : laws::RheologyState{};
      creep.push_back(st.creep());
      for (int k = 0; k < laws::kMaxInternal; ++k) qr(i, k) = st.q[k];
      dcreep.push_back(i < static_cast<py::ssize_t>(incr.size()) ? incr[i] : 0.0);
    }
    py::dict d;
    d["id"] = to_numpy(id);
    d["joint_set"] = to_numpy(js);
    d["state"] = str_array(state_names);
    d["kind"] = str_array(kind_names);
    d["vertex_block"] = to_numpy(vb);
    d["vertex"] = to_numpy(vx);
    d["edge_block"] = to_numpy(eb);
    d["edge"] = to_numpy(ed);
    d["x"] = to_numpy(x);
    d["y"] = to_numpy(y);
    d["normal_force"] = to_numpy(nf);
    d["shear_force"] = to_numpy(sf);
    d["shear_displacement"] = to_numpy(sd);
    d["penetration"] = to_numpy(pen);
    d["length"] = to_numpy(len);
    d["creep_displacement"] = to_numpy(creep);
    d["creep_increment"] = to_numpy(dcreep);
    d["q"] = q;
    for (auto item : d) read_only(item.second.cast<py::array>());
    return d;
  }

  py::dict history() const {
    py::dict d;
    for (std::size_t i = 0; i < columns_.size(); ++i) d[py::str(columns_[i])] = read_only(to_numpy(history_[i]));
    return d;
  }
  const std::vector<std::string>& columns() const { return columns_; }

  // --- changing the model between steps ----------------------------------

  /// Load `index` (scene order) holds `force` (fx, fy) from the next step on.
  void set_load(int index, double fx, double fy) {
    set_load_history(index, {{engine_->time(), fx, fy}});
  }

  /// Load `index` follows the samples (t, fx, fy) from now on (piecewise linear, as in a scene).
  void set_load_history(int index, const std::vector<std::array<double, 3>>& samples) {
    core::Model m = next_model();
    if (index < 0 || index >= static_cast<int>(m.point_loads.size()))
      throw InputError(fmt::format("set_load: load {} does not exist; the scene has {} loads (0..{})", index,
                                   m.point_loads.size(), static_cast<int>(m.point_loads.size()) - 1));
    if (samples.empty()) throw InputError("set_load_history: no samples");
    std::vector<core::LoadSample> h;
    for (const auto& s : samples) h.push_back({s[0], {s[1], s[2]}});
    m.point_loads[index].history = std::move(h);
    prepare_engine(std::move(m), false);
  }

  /// Step settings, by their scene names (analysis.*).
  void set_settings(const py::kwargs& kw) {
    core::Model m = next_model();
    core::Settings& s = m.settings;
    bool dt_changed = false;
    for (auto item : kw) {
      const auto key = item.first.cast<std::string>();
      auto number = [&] { return item.second.cast<double>(); };
      if (key == "dt") {
        s.dt = number();
        dt_changed = true;
      } else if (key == "dt_growth") s.dt_growth = number();
      else if (key == "dt_cut") s.dt_cut = number();
      else if (key == "max_cuts") s.max_cuts = item.second.cast<int>();
      else if (key == "max_displacement_ratio") s.g2 = number();
      else if (key == "creep_tolerance") s.creep_tolerance = number();
      else if (key == "step_tolerance") s.step_tolerance = number();
      else if (key == "step_extrapolation") s.step_extrapolation = item.second.cast<bool>();
      else if (key == "dt_max") s.dt_max = number();
      else if (key == "open_close_limit") s.max_open_close = item.second.cast<int>();
      else if (key == "solver_tolerance") s.pcg_tolerance = number();
      else if (key == "solver_max_iterations") s.pcg_max_iterations = item.second.cast<int>();
      else if (key == "solver_iterate_tolerance") s.pcg_iterate_tolerance = number();
      else
        throw InputError(fmt::format(
            "set_settings: unknown setting '{}'; valid: dt, dt_growth, dt_cut, max_cuts, max_displacement_ratio, "
            "creep_tolerance, step_tolerance, step_extrapolation, dt_max, open_close_limit, solver_tolerance, "
            "solver_max_iterations, solver_iterate_tolerance",
            key));
    }
    prepare_engine(std::move(m), dt_changed);
  }

  /// The law of joint set `name` gets these parameters (the others kept) from the next step on.
  void set_law_parameters(const std::string& name, const py::dict& values) {
    const int j = joint_set_index(name);
    auto& js = const_cast<contact::JointSet&>(contacts_->joint_sets()[j]);
    if (!js.law) throw InputError("set_law_parameters: joint set '" + name + "' has no law");
    const laws::LawInfo* info = laws::LawRegistry::builtin().find(js.law->name());
    if (!info)
      throw InputError("set_law_parameters: the law of joint set '" + name + "' (" + std::string(js.law->name()) +
                       ") is not a registered law; change a Python law's own attributes instead");
    laws::ParameterValues p = js.law->parameters();
    for (auto item : values) p[item.first.cast<std::string>()] = item.second.cast<double>();
    std::shared_ptr<const laws::ContactRheology> law = laws::LawRegistry::builtin().create(info->name, p);
    if (law->internal_count() != js.law->internal_count())
      throw InputError("set_law_parameters: the new parameters change the number of internal displacements");
    if (law->instantaneous_stiffness().has_value() != js.law->instantaneous_stiffness().has_value())
      throw InputError("set_law_parameters: the new parameters add or remove the instantaneous spring E1");
    // The contact system reads the law at each begin_step (step constants, E1);
    // between steps it holds no value derived from it. The object is not const
    // (ContactSystem owns a non-const vector), so the write is well defined.
    js.law = std::move(law);
    scene_.joint_sets[j].law->parameters = js.law->parameters();
  }

  py::dict law_parameters(const std::string& name) const {
    const auto& js = contacts_->joint_sets()[joint_set_index(name)];
    py::dict d;
    if (js.law)
      for (const auto& [k, v] : js.law->parameters()) d[py::str(k)] = v;
    return d;
  }

  py::dict settings() const {
    const core::Settings& s = (pending_engine_ ? pending_engine_ : engine_)->model().settings;
    py::dict d;
    d["dt"] = s.dt;
    d["dt_growth"] = s.dt_growth;
    d["dt_cut"] = s.dt_cut;
    d["max_cuts"] = s.max_cuts;
    d["max_displacement_ratio"] = s.g2;
    d["creep_tolerance"] = s.creep_tolerance;
    d["step_tolerance"] = s.step_tolerance;
    d["step_extrapolation"] = s.step_extrapolation;
    d["dt_max"] = s.dt_max;
    d["open_close_limit"] = s.max_open_close;
    d["solver_tolerance"] = s.pcg_tolerance;
    d["solver_max_iterations"] = s.pcg_max_iterations;
    d["solver_iterate_tolerance"] = s.pcg_iterate_tolerance;
    return d;
  }

  py::list load_forces() const {
    py::list r;
    const core::Model& m = (pending_engine_ ? pending_engine_ : engine_)->model();
    for (const auto& l : m.point_loads) {
      py::array_t<double> h({static_cast<py::ssize_t>(l.history.size()), py::ssize_t{3}});
      auto w = h.mutable_unchecked<2>();
      for (std::size_t i = 0; i < l.history.size(); ++i) {
        w(i, 0) = l.history[i].time;
        w(i, 1) = l.history[i].force.x();
        w(i, 2) = l.history[i].force.y();
      }
      r.append(read_only(h));
    }
    return r;
  }

  const scene::SceneDescription& scene() const { return scene_; }
  int joint_set_index(const std::string& name) const {
    for (std::size_t j = 0; j < scene_.joint_sets.size(); ++j)
      if (scene_.joint_sets[j].name == name) return static_cast<int>(j);
    std::vector<std::string> names;
    for (const auto& js : scene_.joint_sets) names.push_back(js.name);
    const std::string near = laws::nearest_name(name, names);
    throw InputError(fmt::format("joint set '{}' is not in the scene{}; joint sets: {}", name,
                                 near.empty() ? "" : " (did you mean '" + near + "'?)", fmt::join(names, ", ")));
  }
  bool failed() const { return failed_; }
  py::object callback() const { return callback_; }
  void set_callback(py::object f) { callback_ = std::move(f); }

 private:
  std::unique_ptr<core::Engine> make_engine(core::Model m) {
    auto e = std::make_unique<core::Engine>(std::move(m), *adapter_);
    observe(*e);
    return e;
  }

  /// Passes the engine's accepted steps to observer_.
  void observe(core::Engine& e) {
    e.add_observer([this](const core::Engine&, const core::StepReport& r) {
      if (observer_) observer_(r);
    });
  }

  core::Model next_model() const { return (pending_engine_ ? pending_engine_ : engine_)->model(); }

  /// Builds the engine that takes over after this step (validated now, so a bad
  /// value raises at the call that gave it).
  void prepare_engine(core::Model m, bool dt_changed) {
    auto e = make_engine(std::move(m));
    core::EngineState st = engine_->save();
    if (dt_changed) st.next_dt = e->model().settings.dt;
    e->restore(st);
    pending_engine_ = std::move(e);
    if (!stepping_) adopt_pending();
  }

  void adopt_pending() {
    if (pending_engine_) engine_ = std::move(pending_engine_);
  }

  void check_block(int b) const {
    if (b < 0 || b >= engine_->block_count())
      throw InputError(fmt::format("block {} does not exist; the scene has {} blocks", b, engine_->block_count()));
  }

  /// One row of the history, the columns of history.csv (run.cpp history_row), at full precision.
  void record(const core::StepReport* r) {
    std::size_t i = 0;
    auto put = [&](double v) { history_[i++].push_back(v); };
    put(engine_->time());
    put(engine_->step_count());
    put(r ? r->dt : 0.0);
    put(r ? r->cuts : 0);
    put(r ? r->iterations : 0);
    for (const auto& mp : scene_.measurement_points) {
      const core::Vec2 d = engine_->point_displacement(mp.at.block, {mp.at.point[0], mp.at.point[1]});
      put(d.x());
      put(d.y());
    }
    for (int j : recorded_) {
      int n = 0;
      double shear = 0.0, force = 0.0, magnitude = 0.0;
      for (const auto& c : contacts_->contacts())
        if (c.joint_set == j && c.state != contact::ContactState::open) {
          ++n;
          shear += c.shear_displacement;
          force += c.shear_force;
          magnitude += std::abs(c.shear_displacement);
        }
      put(n);
      put(n ? shear / n : std::nan(""));
      put(n ? force / n : std::nan(""));
      put(n ? magnitude / n : std::nan(""));
    }
    for (const double v : scene::history_energy_values(engine_->energy())) put(v);
  }

  // Declared first, destroyed last: the Python laws outlive the contact system that calls them.
  std::vector<py::object> keep_alive_;
  scene::SceneDescription scene_;
  std::string text_;
  py::object callback_;
  scene::BuiltScene built_;
  std::unique_ptr<contact::ContactSystem> contacts_;
  std::unique_ptr<core::ContactAdapter> adapter_;
  std::unique_ptr<core::Engine> engine_;
  std::unique_ptr<core::Engine> pending_engine_;
  std::function<void(const core::StepReport&)> observer_;
  bool stepping_ = false;
  bool failed_ = false;
  std::string failure_;
  long steps_ = 0;
  std::vector<int> recorded_;
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> history_;
};

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<core::StepReport>(m, "StepReport", "What happened in one accepted step (core/engine.hpp)")
      .def_readonly("step", &core::StepReport::step, "index of the step (0-based)")
      .def_readonly("time", &core::StepReport::time, "time at the end of the step [time]")
      .def_readonly("dt", &core::StepReport::dt, "step size used [time]")
      .def_readonly("iterations", &core::StepReport::iterations,
                    "open-close iterations of the accepted attempt [-]")
      .def_readonly("cuts", &core::StepReport::cuts, "times dt was cut before acceptance [-]")
      .def_readonly("max_displacement", &core::StepReport::max_displacement,
                    "largest vertex displacement of the step [length]")
      .def_readonly("max_penetration", &core::StepReport::max_penetration,
                    "largest penetration reported by the contacts [length]")
      .def_readonly("creep_error", &core::StepReport::creep_error,
                    "the contacts' creep error estimate of the step, under analysis.creep_tolerance (else 0) "
                    "[length]")
      .def_readonly("rejections", &core::StepReport::rejections,
                    "times the step was redone smaller because its error estimate was too large [-]")
      .def_readonly("step_error", &core::StepReport::step_error,
                    "step-doubling error estimate over the block vertices, under analysis.step_tolerance "
                    "(else 0) [length]")
      .def_readonly("extrapolated", &core::StepReport::extrapolated,
                    "under analysis.step_tolerance: the step was extrapolated (2 y(dt/2) - y(dt))")
      .def("__repr__", [](const core::StepReport& r) {
        return fmt::format("<StepReport step {} t {:g} dt {:g} iterations {} cuts {}>", r.step, r.time, r.dt,
                           r.iterations, r.cuts);
      });

  py::class_<Simulation>(m, "_Simulation", "The engine side of rheodda.Simulation (python/rheodda/__init__.py)")
      .def(py::init<const Scene&, const py::dict&, py::object>(), py::arg("scene"), py::arg("laws") = py::dict(),
           py::arg("callback") = py::none())
      .def(
          "_run",
          [](py::object self, double end_time, long max_steps) {
            self.cast<Simulation&>().run(self, end_time, max_steps);
          },
          py::arg("end_time"), py::arg("max_steps"))
      .def_property("_callback", &Simulation::callback, &Simulation::set_callback)
      .def_property_readonly("time", &Simulation::time)
      .def_property_readonly("step_count", &Simulation::step_count)
      .def_property_readonly("duration", [](const Simulation& s) { return s.scene().analysis.duration; })
      .def_property_readonly("failed", &Simulation::failed)
      // State read as read-only arrays: a write would not reach the engine (common.hpp, read_only).
      .def_property_readonly("block_positions", [](const Simulation& s) { return read_only(s.centroids()); })
      .def_property_readonly("block_velocities", [](const Simulation& s) { return read_only(s.velocities()); })
      .def_property_readonly("block_stresses", [](const Simulation& s) { return read_only(s.stresses()); })
      .def("block_vertices", [](const Simulation& s, int b) { return read_only(s.vertices(b)); }, py::arg("block"))
      .def(
          "point_displacement",
          [](const Simulation& s, int b, double x, double y) { return read_only(s.point_displacement(b, x, y)); },
          py::arg("block"), py::arg("x"), py::arg("y"))
      .def("contacts", &Simulation::contacts)
      .def("_history", &Simulation::history)
      .def_property_readonly("columns", &Simulation::columns)
      .def("set_load", &Simulation::set_load, py::arg("index"), py::arg("fx"), py::arg("fy"))
      .def("set_load_history", &Simulation::set_load_history, py::arg("index"), py::arg("samples"))
      .def("set_settings", &Simulation::set_settings)
      .def_property_readonly("settings", &Simulation::settings)
      .def_property_readonly("loads", &Simulation::load_forces)
      .def("set_law_parameters", &Simulation::set_law_parameters, py::arg("joint_set"), py::arg("parameters"))
      .def("law_parameters", &Simulation::law_parameters, py::arg("joint_set"))
      .def_property_readonly("units", [](const Simulation& s) { return units_dict(s.scene().units); })
      .def_property_readonly("joint_sets",
                             [](const Simulation& s) {
                               std::vector<std::string> r;
                               for (const auto& j : s.scene().joint_sets) r.push_back(j.name);
                               return r;
                             })
      .def_property_readonly("blocks", [](const Simulation& s) {
        std::vector<std::string> r;
        for (const auto& b : s.scene().blocks) r.push_back(b.name);
        return r;
      });
}

}  // namespace rheodda::python
