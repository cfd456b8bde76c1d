// A study's case scenes (docs/guide/studies.md, "What a case writes"): the base scene with
// the case's overrides and outputs, its title, and every case checked as a scene before any runs.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/study/study.hpp"
#include "study_internal.hpp"

namespace rheodda::study {

namespace fs = std::filesystem;

using detail::apply;
using detail::output_columns;

std::string case_title(const std::string& base_title, const StudyCase& c, std::size_t common_count) {
  std::vector<std::string> changes;
  const std::size_t common = std::min(common_count, c.set.size());
  auto describe = [&](const Override& o) {
    bool removed = false;
    try {
      removed = YAML::Load(o.value_yaml).IsNull();
    } catch (const YAML::Exception&) {
    }
    changes.push_back(removed ? o.key + " removed" : o.key + " = " + o.value_yaml);
  };
  for (std::size_t i = common; i < c.set.size(); ++i) describe(c.set[i]);
  for (std::size_t i = 0; i < common; ++i) describe(c.set[i]);
  if (changes.empty()) return fmt::format("{} [case {}]", base_title, c.name);
  return fmt::format("{} [case {}: {}]", base_title, c.name, fmt::join(changes, ", "));
}

namespace {

/// What a case writes (docs/guide/studies.md, "What a case writes"): a row of history.csv
/// at each of the study's times within the case's duration (analysis.output_times), and
/// no frames unless the study or the case asks for them (analysis.frames).
void case_outputs(const StudyDescription& study, const StudyCase& c, YAML::Node root) {
  YAML::Node a = root["analysis"];
  if (!a || !a.IsMap()) return;  // the loader says what is wrong with the scene
  double duration = 0.0;
  std::vector<std::pair<double, std::string>> times;  // (value, text as the file gives it)
  try {
    duration = a["duration"].as<double>();
    if (const YAML::Node given = a["output_times"]) {
      if (!given.IsSequence()) return;
      for (const YAML::Node& t : given) times.emplace_back(t.as<double>(), t.Scalar());
    }
  } catch (const YAML::Exception&) {
    return;
  }
  for (double t : study.times)
    if (t > 0.0 && t <= duration) times.emplace_back(t, scene::exact_number(t));
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), [](const auto& x, const auto& y) { return x.first == y.first; }),
              times.end());
  if (!times.empty()) {
    YAML::Node list(YAML::NodeType::Sequence);
    list.SetStyle(YAML::EmitterStyle::Flow);
    for (const auto& t : times) list.push_back(t.second);
    a["output_times"] = list;
  }
  const bool case_sets_frames = std::any_of(c.set.begin(), c.set.end(), [](const Override& o) { return o.key == "analysis.frames"; });
  if (!case_sets_frames) a["frames"] = study.frames;
}

}  // namespace

std::string case_scene_text(const StudyDescription& study, const std::string& base_text, const StudyCase& c) {
  YAML::Node root = YAML::Load(base_text);
  for (const auto& o : c.set) apply(root, o, study.file, fmt::format("cases[{}].set", c.name));
  case_outputs(study, c, root);
  // A case scene is not the base scene: its title (run summary, summary.json, plots) says what changed.
  bool own_title = false;
  for (const auto& o : c.set) own_title = own_title || o.key == "title";
  if (!own_title) {
    const YAML::Node t = YAML::Load(base_text)["title"];
    const std::string base = t && t.IsScalar() ? t.as<std::string>() : fs::path(study.scene).filename().string();
    // A swept case's title is short: the base title and the parameter values.
    root["title"] = c.sweep_label.empty() ? case_title(base, c, study.common_count)
                                          : fmt::format("{} [{}]", base, c.sweep_label);
  }
  YAML::Emitter e;
  e << root;
  std::string head = fmt::format("# Case '{}' of the study {}: the scene {}", c.name, study.file, study.scene);
  for (const auto& o : c.set) head += fmt::format("\n#   {}: {}", o.key, o.value_yaml);
  return head + "\n" + e.c_str() + "\n";
}

std::string case_scene_body(const std::string& text) {
  std::size_t at = 0;
  while (at < text.size() && text[at] == '#') {
    const std::size_t end = text.find('\n', at);
    at = end == std::string::npos ? text.size() : end + 1;
  }
  return text.substr(at);
}

std::string drawn_case_name(std::size_t k, std::size_t count) {
  const int width = std::max(2, static_cast<int>(std::to_string(count).size()));
  return fmt::format("sample{:0{}}", k + 1, width);
}

std::vector<std::string> prepare_cases(const StudyDescription& study, const volatile std::sig_atomic_t* stop) {
  std::string base_text;
  {
    std::ifstream in(study.scene, std::ios::binary);
    if (!in)
      throw SceneError(study.file, study.scene_where, "scene",
                       fmt::format("cannot open {}: {}", study.scene, std::strerror(errno)));
  }
  try {
    base_text = scene::read_scene_text(study.scene);
    (void)scene::parse_scene(base_text, study.scene);  // the base scene's own faults are reported in its own file
  } catch (const SceneError& e) {
    if (!e.file().empty() && e.file() == study.scene && e.line() > 0) throw;
    throw SceneError(study.file, {}, "scene", e.what());
  }
  std::vector<std::string> texts;
  for (const auto& c : study.cases) {
    if (stop && *stop != 0) return texts;
    std::string text = case_scene_text(study, base_text, c);
    scene::SceneDescription s;
    try {
      s = scene::parse_scene(text, fmt::format("case {}", c.name));
    } catch (const SceneError& e) {
      // Locate the fault at the override whose key it falls under, else at the case.
      SourceLocation at = c.where;
      std::string key = fmt::format("cases[{}]", c.name);
      for (const auto& o : c.set)
        if (e.key() == o.key || e.key().rfind(o.key + ".", 0) == 0 || e.key().rfind(o.key + "[", 0) == 0) {
          at = o.where;
          key = fmt::format("cases[{}].set.{}", c.name, o.key);
        }
      throw SceneError(study.file, at, key, fmt::format("case '{}' is not a valid scene: {}: {}", c.name, e.key(), e.message()));
    }
    const auto columns = output_columns(s);
    for (std::size_t i = 0; i < study.outputs.size(); ++i)
      if (!columns.count(study.outputs[i]))
        throw SceneError(study.file, c.where, fmt::format("outputs[{}]", i),
                         fmt::format("case '{}' has no history column '{}'; its columns: {}", c.name,
                                     study.outputs[i], fmt::join(columns, ", ")));
    for (double t : study.times)
      if (t > s.analysis.duration * (1 + 1e-12))
        throw SceneError(study.file, c.where, "times",
                         fmt::format("time {:g} is after the end of case '{}' (duration {:g})", t, c.name,
                                     s.analysis.duration));
    texts.push_back(std::move(text));
  }
  return texts;
}

}  // namespace rheodda::study
