// rheodda.Simulation (simulation.hpp): construction, the run with its step
// callback, the history, the step settings and the loads' histories.
#include "simulation.hpp"

#include <rheodda/core/settings.hpp>
#include <rheodda/laws/registry.hpp>
#include <rheodda/scene/assemble.hpp>
#include <rheodda/scene/history_columns.hpp>
#include <rheodda/scene/output.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <type_traits>
#include <variant>

#include "laws.hpp"

namespace rheodda::python {
namespace {

/// Thrown by the step observer to leave Engine::run_until between two steps.
struct LeaveRun {};

/// The step settings Simulation.set_settings takes: the engine's declared settings that
/// may change between steps (core/settings.hpp, SettingSpec::between_steps and
/// ChoiceSpec::between_steps), by their scene names (analysis.*); the one list the setter,
/// the getter and the error's list of valid names read. A number's or flag's value is
/// kept in the change log as its member's type, a choice's as its word.
using SettingMember = decltype(core::SettingSpec::field);

std::vector<const core::SettingSpec*> step_settings() {
  std::vector<const core::SettingSpec*> out;
  for (const core::SettingSpec& s : core::setting_specs())
    if (s.between_steps) out.push_back(&s);
  return out;
}

std::vector<const core::ChoiceSpec*> step_choices() {
  std::vector<const core::ChoiceSpec*> out;
  for (const core::ChoiceSpec& c : core::choice_specs())
    if (c.between_steps) out.push_back(&c);
  return out;
}

/// The step choice named `key`; nullptr when `key` names none.
const core::ChoiceSpec* step_choice(const std::string& key) {
  for (const core::ChoiceSpec* c : step_choices())
    if (key == c->name()) return c;
  return nullptr;
}

const SettingMember& setting(const std::string& key) {
  for (const core::SettingSpec* s : step_settings())
    if (key == s->name()) return s->field;
  std::vector<std::string> names;
  for (const core::SettingSpec* s : step_settings()) names.push_back(s->name());
  for (const core::ChoiceSpec* c : step_choices()) names.push_back(c->name());
  throw InputError(fmt::format("set_settings: unknown setting '{}'; valid: {}", key, fmt::join(names, ", ")));
}

/// The word `value` given for the choice `c`, refused unless it is a string among its words.
std::string choice_word(const core::ChoiceSpec& c, const py::handle& value) {
  const std::string words = fmt::format("{}", fmt::join(c.words, ", "));
  if (!py::isinstance<py::str>(value))
    throw InputError(fmt::format("set_settings: {} is a word ({}), not {}", c.name(), words,
                                 py::str(py::type::of(value).attr("__name__")).cast<std::string>()));
  const auto word = value.cast<std::string>();
  if (std::find(c.words.begin(), c.words.end(), word) == c.words.end())
    throw InputError(fmt::format("set_settings: {} '{}' is not one of: {}", c.name(), word, words));
  return word;
}

}  // namespace

double unhex(const json& j) { return j.is_string() ? std::strtod(j.get<std::string>().c_str(), nullptr) : j.get<double>(); }

Simulation::Simulation(const Scene& s, const py::dict& law_overrides, py::object callback)
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
    scene::LawChoice choice;  // the override's law: none of a fit's marks (docs/guide/fitting.md)
    choice.name = std::string(law.name());
    choice.parameters = law.parameters();
    scene_.joint_sets[j].law = std::move(choice);
    // What restore() gives again: a built-in law by its parameters, a Python law by the object itself.
    if (dynamic_cast<const PythonLaw*>(&law)) {
      laws_[name] = "python";
    } else {
      json p = json::object();
      for (const auto& [k, v] : law.parameters()) p[k] = hex(v);
      laws_[name] = {{"name", std::string(law.name())}, {"parameters", p}};
    }
  }
  scene::AssembledScene assembled = scene::assemble_scene(scene_, built_);
  contacts_ = std::move(assembled.contacts);
  adapter_ = std::move(assembled.adapter);
  engine_ = std::move(assembled.engine);
  observe(*engine_);
  for (std::size_t j = 0; j < scene_.joint_sets.size(); ++j)
    if (scene_.joint_sets[j].record) recorded_.push_back(static_cast<int>(j));
  for (std::size_t k = 0; k < engine_->model().point_loads.size(); ++k) load_ids_.push_back(next_load_id_++);
  // history.csv's declared columns (scene/history_columns.hpp), without those after the
  // settling stage, of the bolts and of the stage.
  std::vector<std::string> points, recorded;
  for (const auto& mp : scene_.measurement_points) points.push_back(mp.name);
  for (int j : recorded_) recorded.push_back(scene_.joint_sets[j].name);
  columns_ = scene::history_columns_of(points, false, recorded, false, false);
  history_.assign(columns_.size(), {});
  record(nullptr);
}

