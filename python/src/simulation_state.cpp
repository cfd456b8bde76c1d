// rheodda.Simulation's save() and restore() (simulation.hpp; docs/guide/python.md,
// "Saving and restoring"). The bytes: one line of JSON (the header:
// "rheodda_simulation" the format version, "program", the scene's "file" and
// "text", the "laws" given at construction, every "change" since t = 0 in
// order, the loads' ids, the "history" columns as C99 hex floats), then the
// engine's and the contact system's state in the format of a checkpoint's state
// file (scene/saved_state.hpp). restore() builds the simulation from the scene
// and the laws, makes the changes again (blocks and loads as material points,
// EditReport::replay), then takes up the saved state: the steps after it are
// those the saved simulation would have taken, bit for bit.
#include <rheodda/scene/saved_state.hpp>
#include <rheodda/version.hpp>

#include "simulation.hpp"

namespace rheodda::python {
namespace {

constexpr int kSimulationFormat = 1;

/// The header and the engine part of save()'s bytes.
std::pair<json, std::string> split(const std::string& bytes) {
  const std::size_t eol = bytes.find('\n');
  json h;
  try {
    if (eol == std::string::npos) throw std::runtime_error("no header line");
    h = json::parse(bytes.substr(0, eol));
    if (!h.is_object() || !h.contains("rheodda_simulation")) throw std::runtime_error("no format version");
  } catch (const std::exception&) {
    throw InputError("Simulation.restore: not a saved simulation (its first line is not the header "
                     "Simulation.save writes)");
  }
  if (h.at("rheodda_simulation").get<int>() != kSimulationFormat)
    throw InputError(fmt::format("Simulation.restore: a saved simulation of format {}; this rheodda reads format {}",
                                 h.at("rheodda_simulation").get<int>(), kSimulationFormat));
  if (h.value("program", "") != kProgramVersion)
    throw InputError(fmt::format("Simulation.restore: saved by {}; this is {}, whose engine may not continue it the "
                                 "same way",
                                 h.value("program", "?"), kProgramVersion));
  return {std::move(h), bytes.substr(eol + 1)};
}

core::Vec2 vec2(const json& j) { return {unhex(j.at(0)), unhex(j.at(1))}; }

std::vector<core::LoadSample> samples(const json& j) {
  std::vector<core::LoadSample> h;
  for (const auto& s : j) h.push_back({unhex(s.at(0)), {unhex(s.at(1)), unhex(s.at(2))}});
  return h;
}

}  // namespace

py::bytes Simulation::save() const {
  if (failed_) throw RunFailure("the simulation failed earlier (" + failure_ + "); it has no state to save");
  json history = json::object();
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    json c = json::array();
    for (const double v : history_[i]) c.push_back(hex(v));
    history[columns_[i]] = std::move(c);
  }
  const json h = {{"rheodda_simulation", kSimulationFormat},
                  {"program", kProgramVersion},
                  {"file", scene_.file},
                  {"scene", text_},
                  {"laws", laws_},
                  {"changes", changes_},
                  {"load_ids", load_ids_},
                  {"next_load_id", next_load_id_},
                  {"history", history}};
  const core::Engine& e = eng();
  return py::bytes(h.dump() + "\n" +
                   scene::encode_snapshot({e.save(), contacts_->state()}, text_, scene_.joint_sets.size()));
}

py::dict Simulation::state_header(const std::string& bytes) {
  const json h = split(bytes).first;
  py::dict d;
  d["file"] = h.at("file").get<std::string>();
  d["scene"] = h.at("scene").get<std::string>();
  py::dict laws;
  for (const auto& [name, law] : h.at("laws").items()) {
    if (law.is_string()) {
      laws[py::str(name)] = law.get<std::string>();
      continue;
    }
    py::dict p;
    for (const auto& [k, v] : law.at("parameters").items()) p[py::str(k)] = unhex(v);
    laws[py::str(name)] = py::make_tuple(law.at("name").get<std::string>(), p);
  }
  d["laws"] = laws;
  return d;
}

void Simulation::restore(const std::string& bytes) {
  if (engine_->step_count() != 0 || !changes_.empty())
    throw InputError("Simulation.restore: the state goes into a simulation just built, before any step or change");
  auto [h, rest] = split(bytes);
  if (h.at("scene").get<std::string>() != text_)
    throw InputError("Simulation.restore: the state is of another scene text than this simulation's");
  for (const auto& c : h.at("changes")) replay(c);
  scene::EngineSnapshot snap;
  try {
    snap = scene::decode_snapshot(rest, "the saved state", text_);
    engine_->restore(snap.engine);
    contacts_->restore(snap.contacts);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("Simulation.restore: ") + e.what());
  }
  changes_ = h.at("changes");
  load_ids_ = h.at("load_ids").get<std::vector<long>>();
  next_load_id_ = h.at("next_load_id").get<long>();
  const json& history = h.at("history");
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    history_[i].clear();
    for (const auto& v : history.at(columns_[i])) history_[i].push_back(unhex(v));
  }
}

void Simulation::replay(const json& c) {
  const std::string kind = c.at("kind").get<std::string>();
  if (kind == "edit") {
    core::ModelEdit e;
    e.material_points = true;  // the points are material points already (EditReport::replay)
    e.remove_fixed_points = c.at("remove_fixed_points").get<std::vector<int>>();
    e.remove_point_loads = c.at("remove_point_loads").get<std::vector<int>>();
    e.remove_blocks = c.at("remove_blocks").get<std::vector<int>>();
    for (const auto& f : c.at("add_fixed_points")) {
      core::FixedPoint fp{f.at("block").get<int>(), vec2(f.at("point")), vec2(f.at("material_point"))};
      fp.hold_x = f.value("hold_x", true);
      fp.hold_y = f.value("hold_y", true);
      fp.hold_rotation = f.value("hold_rotation", false);
      if (fp.hold_rotation) fp.held_rotation = unhex(f.at("held_rotation"));
      e.add_fixed_points.push_back(fp);
    }
    for (const auto& l : c.at("add_point_loads")) {
      core::PointLoad p;
      p.block = l.at("block").get<int>();
      p.point = vec2(l.at("point"));
      p.history = samples(l.at("history"));
      e.add_point_loads.push_back(std::move(p));
    }
    eng().edit(e);
  } else if (kind == "joint_sets") {
    apply_joint_set_change(0, c.at("text").get<std::string>());
  } else if (kind == "load_history") {
    apply_load_history(c.at("index").get<int>(), samples(c.at("samples")));
  } else if (kind == "settings") {
    core::Model m = next_model();
    const bool dt_changed = apply_settings(m.settings, c.at("values"));
    prepare_engine(std::move(m), dt_changed);
  } else {
    throw InputError("Simulation.restore: the state holds a change of unknown kind '" + kind + "'");
  }
}

void bind_simulation_state(py::class_<Simulation>& c) {
  c.def("_save", &Simulation::save)
      .def("_restore", [](Simulation& s, const py::bytes& b) { s.restore(std::string(b)); }, py::arg("state"))
      .def_static("_state_header", [](const py::bytes& b) { return Simulation::state_header(std::string(b)); },
                  py::arg("state"));
}

}  // namespace rheodda::python
