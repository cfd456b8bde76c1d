// Study files (docs/guide/studies.md): reading and checking them (the case scenes are
// built in study_cases.cpp).
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/quantity.hpp"
#include "rheodda/study/study.hpp"
#include "rheodda/units/units.hpp"
#include "rheodda/scene/output.hpp"
#include "study_internal.hpp"
#include "yaml_reader.hpp"  // the scene reader's (scene/src): Ctx, MapReader, location

namespace rheodda::study {
namespace fs = std::filesystem;
namespace {

// A study file is read with the scene reader's YAML helpers (scene/src/yaml_reader.hpp):
// every error names the file, the line and column and the key, as a scene's does.
using scene::detail::Ctx;
using scene::detail::location;

/// The keys of one of the study file's maps, checked as a scene's (scene::detail::MapReader):
/// an unknown key is refused at its place with the valid keys and the nearest of them
/// ("did you mean"), a key given twice at its second place.
void check_keys(const Ctx& ctx, const YAML::Node& map, const std::string& path, std::vector<std::string> valid) {
  (void)scene::detail::MapReader(ctx, map, path, "", std::move(valid));  // no scene map: no handle applies
}

std::string scalar_string(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) ctx.fail(n, key, "expected a text value");
  return n.as<std::string>();
}

double number(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) ctx.fail(n, key, "expected a number");
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    ctx.fail(n, key, fmt::format("'{}' is not a number", n.as<std::string>()));
  }
  if (!std::isfinite(v)) ctx.fail(n, key, "NaN and infinity are not allowed");
  return v;
}

