// rheodda.Scene: a validated scene, its keys and values (python/src/scene.hpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <rheodda/scene/describe.hpp>
#include <rheodda/scene/keys.hpp>
#include <rheodda/scene/loader.hpp>

#include <string>
#include <variant>

#include "common.hpp"
#include "scene.hpp"

namespace rheodda::python {

py::dict units_dict(const scene::Units& u) {
  py::dict d;
  d["length"] = u.length;
  d["force"] = u.force;
  d["time"] = u.time;
  d["stress"] = u.stress();
  return d;
}

namespace {

/// A declared key's value in Python: None where it is not set, a tuple for a point.
py::object value_object(const scene::KeyValue& v) {
  return std::visit(
      [](const auto& x) -> py::object {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>)
          return py::none();
        else if constexpr (std::is_same_v<std::decay_t<decltype(x)>, scene::Point>)
          return py::make_tuple(x[0], x[1]);
        else
          return py::cast(x);
      },
      v);
}

/// The declared keys of one map (rheodda/scene/keys.hpp) with their values: None where a
/// key does not apply, a nested dict for a sub-map (`settle`), None for one not given.
py::object analysis_dict(const scene::Analysis& a, const std::string& map) {
  py::dict d;
  bool applies = false;
  for (const scene::KeySpec& k : scene::analysis_keys()) {
    if (k.map != map) continue;
    py::object v = k.type == scene::KeyType::map ? analysis_dict(a, map + "." + k.name) : value_object(k.get(a));
    applies = applies || !v.is_none();
    d[py::str(k.name)] = v;
  }
  return applies ? py::object(d) : py::object(py::none());
}

/// The declared keys of the map `map` with their values in one entry `e` (None: not set).
template <class E>
py::dict entry_dict(const std::vector<scene::EntryKey<E>>& keys, const std::string& map, const E& e) {
  py::dict d;
  for (const scene::EntryKey<E>& k : keys)
    if (k.map == map) d[py::str(k.name)] = value_object(k.get(e));
  return d;
}

/// summary.json's "inputs" (scene::scene_json_text, scene/src/scene_json.cpp) parsed
/// afresh by Python's json module: every section the run writes, with every key and value.
py::dict inputs_of(const Scene& s) {
  return py::module_::import("json").attr("loads")(scene::scene_json_text(s.description));
}

/// The section `key` of the inputs, or `absent` where the scene has none.
py::object section(const Scene& s, const char* key, const py::object& absent) {
  return inputs_of(s).attr("get")(key, absent);
}

/// A list of named entries (blocks, measurement points) as a dict by name, in the list's order.
py::dict by_name(const py::object& entries) {
  py::dict d;
  for (const py::handle e : entries) d[e["name"]] = e;
  return d;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Scene> cls(m, "Scene",
                        "A validated scene (docs/reference/scene-format.md): rheodda.load_scene(path) or "
                        "rheodda.parse_scene(text) or rheodda.scene_from_dict(d)");
  cls.def_property_readonly("file", [](const Scene& s) { return s.description.file; },
                             "the file name the scene was read from (or given to parse_scene)")
      .def_property_readonly("title", [](const Scene& s) { return s.description.title; }, "the scene's title")
      .def_property_readonly("text", [](const Scene& s) { return s.text; },
                             "the scene's YAML text (error lines refer to it)")
      .def_property_readonly("units", [](const Scene& s) { return units_dict(s.description.units); },
                             "the scene's unit names: length, force, time, stress")
      .def_property_readonly("duration", [](const Scene& s) { return s.description.analysis.duration; },
                             "analysis.duration [time]")
      .def_property_readonly("dt", [](const Scene& s) { return s.description.analysis.dt; },
                             "analysis.dt, the first step size [time]")
      .def_property_readonly(
          "analysis", [](const Scene& s) { return analysis_dict(s.description.analysis, "analysis"); },
          "Every `analysis:` key with its value, defaults filled in, by the scene file's names (`settle` a "
          "dict, or None without a settling stage); the same keys and values as summary.json's inputs "
          "(docs/reference/scene-format.md). A copy: change a scene through its text or scene_from_dict.")
      .def_property_readonly(
          "materials",
          [](const Scene& s) {
            py::dict d;
            for (const auto& m : s.description.materials)
              d[py::str(m.name)] = entry_dict(scene::material_keys(), "materials", m);
            return d;
          },
          "Every material by name, with every declared `materials:` key and its value, defaults filled in "
          "(None: not set, e.g. damping_ratio without damping); docs/reference/scene-format.md. A copy.")
      .def_property_readonly("inputs", &inputs_of,
                             "The whole scene as summary.json's `inputs` (docs/reference/outputs.md): every section "
                             "with every key and value, defaults filled in, as the run writes them. A fresh copy "
                             "at each read.")
      .def_property_readonly(
          "joint_sets", [](const Scene& s) { return section(s, "joint_sets", py::dict()); },
          "Every joint set by name, in scene order, with every key and value of summary.json's inputs "
          "(iterating, `in` and len() give the names). A copy.")
      .def_property_readonly(
          "blocks", [](const Scene& s) { return by_name(section(s, "blocks", py::list())); },
          "Every block by name, in scene order (the block index of the state arrays), with every key and "
          "value of summary.json's inputs (iterating, `in` and len() give the names). A copy.")
      .def_property_readonly(
          "measurement_points", [](const Scene& s) { return by_name(section(s, "measurement_points", py::list())); },
          "Every measurement point by name, in scene order, with every key and value of summary.json's "
          "inputs (iterating, `in` and len() give the names). A copy.");
  // The other sections as the inputs write them: a list of dicts (empty where the scene has
  // none) or one dict (None where the scene has none).
  struct Section {
    const char* key;
    bool list;
    const char* doc;
  };
  for (const Section& c :
       {Section{"fixed_points", true, "The fixed points, in scene order, as summary.json's inputs write them. A copy."},
        Section{"loads", true,
                "The loads, in scene order (the indices of Simulation.set_load), as summary.json's inputs write "
                "them. A copy."},
        Section{"bolts", true,
                "The bolts installed from the start (those a stage adds are in stages), as summary.json's inputs "
                "write them (docs/reference/bolts.md); empty without bolts. A copy."},
        Section{"stages", true,
                "The stages, in scene order, as summary.json's inputs write them (docs/reference/stages.md); "
                "empty without stages. A copy."},
        Section{"rock_mass", false,
                "The rock mass the blocks were cut from, as summary.json's inputs write it "
                "(docs/guide/rockmass.md); None where they hold none. A copy."},
        Section{"water", false,
                "The water, as summary.json's inputs write it (docs/reference/water.md); None without water. "
                "A copy."}})
    cls.def_property_readonly(
        c.key, [c](const Scene& s) { return section(s, c.key, c.list ? py::object(py::list()) : py::none()); },
        c.doc);
  cls.def_property_readonly("load_count", [](const Scene& s) { return s.description.loads.size(); },
                             "the number of loads (indices of Simulation.set_load)")
      // pickle and copy: a scene is its text and file name, parsed again (and so validated again).
      .def("__reduce__",
           [](const Scene& s) {
             return py::make_tuple(py::module_::import("rheodda._scripting").attr("_make_scene"),
                                   py::make_tuple(s.text, s.description.file));
           })
      .def("describe", [](const Scene& s) { return scene::describe_scene(s.description); },
           "What `rheodda check` prints: the scene with every default filled in")
      .def("__repr__", [](const Scene& s) {
        return fmt::format("<rheodda.Scene '{}' from {}: {} blocks, {} joint sets>", s.description.title,
                           s.description.file, s.description.blocks.size(), s.description.joint_sets.size());
      });

  m.def(
      "load_scene",
      [](const std::string& path) {
        Scene s;
        s.text = scene::read_scene_text(path);
        s.description = scene::parse_scene(s.text, path);
        return s;
      },
      py::arg("path"), "Reads and validates a scene file; raises rheodda.SceneError (file:line:column: key: ...)");
  m.def(
      "parse_scene",
      [](const std::string& text, const std::string& file) {
        Scene s;
        s.text = text;
        s.description = scene::parse_scene(text, file);
        return s;
      },
      py::arg("text"), py::arg("file") = "<text>",
      "Parses and validates scene text (YAML; JSON is YAML too); `file` names it in error messages");
}

}  // namespace rheodda::python
