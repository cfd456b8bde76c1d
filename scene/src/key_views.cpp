// The declared keys of every map (keys.hpp) seen whatever their entry type: the list of
// declared maps, each map's KeyInfos, their value as text and their Markdown table.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <stdexcept>

#include "rheodda/core/settings.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::scene {

namespace {

/// The KeyInfos of the keys of `map` in a typed list.
template <class E>
std::vector<KeyInfo> infos(const std::vector<EntryKey<E>>& keys, const std::string& map) {
  std::vector<KeyInfo> out;
  for (const EntryKey<E>& k : keys)
    if (k.map == map) out.push_back(k);
  return out;
}

/// A declared map whose keys are those of `map` in the list `list()`.
template <class E>
DeclaredMap declared(const std::string& map, std::vector<std::string> paths, std::vector<EntryKey<E>>& (*list)()) {
  return {map, std::move(paths), [map, list] { return infos(list(), map); }};
}

}  // namespace

const std::vector<DeclaredMap>& declared_maps() {
  static const std::vector<DeclaredMap> maps{
      declared("top", {""}, &top_keys),
      declared("units", {"units"}, &units_keys),
      declared("analysis", {"analysis"}, &analysis_keys),
      declared("analysis.settle", {"analysis.settle"}, &analysis_keys),
      declared("materials", {"materials.*"}, &material_keys),
      declared("joint_sets", {"joint_sets.*"}, &joint_set_keys),
      declared("law", {"joint_sets.*.law", "bolts[*].law", "stages[*].joint_sets.*.law", "stages[*].add_bolts[*].law"},
               &law_keys),
      declared("blocks", {"blocks[*]"}, &block_keys),
      declared("blocks.rectangle", {"blocks[*].rectangle"}, &rectangle_keys),
      declared("blocks.grid", {"blocks[*].grid"}, &grid_keys),
      declared("rock_mass", {"rock_mass"}, &rock_mass_keys),
      declared("rock_mass.joint_sets", {"rock_mass.joint_sets[*]"}, &rock_mass_joint_set_keys),
      declared("rock_mass.traces", {"rock_mass.traces[*]"}, &rock_mass_trace_keys),
      declared("fixed_points", {"fixed_points[*]"}, &fixed_point_keys),
      declared("loads", {"loads[*]"}, &load_keys),
      declared("measurement_points", {"measurement_points[*]"}, &measurement_point_keys),
      declared("water", {"water", "stages[*].water"}, &water_keys),
      declared("water.surface_history", {"water.surface_history[*]"}, &water_sample_keys),
      declared("bolts", {"bolts[*]", "stages[*].add_bolts[*]"}, &bolt_keys),
      declared("bolts.from", {"bolts[*].from", "stages[*].add_bolts[*].from"}, &bolt_end_keys),
      declared("bolts.to", {"bolts[*].to", "stages[*].add_bolts[*].to"}, &bolt_to_keys),
      declared("stages", {"stages[*]"}, &stage_keys),
      declared("stages.remove_blocks", {"stages[*].remove_blocks"}, &stage_remove_blocks_keys),
      declared("stages.add_fixed_points", {"stages[*].add_fixed_points[*]"}, &stage_fixed_point_keys),
      declared("stages.add_loads", {"stages[*].add_loads[*]"}, &stage_load_keys),
      declared("stages.joint_sets", {"stages[*].joint_sets.*"}, &stage_joint_set_keys),
      declared("stages.analysis", {"stages[*].analysis"}, &stage_analysis_keys),
  };
  return maps;
}

std::vector<KeyInfo> declared_keys(const std::string& map) {
  for (const DeclaredMap& m : declared_maps())
    if (m.name == map) return m.keys();
  return {};
}

std::vector<std::string> declared_key_names(const std::string& map) {
  std::vector<std::string> names;
  for (const KeyInfo& k : declared_keys(map)) names.push_back(k.name);
  return names;
}