std::string to_yaml(const YAML::Node& n) {
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

std::vector<Override> read_set(const Ctx& ctx, const YAML::Node& set, const std::string& path) {
  if (!set.IsMap()) ctx.fail(set, path, "expected a map of dotted scene keys to values, e.g. {analysis.dt: 0.5}");
  std::vector<Override> out;
  for (const auto& kv : set) {
    const std::string key = scalar_string(ctx, kv.first, path);
    if (key.empty()) ctx.fail(kv.first, path, "empty scene key");
    out.push_back({key, to_yaml(kv.second), location(kv.first)});
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




bool valid_parameter_name(const std::string& s) {
  if (s.empty()) return false;
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) return false;
  return true;
}

/// A whole number >= lo (samples, count, seed).
std::uint64_t whole_number(const Ctx& ctx, const YAML::Node& n, const std::string& key, std::uint64_t lo) {
  const double v = number(ctx, n, key);
  if (v != std::floor(v) || v < static_cast<double>(lo) || v > 9.0e15)
    ctx.fail(n, key, fmt::format("{} is not a whole number >= {}", n.as<std::string>(), lo));
  return static_cast<std::uint64_t>(v);
}

/// `sweep:` (docs/guide/studies.md, "Sweeps"): the method, its draws, and each parameter.
void read_sweep(const Ctx& ctx, const YAML::Node& sw, StudyDescription& s) {
  if (!sw.IsMap()) ctx.fail(sw, "sweep", "expected a map with keys method, parameters (samples, seed)");
  check_keys(ctx, sw, "sweep", {"method", "parameters", "samples", "seed"});
  const std::string method = sw["method"] ? scalar_string(ctx, sw["method"], "sweep.method") : "grid";
  if (method == "grid") s.method = SweepMethod::grid;
  else if (method == "random") s.method = SweepMethod::random;
  else if (method == "latin_hypercube") s.method = SweepMethod::latin_hypercube;
  else ctx.fail(sw["method"], "sweep.method", fmt::format("unknown method '{}'; valid: grid, random, latin_hypercube", method));
  const bool drawn = s.method != SweepMethod::grid;
  if (drawn) {
    if (!sw["samples"]) ctx.fail(sw, "sweep.samples", fmt::format("missing key 'samples' (how many cases the {} method draws)", method));
    s.samples = whole_number(ctx, sw["samples"], "sweep.samples", 1);
    if (s.samples > 100000) ctx.fail(sw["samples"], "sweep.samples", "more than 100000 cases");
    s.seed = sw["seed"] ? whole_number(ctx, sw["seed"], "sweep.seed", 0) : 1;
  } else {
    for (const char* k : {"samples", "seed"})
      if (sw[k]) ctx.fail(sw[k], fmt::format("sweep.{}", k), fmt::format("'{}' is for the random and latin_hypercube methods; a grid takes every combination", k));
  }
  const YAML::Node ps = sw["parameters"];
  if (!ps) ctx.fail(sw, "sweep.parameters", "missing key 'parameters' (the swept scene keys)");
  if (!ps.IsSequence() || ps.size() == 0) ctx.fail(ps, "sweep.parameters", "expected a non-empty list of {name, key, unit, values or range}");
  std::set<std::string> names, keys;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const YAML::Node p = ps[i];
    const std::string at = fmt::format("sweep.parameters[{}]", i);
    if (!p.IsMap()) ctx.fail(p, at, "expected a map {name, key, unit, values or range}");
    check_keys(ctx, p, at, {"name", "key", "unit", "values", "range", "count", "scale"});
    SweepParameter sp;
    sp.where = location(p);
    if (!p["key"]) ctx.fail(p, at + ".key", "missing key 'key' (the dotted scene key, e.g. joint_sets.base.friction_angle)");
    sp.key = scalar_string(ctx, p["key"], at + ".key");
    if (split_key(sp.key).empty()) ctx.fail(p["key"], at + ".key", "malformed scene key (expected e.g. joint_sets.base.friction_angle)");
    if (!keys.insert(sp.key).second) ctx.fail(p["key"], at + ".key", fmt::format("'{}' is swept twice", sp.key));
    if (p["name"]) {
      sp.name = scalar_string(ctx, p["name"], at + ".name");
    } else {
      const auto parts = split_key(sp.key);
      sp.name = parts.back();
    }
    if (!valid_parameter_name(sp.name))
      ctx.fail(p["name"] ? p["name"] : p["key"], at + ".name",
           fmt::format("'{}': a parameter name is letters, digits and '_' (it names cases and a study.csv column)", sp.name));
    if (!names.insert(sp.name).second) ctx.fail(p, at + ".name", fmt::format("parameter name '{}' given twice", sp.name));
    if (!p["unit"]) ctx.fail(p, at + ".unit", "missing key 'unit' (written in study.csv and on the plots; '-' for none)");
    sp.unit = scalar_string(ctx, p["unit"], at + ".unit");
    if (sp.unit.empty() || sp.unit.find_first_of(",\"[]\n") != std::string::npos)
      ctx.fail(p["unit"], at + ".unit", "a unit is non-empty text without ',', '\"', '[' or ']' (e.g. deg, Pa/m, -)");
    if (p["scale"]) {
      const std::string sc = scalar_string(ctx, p["scale"], at + ".scale");
      if (sc != "linear" && sc != "log") ctx.fail(p["scale"], at + ".scale", fmt::format("unknown scale '{}'; valid: linear, log", sc));
      sp.log_scale = sc == "log";
    }
    if (p["values"] && p["range"]) ctx.fail(p["range"], at, "give either 'values' or 'range', not both");
    if (p["values"]) {
      if (drawn) ctx.fail(p["values"], at + ".values", fmt::format("the {} method draws from a 'range: [from, to]'", method));
      if (p["count"]) ctx.fail(p["count"], at + ".count", "'count' spaces a 'range'; 'values' lists them");
      const YAML::Node v = p["values"];
      if (!v.IsSequence() || v.size() == 0) ctx.fail(v, at + ".values", "expected a non-empty list of numbers");
      for (std::size_t k = 0; k < v.size(); ++k) sp.values.push_back(number(ctx, v[k], fmt::format("{}.values[{}]", at, k)));
      if (sp.log_scale)
        for (std::size_t k = 0; k < v.size(); ++k)
          if (sp.values[k] <= 0) ctx.fail(v[k], fmt::format("{}.values[{}]", at, k), "a log scale needs values > 0");
    } else if (p["range"]) {
      const YAML::Node r = p["range"];
      if (!r.IsSequence() || r.size() != 2) ctx.fail(r, at + ".range", "expected [from, to]");
      sp.from = number(ctx, r[0], at + ".range[0]");
      sp.to = number(ctx, r[1], at + ".range[1]");
      if (!(sp.from < sp.to)) ctx.fail(r, at + ".range", fmt::format("from {:g} is not below to {:g}", sp.from, sp.to));
      if (sp.log_scale && sp.from <= 0) ctx.fail(r, at + ".range", "a log scale needs a range above 0");
      if (!drawn) {
        if (!p["count"]) ctx.fail(p, at + ".count", "missing key 'count' (how many values a grid takes in the range, >= 2)");
        const auto n = whole_number(ctx, p["count"], at + ".count", 2);
        if (n > 100000) ctx.fail(p["count"], at + ".count", "more than 100000 values");
        for (std::uint64_t k = 0; k < n; ++k) {
          const double f = static_cast<double>(k) / static_cast<double>(n - 1);
          // Evenly spaced in the value, or in its logarithm; the ends exactly, and the values
          // between to 12 significant digits: a log grid from 1e10 to 1.6e11 takes 8e10, not the
          // 79999999999.99991 of exp(log) (issue 52), a linear one from 0.1 to 0.7 takes 0.3.
          double v = sp.log_scale ? std::exp(std::log(sp.from) + f * (std::log(sp.to) - std::log(sp.from)))
                                  : sp.from + f * (sp.to - sp.from);
          v = std::strtod(fmt::format("{:.12g}", v).c_str(), nullptr);
          if (k == 0) v = sp.from;
          if (k + 1 == n) v = sp.to;
          sp.values.push_back(v);
        }
      } else if (p["count"]) {
        ctx.fail(p["count"], at + ".count", fmt::format("the {} method draws 'sweep.samples' values; 'count' is for a grid", method));
      }
    } else {
      ctx.fail(p, at, drawn ? "missing key 'range' ([from, to] to draw from)" : "missing key 'values' or 'range'");
    }
    s.parameters.push_back(std::move(sp));
  }
}

/// Short text of a value for case names: 6 significant digits, no '+' ("1e+08" -> "1e08").
std::string name_value(double v) {
  std::string t = fmt::format("{:.6g}", v);
  t.erase(std::remove(t.begin(), t.end(), '+'), t.end());
  return t;
}

}  // namespace

