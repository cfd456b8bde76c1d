// rheodda.Simulation's engine side (docs/guide/python.md): a scene driven
// through core::Engine step by step, read and changed between steps. One
// concern per file:
//   simulation.cpp             construction, running, history, step settings, loads' histories
//   simulation_blocks.cpp      the blocks (read, fix, free, remove, loads added and removed),
//                              the contacts and the bolts as arrays
//   simulation_joint_sets.cpp  the joint sets read and changed (friction, cohesion, law ...)
//   simulation_state.cpp       save() and restore(): the state as bytes
//
// How a change between steps is made.
// - Block and joint set changes go through Engine::edit (core::ModelEdit: the
//   changes of a scene's stage), checked by the engine (ModelError) and, for
//   joint sets, first by the stage reader (scene/edits.hpp) so that a value is
//   refused in the loader's words.
// - Step settings and load histories have no ModelEdit: a new Engine is built
//   from the changed Model on the same contact system (whose contacts,
//   histories and penalty carry on), is given the blocks removed so far, and
//   takes the old engine's EngineState (Engine::save/restore: vertices,
//   stresses, velocities, time, energy account). Inside a step callback the
//   running engine cannot be replaced: the new one waits (pending_engine_) and
//   the run leaves Engine::run_until after the callback to take it up.
// Every change is logged (changes_, JSON with exact hex doubles) so that
// restore() can make the same model again before it takes up a saved state.
#pragma once

#include <rheodda/contact/contact_system.hpp>
#include <rheodda/core/contact_adapter.hpp>
#include <rheodda/core/engine.hpp>
#include <rheodda/scene/build.hpp>

#include <fmt/format.h>

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "scene.hpp"

namespace rheodda::python {

using json = nlohmann::ordered_json;

class Simulation {
 public:
  Simulation(const Scene& s, const py::dict& law_overrides, py::object callback);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Runs until `end_time` or until `max_steps` more steps are accepted, whichever comes first.
  void run(const py::object& self, double end_time, long max_steps);

  // --- simulation.cpp ------------------------------------------------------
  double time() const { return eng().time(); }
  int step_count() const { return eng().step_count(); }
  py::dict history() const;
  const std::vector<std::string>& columns() const { return columns_; }
  void set_load(int index, double fx, double fy);
  void set_load_history(int index, const std::vector<std::array<double, 3>>& samples);
  void set_settings(const py::kwargs& kw);
  py::dict settings() const;
  py::list load_forces() const;
  const scene::SceneDescription& scene() const { return scene_; }
  const std::string& text() const { return text_; }
  int joint_set_index(const std::string& name) const;
  bool failed() const { return failed_; }
  /// Engine::stable_cycle on the current state: (cycle [time], block; -1 where none).
  std::pair<double, int> stable_cycle() const {
    const core::Engine::StableCycle c = eng().stable_cycle();
    return {c.cycle, c.block};
  }
  /// Engine::block_cycles on the current state [time].
  std::vector<double> block_cycles() const { return eng().block_cycles(); }
  bool in_stage() const { return eng().in_stage(); }
  py::object callback() const { return callback_; }
  void set_callback(py::object f) { callback_ = std::move(f); }

  // --- simulation_blocks.cpp ----------------------------------------------
  /// One quantity of every block as an array (n, width) or (n,) (Blocks' views).
  py::array block_column(const std::string& quantity) const;
  /// One quantity of block b (a Block's attribute).
  py::object block_value(int b, const std::string& quantity) const;
  py::array_t<double> vertices(int b) const;
  py::array_t<double> point_displacement(int b, double x, double y) const;
  /// Holds block b in `dofs` (some of x, y, rotation; docs/guide/python.md, "Blocks").
  void fix(int b, const std::vector<std::string>& dofs);
  /// Gives block b the velocity (u0, v0, r0) or (u0, v0, r0, ex, ey, gxy) (ModelEdit::set_velocities).
  void set_velocity(int b, const std::vector<double>& v);
  void free(int b);
  void remove(int b);
  /// Adds a load on block b at (x, y) now, following `samples` (t from now, fx, fy); its id.
  long add_load(int b, double x, double y, const std::vector<std::array<double, 3>>& samples);
  void remove_load(long id);
  const std::vector<long>& load_ids() const { return load_ids_; }
  py::dict contacts() const;
  py::dict bolts() const;
  void check_block(int b) const;

  // --- simulation_joint_sets.cpp ------------------------------------------
  py::dict joint_set(int j) const;
  /// Changes joint set j (scene keys: friction_angle, cohesion, ... law), checked as a stage's.
  void change_joint_set(int j, const py::dict& values);
  void set_law_parameters(const std::string& name, const py::dict& values);
  py::dict law_parameters(const std::string& name) const;

  // --- simulation_state.cpp -----------------------------------------------
  /// The state as bytes: a JSON header line (scene, laws, changes, history), then Engine and contacts.
  py::bytes save() const;
  /// Takes up save()'s bytes in a simulation just built from the same scene and laws.
  void restore(const std::string& bytes);
  /// The header of save()'s bytes: scene text and file, the laws given (python/state.py reads it).
  static py::dict state_header(const std::string& bytes);

 private:
  core::Engine& eng() const { return pending_engine_ ? *pending_engine_ : *engine_; }
  std::unique_ptr<core::Engine> make_engine(core::Model m);
  void observe(core::Engine& e);
  core::Model next_model() const { return eng().model(); }
  void prepare_engine(core::Model m, bool dt_changed);
  void adopt_pending() {
    if (pending_engine_) engine_ = std::move(pending_engine_);
  }
  void record(const core::StepReport* r);
  /// Engine::edit with its ModelError in the scene's words, prefixed with `what`; logs the replay.
  core::EditReport apply_edit(const core::ModelEdit& e, const std::string& what);
  /// set_settings' values applied to `s` (keys checked).
  static bool apply_settings(core::Settings& s, const json& values);
  void apply_load_history(int index, const std::vector<core::LoadSample>& h);
  void apply_joint_set_change(int j, const std::string& text);
  void replay(const json& change);

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
  std::vector<int> recorded_;
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> history_;
  json laws_ = json::object();     ///< the laws given at construction: {joint set: {name, parameters} | "python"}
  json changes_ = json::array();   ///< every change since t = 0, in order (replay())
  std::vector<long> load_ids_;     ///< per model().point_loads: its id (scene loads 0..n-1, then added ones)
  long next_load_id_ = 0;
};

/// Exact text of a double (C99 hex float) and back: the saved state's numbers.
inline std::string hex(double v) { return fmt::format("{:a}", v); }
double unhex(const json& j);

void bind_simulation_blocks(py::class_<Simulation>& c);
void bind_simulation_joint_sets(py::class_<Simulation>& c);
void bind_simulation_state(py::class_<Simulation>& c);

}  // namespace rheodda::python
