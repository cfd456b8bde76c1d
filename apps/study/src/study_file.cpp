// Study files (docs/studies.md): reading, checking, and building the case scenes.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "rheodda/scene/loader.hpp"
#include "rheodda/study/study.hpp"

namespace rheodda::study {
namespace fs = std::filesystem;
namespace {

SourceLocation where_of(const YAML::Node& n) {
  const YAML::Mark m = n.Mark();
  if (m.is_null()) return {};
  return {m.line + 1, m.column + 1};
}

[[noreturn]] void fail(const std::string& file, const YAML::Node& n, const std::string& key, const std::string& msg) {
  throw SceneError(file, where_of(n), key, msg);
}

void check_keys(const std::string& file, const YAML::Node& map, const std::string& path,
                const std::vector<std::string>& valid) {
  for (const auto& kv : map) {
    const auto k = kv.first.as<std::string>();
    if (std::find(valid.begin(), valid.end(), k) == valid.end())
      fail(file, kv.first, path.empty() ? k : path + "." + k,
           fmt::format("unknown key '{}'; valid keys here: {}", k, fmt::join(valid, ", ")));
  }
}

std::string scalar_string(const std::string& file, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) fail(file, n, key, "expected a text value");
  return n.as<std::string>();
}

double number(const std::string& file, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) fail(file, n, key, "expected a number");
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(file, n, key, fmt::format("'{}' is not a number", n.as<std::string>()));
  }
  if (!std::isfinite(v)) fail(file, n, key, "NaN and infinity are not allowed");
  return v;
}

std::string to_yaml(const YAML::Node& n) {
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

std::vector<Override> read_set(const std::string& file, const YAML::Node& set, const std::string& path) {
  if (!set.IsMap()) fail(file, set, path, "expected a map of dotted scene keys to values, e.g. {analysis.dt: 0.5}");
  std::vector<Override> out;
  for (const auto& kv : set) {
    const std::string key = scalar_string(file, kv.first, path);
    if (key.empty()) fail(file, kv.first, path, "empty scene key");
    out.push_back({key, to_yaml(kv.second), where_of(kv.first)});
  }
  return out;
}

bool valid_case_name(const std::string& s) {
  if (s.empty() || s == "." || s == "..") return false;
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.')) return false;
  return true;
}

/// Splits "a.b[c].d" into {"a", "b", "[c]", "d"}.
std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::string cur;
  for (std::size_t i = 0; i < key.size(); ++i) {
    const char ch = key[i];
    if (ch == '.') {
      if (!cur.empty()) parts.push_back(cur);
      cur.clear();
    } else if (ch == '[') {
      if (!cur.empty()) parts.push_back(cur);
      const auto close = key.find(']', i);
      if (close == std::string::npos) return {};
      parts.push_back(key.substr(i, close - i + 1));
      cur.clear();
      i = close;
    } else {
      cur += ch;
    }
  }
  if (!cur.empty()) parts.push_back(cur);
  return parts;
}

/// Applies one override to the scene tree; throws SceneError at the override.
void apply(YAML::Node root, const Override& o, const std::string& file, const std::string& case_key) {
  const auto bad = [&](const std::string& msg) -> void {
    throw SceneError(file, o.where, case_key + "." + o.key, msg);
  };
  const auto parts = split_key(o.key);
  if (parts.empty()) bad("malformed scene key (expected e.g. joint_sets.base.friction_angle or blocks[block3].fixed)");
  YAML::Node value;
  try {
    value = YAML::Load(o.value_yaml);
  } catch (const YAML::Exception& e) {
    bad(e.what());
  }
  YAML::Node cur = root;
  std::string walked;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    const bool last = i + 1 == parts.size();
    if (p.front() == '[') {
      const std::string inner = p.substr(1, p.size() - 2);
      if (!cur.IsSequence()) bad(fmt::format("'{}' is not a list in the base scene", walked));
      YAML::Node found;
      std::size_t index = 0;
      const bool numeric = !inner.empty() && inner.find_first_not_of("0123456789") == std::string::npos;
      if (numeric) {
        index = std::stoul(inner);
        if (index >= cur.size()) bad(fmt::format("'{}' has {} elements, no [{}]", walked, cur.size(), inner));
      } else {
        bool hit = false;
        for (std::size_t k = 0; k < cur.size(); ++k) {
          const YAML::Node e = cur[k];
          if (e.IsMap() && e["name"] && e["name"].IsScalar() && e["name"].as<std::string>() == inner) {
            index = k;
            hit = true;
            break;
          }
        }
        if (!hit) bad(fmt::format("no element named '{}' in '{}' of the base scene", inner, walked));
      }
      walked += p;
      if (last) {
        cur[index] = value;
      } else {
        YAML::Node next = cur[index];
        cur.reset(next);
      }
    } else {
      if (!cur.IsMap()) bad(fmt::format("'{}' is not a map in the base scene", walked.empty() ? "the scene" : walked));
      walked += (walked.empty() ? "" : ".") + p;
      if (last) {
        if (value.IsNull()) {  // `~` removes the key (e.g. a joint set's law)
          if (!cur[p]) bad(fmt::format("the base scene has no '{}' to remove", walked));
          cur.remove(p);
        } else {
          cur[p] = value;  // a new key is allowed here; the scene loader then checks it
        }
      } else {
        if (!cur[p]) bad(fmt::format("the base scene has no '{}'", walked));
        YAML::Node next = cur[p];
        cur.reset(next);
      }
    }
  }
}