Simulation::~Simulation() {
  // The engine and contacts may call Python laws' destructors: not here (keep_alive_ goes last).
  engine_.reset();
  pending_engine_.reset();
  adapter_.reset();
  contacts_.reset();
}

void Simulation::run(const py::object& self, double end_time, long max_steps) {
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
        locate_python_law_error(e, engine_->step_count() + 1, engine_->time(), scene_.units.time);
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
    if (python_error) {
      adopt_pending();
      throw std::move(*python_error);  // the step before is complete: may go on
    }
  }
}

py::dict Simulation::history() const {
  py::dict d;
  for (std::size_t i = 0; i < columns_.size(); ++i) d[py::str(columns_[i])] = read_only(to_numpy(history_[i]));
  return d;
}

// --- loads' histories and step settings: a new engine ---------------------

void Simulation::set_load(int index, double fx, double fy) {
  // What the user gave is named, not the history the call makes of it.
  if (!std::isfinite(fx) || !std::isfinite(fy))
    throw InputError(fmt::format("set_load: load {}: force ({:g}, {:g}) must be finite [{}]", index, fx, fy,
                                 scene_.units.force));
  set_load_history(index, {{eng().time(), fx, fy}});
}

void Simulation::set_load_history(int index, const std::vector<std::array<double, 3>>& samples) {
  const auto& loads = eng().model().point_loads;
  if (index < 0 || index >= static_cast<int>(loads.size()))
    throw InputError(fmt::format("set_load: load {} does not exist; the model has {} loads (0..{})", index,
                                 loads.size(), static_cast<int>(loads.size()) - 1));
  if (samples.empty()) throw InputError("set_load_history: no samples");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& s = samples[k];
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || !std::isfinite(s[2]))
      throw InputError(fmt::format("set_load_history: load {}: samples[{}] = ({:g}, {:g}, {:g}) must be finite "
                                   "(t [{}], fx, fy [{}])", index, k, s[0], s[1], s[2], scene_.units.time,
                                   scene_.units.force));
    if (k > 0 && !(s[0] > samples[k - 1][0]))
      throw InputError(fmt::format("set_load_history: load {}: samples[{}]: time {:g} does not follow {:g}: times "
                                   "must increase strictly", index, k, s[0], samples[k - 1][0]));
  }
  std::vector<core::LoadSample> h;
  json logged = json::array();
  for (const auto& s : samples) {
    h.push_back({s[0], {s[1], s[2]}});
    logged.push_back({hex(s[0]), hex(s[1]), hex(s[2])});
  }
  apply_load_history(index, h);
  changes_.push_back({{"kind", "load_history"}, {"index", index}, {"samples", logged}});
}

void Simulation::apply_load_history(int index, const std::vector<core::LoadSample>& h) {
  core::Model m = next_model();
  m.point_loads[static_cast<std::size_t>(index)].history = h;
  prepare_engine(std::move(m), false);
}

void Simulation::set_settings(const py::kwargs& kw) {
  json values = json::object();
  for (auto item : kw) {
    const auto key = item.first.cast<std::string>();
    if (const core::ChoiceSpec* c = step_choice(key)) {
      values[key] = choice_word(*c, item.second);
      continue;
    }
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(std::declval<core::Settings>().*member)>;
          if constexpr (std::is_same_v<T, double>)
            values[key] = hex(item.second.cast<double>());  // exact through the change log
          else
            values[key] = item.second.cast<T>();
        },
        setting(key));
  }
  core::Model m = next_model();
  const bool dt_changed = apply_settings(m.settings, values);
  prepare_engine(std::move(m), dt_changed);
  changes_.push_back({{"kind", "settings"}, {"values", values}});
}

bool Simulation::apply_settings(core::Settings& s, const json& values) {
  bool dt_changed = false;
  for (const auto& [key, v] : values.items()) {
    if (const core::ChoiceSpec* c = step_choice(key)) {
      c->set(s, v.get<std::string>());
      continue;
    }
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, double>)
            s.*member = unhex(v);
          else
            s.*member = v.template get<T>();
        },
        setting(key));
    dt_changed = dt_changed || key == "dt";
  }
  return dt_changed;
}

py::dict Simulation::settings() const {
  const core::Settings& s = eng().model().settings;
  py::dict d;
  for (const core::SettingSpec* spec : step_settings())
    std::visit([&](auto m) { d[spec->name().c_str()] = s.*m; }, spec->field);
  for (const core::ChoiceSpec* c : step_choices()) d[c->name().c_str()] = c->word_of(s);
  return d;
}

