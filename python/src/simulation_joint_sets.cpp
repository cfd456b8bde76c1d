// rheodda.Simulation's joint sets (simulation.hpp): their values read from the
// contact system, and changed between steps as a scene's stage changes them
// (docs/reference/scene-format.md, "stages.joint_sets"): the values are read by
// the stage reader (scene/edits.hpp), so a value is refused with the loader's
// key and message, and handed to the engine (ModelEdit::joint_sets).
#include <rheodda/contact/joint_set_specs.hpp>
#include <rheodda/laws/registry.hpp>
#include <rheodda/scene/edits.hpp>

#include "laws.hpp"
#include "simulation.hpp"

namespace rheodda::python {
namespace {

py::object optional(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

/// A Python value as JSON for the loader: numbers, flags and text as they are, NaN and
/// infinities as YAML's .nan and .inf (so that the loader refuses them by its words).
json value_json(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::dict>(v)) {
    json j = json::object();
    for (auto item : v.cast<py::dict>()) j[py::str(item.first).cast<std::string>()] = value_json(item.second);
    return j;
  }
  const double d = v.cast<double>();
  if (std::isnan(d)) return ".nan";
  if (std::isinf(d)) return d > 0 ? ".inf" : "-.inf";
  return d;
}

/// The declared properties of a joint set (contact/joint_set_specs.hpp), in their order:
/// what rheodda.JointSet's properties say of themselves and which of them it may change.
py::list joint_set_properties() {
  py::list out;
  for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
    py::dict e;
    e["name"] = s.name();
    e["unit"] = s.parameter.unit;
    e["range"] = s.range_text();
    e["default"] = s.default_text();
    e["meaning"] = s.parameter.meaning;
    e["between_steps"] = s.between_steps;
    out.append(e);
  }
  return out;
}

}  // namespace

py::dict Simulation::joint_set(int j) const {
  const contact::JointSet& js = contacts_->joint_sets()[static_cast<std::size_t>(j)];
  py::dict d;
  d["name"] = js.name;
  for (const contact::JointPropertySpec& s : contact::joint_property_specs())  // contact/joint_set_specs.hpp
    d[py::str(s.name())] = optional(s.value(js));
  d["law"] = js.law ? py::object(py::str(std::string(js.law->name()))) : py::object(py::none());
  py::dict p;
  if (js.law)
    for (const auto& [k, v] : js.law->parameters()) p[py::str(k)] = v;
  d["law_parameters"] = p;
  return d;
}

void Simulation::change_joint_set(int j, const py::dict& values) {
  if (j < 0 || j >= static_cast<int>(scene_.joint_sets.size()))
    throw InputError(fmt::format("joint set {} does not exist; the scene has {} joint sets", j,
                                 scene_.joint_sets.size()));
  json change = json::object();
  change[scene_.joint_sets[static_cast<std::size_t>(j)].name] = value_json(values);
  apply_joint_set_change(j, change.dump());
}

void Simulation::apply_joint_set_change(int j, const std::string& text) {
  if (failed_) throw RunFailure("the simulation failed earlier (" + failure_ + "); build a new one");
  std::vector<scene::StageJointSet> changes;
  try {
    changes = scene::read_joint_set_changes(scene_, text, "joint_sets", "<Simulation.joint_sets>");
  } catch (const scene::SceneError& e) {
    throw core::ModelError(e.key(), e.message());
  }
  core::ModelEdit e;
  for (const auto& c : changes)
    e.joint_sets.emplace_back(
        c.joint_set, scene::changed_joint_set(contacts_->joint_sets()[static_cast<std::size_t>(c.joint_set)], c));
  const std::string key = "joint_sets." + scene_.joint_sets[static_cast<std::size_t>(j)].name;
  try {
    eng().edit(e);
  } catch (const contact::JointSetError& err) {  // the contact layer's checks (residual above peak ...)
    throw core::ModelError(key + "." + err.key(), err.message());  // as the loader: key, then its message
  } catch (const std::invalid_argument& err) {
    throw core::ModelError(key, err.what());
  }
  changes_.push_back({{"kind", "joint_sets"}, {"text", text}});
}

void Simulation::set_law_parameters(const std::string& name, const py::dict& values) {
  const int j = joint_set_index(name);
  const contact::JointSet& js = contacts_->joint_sets()[static_cast<std::size_t>(j)];
  if (!js.law) throw InputError("set_law_parameters: joint set '" + name + "' has no law");
  const laws::LawInfo* info = laws::LawRegistry::builtin().find(js.law->name());
  if (!info || dynamic_cast<const PythonLaw*>(js.law.get()))
    throw InputError("set_law_parameters: the law of joint set '" + name + "' (" + std::string(js.law->name()) +
                     ") is not a registered law; change a Python law's own attributes instead");
  laws::ParameterValues p = js.law->parameters();
  for (auto item : values) p[item.first.cast<std::string>()] = item.second.cast<double>();
  // The registry's check first: a bad value raises LawError, with the message the loader
  // gives under the law's key (read_law).
  (void)laws::LawRegistry::builtin().create(info->name, p);
  json law = {{"name", info->name}};
  for (const auto& [k, v] : p) law[k] = v;
  json change = json::object();
  change[name] = {{"law", law}};
  apply_joint_set_change(j, change.dump());
}

py::dict Simulation::law_parameters(const std::string& name) const {
  const auto& js = contacts_->joint_sets()[static_cast<std::size_t>(joint_set_index(name))];
  py::dict d;
  if (js.law)
    for (const auto& [k, v] : js.law->parameters()) d[py::str(k)] = v;
  return d;
}

void bind_simulation_joint_sets(py::class_<Simulation>& c) {
  c.def("_joint_set", &Simulation::joint_set, py::arg("index"))
      .def("_change_joint_set", &Simulation::change_joint_set, py::arg("index"), py::arg("values"))
      .def("set_law_parameters", &Simulation::set_law_parameters, py::arg("joint_set"), py::arg("parameters"))
      .def("law_parameters", &Simulation::law_parameters, py::arg("joint_set"))
      .def_static("_joint_set_properties", &joint_set_properties);
}

}  // namespace rheodda::python