/// history.csv columns a scene's run will have (docs/outputs.md), plus the derived POINT.displacement.
std::set<std::string> history_columns(const scene::SceneDescription& s) {
  std::set<std::string> c{"time", "step", "dt", "cuts", "iterations"};
  for (const auto& m : s.measurement_points)
    for (const char* f : {".u", ".v", ".displacement"}) c.insert(m.name + f);
  for (const auto& j : s.joint_sets)
    if (j.record)
      for (const char* f : {".contacts", ".shear_displacement", ".shear_force", ".shear_displacement_magnitude"})
        c.insert(j.name + f);
  return c;
}

}  // namespace

StudyDescription parse_study(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw SceneError(file, {e.mark.line + 1, e.mark.column + 1}, "", e.msg);
  }
  if (!root.IsMap()) fail(file, root, "", "a study file is a map with keys scene, outputs, times, cases");
  check_keys(file, root, "", {"title", "scene", "set", "outputs", "times", "plot", "cases"});
  StudyDescription s;
  s.file = file;
  s.title = root["title"] ? scalar_string(file, root["title"], "title") : fs::path(file).filename().string();
  if (!root["scene"]) fail(file, root, "scene", "missing key 'scene' (the base scene file)");
  s.scene = scalar_string(file, root["scene"], "scene");
  s.scene_where = where_of(root["scene"]);
  if (fs::path(s.scene).is_relative()) s.scene = (fs::path(file).parent_path() / s.scene).lexically_normal().string();

  std::vector<Override> common;
  if (root["set"]) common = read_set(file, root["set"], "set");
  s.common_count = common.size();

  const YAML::Node outs = root["outputs"];
  if (!outs) fail(file, root, "outputs", "missing key 'outputs' (history.csv columns, e.g. [block1_top.u])");
  if (!outs.IsSequence() || outs.size() == 0) fail(file, outs, "outputs", "expected a non-empty list of columns");
  for (std::size_t i = 0; i < outs.size(); ++i)
    s.outputs.push_back(scalar_string(file, outs[i], fmt::format("outputs[{}]", i)));

  const YAML::Node times = root["times"];
  if (!times) fail(file, root, "times", "missing key 'times' (times to read the outputs at, scene time unit)");
  if (!times.IsSequence() || times.size() == 0) fail(file, times, "times", "expected a non-empty list of times");
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = number(file, times[i], fmt::format("times[{}]", i));
    if (t < 0) fail(file, times[i], fmt::format("times[{}]", i), fmt::format("{:g} is out of range (>= 0)", t));
    s.times.push_back(t);
  }

  s.plot = s.outputs.front();
  if (root["plot"]) {
    s.plot = scalar_string(file, root["plot"], "plot");
    if (std::find(s.outputs.begin(), s.outputs.end(), s.plot) == s.outputs.end())
      fail(file, root["plot"], "plot", fmt::format("'{}' is not one of the outputs ({})", s.plot, fmt::join(s.outputs, ", ")));
  }

  const YAML::Node cases = root["cases"];
  if (!cases) fail(file, root, "cases", "missing key 'cases'");
  if (!cases.IsSequence() || cases.size() == 0) fail(file, cases, "cases", "expected a non-empty list of cases");
  std::set<std::string> names;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const YAML::Node c = cases[i];
    const std::string key = fmt::format("cases[{}]", i);
    if (!c.IsMap()) fail(file, c, key, "expected a map {name: ..., set: {...}}");
    check_keys(file, c, key, {"name", "set"});
    if (!c["name"]) fail(file, c, key + ".name", "missing key 'name'");
    StudyCase sc;
    sc.name = scalar_string(file, c["name"], key + ".name");
    if (!valid_case_name(sc.name))
      fail(file, c["name"], key + ".name",
           fmt::format("'{}': a case name is a folder name: letters, digits, '_', '-', '.'", sc.name));
    if (!names.insert(sc.name).second) fail(file, c["name"], key + ".name", fmt::format("case '{}' given twice", sc.name));
    sc.where = where_of(c);
    sc.set = common;
    if (c["set"]) {
      auto own = read_set(file, c["set"], key + ".set");
      sc.set.insert(sc.set.end(), own.begin(), own.end());
    }
    s.cases.push_back(std::move(sc));
  }
  return s;
}

StudyDescription load_study(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, {}, "", fmt::format("cannot open {}: {}", path, std::strerror(errno)));
  std::ostringstream b;
  b << in.rdbuf();
  return parse_study(b.str(), path);
}

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

std::string case_scene_text(const StudyDescription& study, const std::string& base_text, const StudyCase& c) {
  YAML::Node root = YAML::Load(base_text);
  for (const auto& o : c.set) apply(root, o, study.file, fmt::format("cases[{}].set", c.name));
  // A case scene is not the base scene: its title (run summary, summary.json, plots) says what changed.
  bool own_title = false;
  for (const auto& o : c.set) own_title = own_title || o.key == "title";
  if (!own_title) {
    const YAML::Node t = YAML::Load(base_text)["title"];
    const std::string base = t && t.IsScalar() ? t.as<std::string>() : fs::path(study.scene).filename().string();
    root["title"] = case_title(base, c, study.common_count);
  }
  YAML::Emitter e;
  e << root;
  std::string head = fmt::format("# Case '{}' of the study {}: the scene {}", c.name, study.file, study.scene);
  for (const auto& o : c.set) head += fmt::format("\n#   {}: {}", o.key, o.value_yaml);
  return head + "\n" + e.c_str() + "\n";
}

std::vector<std::string> prepare_cases(const StudyDescription& study) {
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
    const auto columns = history_columns(s);
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