py::list Simulation::load_forces() const {
  py::list r;
  for (const auto& l : eng().model().point_loads) {
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

int Simulation::joint_set_index(const std::string& name) const {
  for (std::size_t j = 0; j < scene_.joint_sets.size(); ++j)
    if (scene_.joint_sets[j].name == name) return static_cast<int>(j);
  std::vector<std::string> names;
  for (const auto& js : scene_.joint_sets) names.push_back(js.name);
  const std::string near = laws::nearest_name(name, names);
  throw InputError(fmt::format("joint set '{}' is not in the scene{}; joint sets: {}", name,
                               near.empty() ? "" : " (did you mean '" + near + "'?)", fmt::join(names, ", ")));
}

std::unique_ptr<core::Engine> Simulation::make_engine(core::Model m) {
  auto e = std::make_unique<core::Engine>(std::move(m), *adapter_);
  observe(*e);
  return e;
}

void Simulation::observe(core::Engine& e) {
  e.add_observer([this](const core::Engine&, const core::StepReport& r) {
    if (observer_) observer_(r);
  });
}

void Simulation::prepare_engine(core::Model m, bool dt_changed) {
  // Built now, so that a bad value raises at the call that gave it.
  auto e = make_engine(std::move(m));
  const core::Engine& now = eng();
  // The blocks removed so far stay removed (the model lists no point on them any more,
  // and the contact system has dropped them already).
  core::ModelEdit gone;
  const auto removed = now.removed_blocks();
  for (std::size_t b = 0; b < removed.size(); ++b)
    if (removed[b]) gone.remove_blocks.push_back(static_cast<int>(b));
  if (!gone.remove_blocks.empty()) e->edit(gone);
  core::EngineState st = now.save();
  if (dt_changed) st.next_dt = e->model().settings.dt;
  e->restore(st);
  pending_engine_ = std::move(e);
  if (!stepping_) adopt_pending();
}

void Simulation::record(const core::StepReport* r) {
  // One row of the history, the columns of history.csv (run.cpp history_row), at full precision.
  const core::Engine& e = eng();
  std::size_t i = 0;
  auto put = [&](double v) { history_[i++].push_back(v); };
  put(e.time());
  put(e.step_count());
  put(r ? r->dt : 0.0);
  put(r ? r->cuts : 0);
  put(r ? r->iterations : 0);
  for (const auto& mp : scene_.measurement_points) {
    const core::Vec2 d = e.point_displacement(mp.at.block, {mp.at.point[0], mp.at.point[1]});
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
  for (const double v : scene::history_energy_values(e.energy())) put(v);
}

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
      .def_readonly("cycles", &core::StepReport::cycles,
                    "explicit cycles of the accepted attempt (0: the step was implicit) [-]")
      .def_readonly("cycle_dt", &core::StepReport::cycle_dt, "length of those cycles [time]")
      .def_readonly("stable_block", &core::StepReport::stable_block,
                    "the block whose stable cycle set their length (-1: none) [-]")
      .def_readonly("mass_scale", &core::StepReport::mass_scale,
                    "the largest density scale of the blocks' masses in those cycles (analysis.stage_cycles) [-]")
      .def("__repr__", [](const core::StepReport& r) {
        return fmt::format("<StepReport step {} t {:g} dt {:g} iterations {} cuts {}>", r.step, r.time, r.dt,
                           r.iterations, r.cuts);
      });

  py::class_<Simulation> c(m, "_Simulation", "The engine side of rheodda.Simulation (python/rheodda/__init__.py)");
  c.def(py::init<const Scene&, const py::dict&, py::object>(), py::arg("scene"), py::arg("laws") = py::dict(),
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
      .def_property_readonly("in_stage", &Simulation::in_stage)
      .def("_stable_cycle", &Simulation::stable_cycle)
      .def("_block_cycles", [](const Simulation& s) {
        const std::vector<double> h = s.block_cycles();
        return py::array_t<double>(static_cast<py::ssize_t>(h.size()), h.data());
      })
      .def("_history", &Simulation::history)
      .def_property_readonly("columns", &Simulation::columns)
      .def("set_load", &Simulation::set_load, py::arg("index"), py::arg("fx"), py::arg("fy"))
      .def("set_load_history", &Simulation::set_load_history, py::arg("index"), py::arg("samples"))
      .def("set_settings", &Simulation::set_settings)
      .def_property_readonly("settings", &Simulation::settings)
      .def_property_readonly("loads", &Simulation::load_forces)
      .def_property_readonly("units", [](const Simulation& s) { return units_dict(s.scene().units); })
      .def_property_readonly("joint_set_names",
                             [](const Simulation& s) {
                               std::vector<std::string> r;
                               for (const auto& j : s.scene().joint_sets) r.push_back(j.name);
                               return r;
                             })
      .def_property_readonly("block_names", [](const Simulation& s) {
        std::vector<std::string> r;
        for (const auto& b : s.scene().blocks) r.push_back(b.name);
        return r;
      });
  bind_simulation_blocks(c);
  bind_simulation_joint_sets(c);
  bind_simulation_state(c);
}

}  // namespace rheodda::python