namespace detail {

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

/// history.csv columns a scene's run will have (scene::history_columns, the run's own list), plus the
/// derived POINT.displacement (and with a settling stage POINT.displacement_after_settling).
std::set<std::string> output_columns(const scene::SceneDescription& s) {
  const std::vector<std::string> run = scene::history_columns(s);
  std::set<std::string> c(run.begin(), run.end());
  for (const auto& m : s.measurement_points) {
    c.insert(m.name + ".displacement");
    if (s.analysis.has_settle()) c.insert(m.name + ".displacement_after_settling");
  }
  return c;
}

}  // namespace detail

using detail::apply;
using detail::output_columns;

std::vector<std::vector<double>> sweep_values(const std::vector<SweepParameter>& ps, SweepMethod method,
                                              std::size_t samples, std::uint64_t seed) {
  std::vector<std::vector<double>> rows;
  if (ps.empty()) return rows;
  if (method == SweepMethod::grid) {
    std::size_t total = 1;
    for (const auto& p : ps) total *= p.values.size();
    for (std::size_t k = 0; k < total; ++k) {
      std::vector<double> row(ps.size());
      std::size_t rest = k;
      for (std::size_t i = ps.size(); i-- > 0;) {  // the last parameter varies fastest
        row[i] = ps[i].values[rest % ps[i].values.size()];
        rest /= ps[i].values.size();
      }
      rows.push_back(std::move(row));
    }
    return rows;
  }
  std::mt19937_64 gen(seed);
  // A uniform draw in [0, 1) from the top 53 bits (the same on every platform, unlike std::uniform_real_distribution).
  const auto uniform = [&] { return static_cast<double>(gen() >> 11) * 0x1.0p-53; };
  std::vector<std::vector<double>> u(samples, std::vector<double>(ps.size()));
  if (method == SweepMethod::random) {
    for (std::size_t k = 0; k < samples; ++k)
      for (std::size_t i = 0; i < ps.size(); ++i) u[k][i] = uniform();
  } else {  // Latin hypercube: sample k of parameter i lies in stratum perm_i[k] of `samples` equal strata
    for (std::size_t i = 0; i < ps.size(); ++i) {
      std::vector<std::size_t> perm(samples);
      for (std::size_t k = 0; k < samples; ++k) perm[k] = k;
      for (std::size_t k = samples; k-- > 1;) {  // Fisher-Yates
        const auto j = std::min(k, static_cast<std::size_t>(uniform() * static_cast<double>(k + 1)));
        std::swap(perm[k], perm[j]);
      }
      for (std::size_t k = 0; k < samples; ++k)
        u[k][i] = (static_cast<double>(perm[k]) + uniform()) / static_cast<double>(samples);
    }
  }
  for (std::size_t k = 0; k < samples; ++k) {
    std::vector<double> row(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const auto& p = ps[i];
      row[i] = p.log_scale ? std::exp(std::log(p.from) + u[k][i] * (std::log(p.to) - std::log(p.from)))
                           : p.from + u[k][i] * (p.to - p.from);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

StudyDescription parse_study(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw SceneError(file, {e.mark.line + 1, e.mark.column + 1}, "", e.msg);
  }
  const Ctx ctx{file};
  if (!root.IsMap()) ctx.fail(root, "", "a study file is a map with keys scene, outputs, times, cases");
  check_keys(ctx, root, "", {"title", "scene", "set", "outputs", "times", "plot", "frames", "cases", "sweep"});
  StudyDescription s;
  s.file = file;
  s.title = root["title"] ? scalar_string(ctx, root["title"], "title") : fs::path(file).filename().string();
  if (!root["scene"]) ctx.fail(root, "scene", "missing key 'scene' (the base scene file)");
  s.scene = scalar_string(ctx, root["scene"], "scene");
  s.scene_where = location(root["scene"]);
  if (fs::path(s.scene).is_relative()) s.scene = (fs::path(file).parent_path() / s.scene).lexically_normal().string();

  std::vector<Override> common;
  if (root["set"]) common = read_set(ctx, root["set"], "set");
  s.common_count = common.size();

  const YAML::Node outs = root["outputs"];
  if (!outs) ctx.fail(root, "outputs", "missing key 'outputs' (history.csv columns, e.g. [block1_top.u])");
  if (!outs.IsSequence() || outs.size() == 0) ctx.fail(outs, "outputs", "expected a non-empty list of columns");
  for (std::size_t i = 0; i < outs.size(); ++i)
    s.outputs.push_back(scalar_string(ctx, outs[i], fmt::format("outputs[{}]", i)));

  const YAML::Node times = root["times"];
  if (!times) ctx.fail(root, "times", "missing key 'times' (times to read the outputs at, scene time unit)");
  if (!times.IsSequence() || times.size() == 0) ctx.fail(times, "times", "expected a non-empty list of times");
  std::optional<scene::Units> scene_units;  // read from the base scene once a time carries its unit
  for (std::size_t i = 0; i < times.size(); ++i) {
    const std::string key = fmt::format("times[{}]", i);
    const YAML::Node& n = times[i];
    bool with_unit = n.IsScalar();
    if (with_unit) {
      try {
        (void)n.as<double>();
        with_unit = false;
      } catch (const YAML::Exception&) {
      }
    }
    double t = 0.0;
    if (with_unit) {  // "100 d": in the scene's time unit
      if (!scene_units) scene_units = scene::load_scene(s.scene).units;
      try {
        t = scene::scene_number(n.Scalar(), "time", *scene_units);
      } catch (const scene::QuantityError& e) {
        ctx.fail(n, key, e.what());
      }
    } else {
      t = number(ctx, n, key);
    }
    if (t < 0) ctx.fail(times[i], fmt::format("times[{}]", i), fmt::format("{:g} is out of range (>= 0)", t));
    s.times.push_back(t);
  }

  s.plot = s.outputs.front();
  if (root["plot"]) {
    s.plot = scalar_string(ctx, root["plot"], "plot");
    if (std::find(s.outputs.begin(), s.outputs.end(), s.plot) == s.outputs.end())
      ctx.fail(root["plot"], "plot", fmt::format("'{}' is not one of the outputs ({})", s.plot, fmt::join(s.outputs, ", ")));
  }

  if (const YAML::Node f = root["frames"]) {
    bool v = false;
    if (!f.IsScalar() || !YAML::convert<bool>::decode(f, v))
      ctx.fail(f, "frames", "expected true or false (each case also writes contacts.csv and the VTK frames)");
    s.frames = v;
  }

  if (root["sweep"]) read_sweep(ctx, root["sweep"], s);
  const YAML::Node cases = root["cases"];
  if (!cases && !root["sweep"]) ctx.fail(root, "cases", "missing key 'cases' (or a 'sweep')");
  if (cases && (!cases.IsSequence() || cases.size() == 0)) ctx.fail(cases, "cases", "expected a non-empty list of cases");
  std::set<std::string> names;
  for (std::size_t i = 0; cases && i < cases.size(); ++i) {
    const YAML::Node c = cases[i];
    const std::string key = fmt::format("cases[{}]", i);
    if (!c.IsMap()) ctx.fail(c, key, "expected a map {name: ..., set: {...}}");
    check_keys(ctx, c, key, {"name", "set"});
    if (!c["name"]) ctx.fail(c, key + ".name", "missing key 'name'");
    StudyCase sc;
    sc.name = scalar_string(ctx, c["name"], key + ".name");
    if (!valid_case_name(sc.name))
      ctx.fail(c["name"], key + ".name",
           fmt::format("'{}': a case name is a folder name: letters, digits, '_', '-', '.'", sc.name));
    if (!names.insert(sc.name).second) ctx.fail(c["name"], key + ".name", fmt::format("case '{}' given twice", sc.name));
    sc.where = location(c);
    sc.set = common;
    if (c["set"]) {
      auto own = read_set(ctx, c["set"], key + ".set");
      sc.set.insert(sc.set.end(), own.begin(), own.end());
    }
    s.cases.push_back(std::move(sc));
  }
  if (!s.parameters.empty()) {
    if (s.method == SweepMethod::grid) {  // the product counted before it is built (two counts of 1e5: 1e10 rows)
      double product = 1.0;
      for (const auto& p : s.parameters) product *= static_cast<double>(p.values.size());
      if (product > 100000)
        ctx.fail(root["sweep"], "sweep", fmt::format("the grid makes {:g} cases (more than 100000)", product));
    }
    const auto rows = sweep_values(s.parameters, s.method, s.samples, s.seed);
    if (rows.size() > 100000) ctx.fail(root["sweep"], "sweep", fmt::format("the grid makes {} cases (more than 100000)", rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) {
      StudyCase sc;
      sc.where = s.parameters.front().where;
      sc.set = common;
      sc.parameter_values = rows[k];
      std::vector<std::string> name_parts, label;
      for (std::size_t i = 0; i < s.parameters.size(); ++i) {
        const auto& p = s.parameters[i];
        // The values are in the parameter's `unit`: one UDUNITS-2 knows goes with each value
        // into the case scene, whose loader converts it into the scene's units (or refuses
        // another dimension, as a value with its unit in the scene file); a label it does not
        // know ("-", "case") leaves the values in the scene's units.
        const bool with_unit = p.unit != "-" && units::known(p.unit);
        sc.set.push_back({p.key, with_unit ? fmt::format("{} {}", rows[k][i], p.unit) : fmt::format("{}", rows[k][i]),
                          p.where});
        name_parts.push_back(p.name + "-" + name_value(rows[k][i]));
        label.push_back(fmt::format("{} = {:.4g}{}", p.name, rows[k][i], p.unit == "-" ? "" : " " + p.unit));
      }
      // A grid case is named by its values (phi-33_E1-1e08); a drawn one by its number (sample07).
      sc.name = s.method == SweepMethod::grid ? fmt::format("{}", fmt::join(name_parts, "_"))
                                              : drawn_case_name(k, rows.size());
      sc.sweep_label = fmt::format("{}", fmt::join(label, ", "));
      if (!names.insert(sc.name).second)
        ctx.fail(root["sweep"], "sweep",
             fmt::format("two cases are named '{}' (a listed case, or values equal to 6 significant digits)", sc.name));
      s.cases.push_back(std::move(sc));
    }
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

}  // namespace rheodda::study