std::string unit_text(const std::string& unit, const Units& u) {
  if (unit == "time") return u.time;
  if (unit == "length") return u.length;
  if (unit == "force") return u.force;
  if (unit == "stress") return u.stress();
  if (unit == "force/length") return u.force + "/" + u.length;
  if (unit == "stress/length") return u.stress() + "/" + u.length;
  if (unit == "stress*time/length") return u.stress() + "*" + u.time + "/" + u.length;  // a law's viscosity
  if (unit == "length/time²") return u.length + "/" + u.time + "^2";
  if (unit == "mass/length³") return u.force + "*" + u.time + "^2/" + u.length + "^4";
  if (unit == "force/length³") return u.force + "/" + u.length + "^3";
  if (unit == "length^2") return u.length + "^2";
  if (unit == "–") return "";
  return unit;  // deg, MB: the same in every scene
}

std::string key_value_text(const KeyInfo& k, const KeyValue& v, const Units& u) {
  const std::string unit = unit_text(k.unit, u);
  const std::string suffix = unit.empty() ? "" : " " + unit;
  if (const auto* d = std::get_if<double>(&v)) return fmt::format("{:g}{}", *d, suffix);
  if (const auto* i = std::get_if<int>(&v)) return fmt::format("{}{}", *i, suffix);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return fmt::format("{}{}", *i, suffix);
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* p = std::get_if<Point>(&v)) return fmt::format("({:g}, {:g}){}", (*p)[0], (*p)[1], suffix);
  if (const auto* x = std::get_if<std::vector<double>>(&v)) return fmt::format("({:g}){}", fmt::join(*x, ", "), suffix);
  return "none";
}

const KeySpec& analysis_key(const std::string& name) {
  for (const KeySpec& k : analysis_keys())
    if (k.map == "analysis" && k.name == name) return k;
  throw std::logic_error("analysis: declares no key " + name);
}

double key_number(const KeyValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<int>(&v)) return *i;
  if (const auto* b = std::get_if<bool>(&v)) return *b ? 1.0 : 0.0;
  throw std::logic_error("key_number: not the value of a number, integer or flag key");
}

KeyValue key_value_of(KeyType type, double v) {
  switch (type) {
    case KeyType::number: return v;
    case KeyType::integer: return static_cast<int>(v);
    case KeyType::flag: return v != 0.0;
    default: throw std::logic_error("key_value_of: not a number, integer or flag key");
  }
}

std::string key_range_text(const KeyInfo& k) {
  if (k.type != KeyType::number && k.type != KeyType::integer) return "";
  auto bound = [&k](double v) {
    if (v == std::numeric_limits<double>::max()) return std::string("∞");
    if (v == std::numeric_limits<double>::lowest()) return std::string("−∞");
    return k.type == KeyType::integer && std::abs(v) < 1e6 ? fmt::format("{:.0f}", v) : core::setting_number_text(v);
  };
  const KeyRange& r = k.range;
  if (r.min == std::numeric_limits<double>::lowest() && r.max == std::numeric_limits<double>::max()) return "";  // any value
  const bool low_open = r.min_exclusive || r.min == std::numeric_limits<double>::lowest();
  const bool high_open = r.max_exclusive || r.max == std::numeric_limits<double>::max();
  return fmt::format("{}{}, {}{}", low_open ? "(" : "[", bound(r.min), bound(r.max), high_open ? ")" : "]");
}

std::string key_table_markdown(const std::string& map) {
  std::string out = "| key | unit | range | meaning | default |\n|---|---|---|---|---|\n";
  for (const KeyInfo& k : declared_keys(map)) {
    std::string meaning = k.meaning;
    if (k.type == KeyType::map && !k.own_table) {
      // The sub-map's keys, from their declarations (schema_test reads them from here).
      const std::vector<std::string> sub = declared_key_names(k.submap.empty() ? map + "." + k.name : k.submap);
      meaning = fmt::format("`{{{}}}`: {}", fmt::join(sub, ", "), meaning);
    }
    out += fmt::format("| `{}` | {} | {} | {} | {} |\n", k.name, k.unit, key_range_text(k), meaning, k.default_text);
  }
  return out;
}

}  // namespace rheodda::scene
