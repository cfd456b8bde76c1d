// The declaration of each key of a scene file's maps, once: its type, unit,
// range, default and meaning, with how it reads and writes its field of the
// entry it fills (scene::Analysis for `analysis:`, scene::Material for a
// material, scene::BoltDescription for a bolt, ...). Everything that lists these
// keys is driven from here: the loader (which keys a map accepts, how each plain
// value is read and checked), the schema (scene_schema()), `rheodda check`'s
// description, the scene echoed in summary.json, the Python module's `Scene`,
// and the key tables of docs/reference/scene-format.md (`rheodda keys --markdown
// MAP`, spliced by scripts/scene-format-tables.sh, checked by a test).
//
// Why a table of declarations (in the spirit of MOOSE's validParams()): a key
// written in six places drifts; adding one meant finding all six. Adding a key
// now is one entry in keys*.cpp (and its field in its struct); what a
// declaration cannot say (checks that tie several keys together, geometry,
// names of other sections, a law's parameters from the law registry) stays in
// the section's reader (read_*.cpp, load_*.cpp), after the declared keys are read.
//
// Design (docs/design/scene-keys.md): EntryKey<Entry> is one key with its getter
// and setter over its entry type; KeyInfo, its base, is what every key says
// whatever the entry (the type-erased view the schema, the docs tables and
// `rheodda keys` read, through declared_maps()).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "rheodda/laws/setting_spec.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// What a key's value is in the file.
enum class KeyType {
  number,     ///< a finite number within `range`
  integer,    ///< a whole number within `range`
  flag,       ///< true or false
  choice,     ///< one of `choices`
  point,      ///< [x, y]
  numbers,    ///< a list of `count` numbers, any value
  name,       ///< a name: letters, digits, '_', '-', '.'
  text,       ///< any text (a title, a unit's label)
  reference,  ///< the name of an entry of another section (a material, joint set, block)
  list,       ///< a list (of vertices, polygons, samples or entries), read by its section's reader
  named,      ///< a map from names (of joint sets, ...) to entries, read by its section's reader
  map,        ///< a map of keys declared in the map `submap`
};

/// A key's value: what a number, integer, flag, choice, name, point or list of numbers
/// reads as; monostate for a key that is not set (an optional key not given, a key of a
/// sub-map the scene does not give) or that the declaration does not read (a map).
using KeyValue =
    std::variant<std::monostate, double, int, bool, std::string, Point, std::vector<double>, std::int64_t>;

/// Valid values of a number or integer key.
struct KeyRange {
  double min = std::numeric_limits<double>::lowest();
  bool min_exclusive = false;
  double max = std::numeric_limits<double>::max();
  bool max_exclusive = false;
};

/// What one key of a map says, whatever the entry it fills: the view that the schema,
/// the docs tables and `rheodda keys` read (declared_maps()).
struct KeyInfo {
  // Every member has an initializer: the declarations name only the members they set
  // (designated initializers), and -Wextra asks that the others have one.
  std::string map{};           ///< the declared map: "analysis", "analysis.settle", "materials", "bolts.to", ...
  std::string name{};          ///< the key: also the C++ field, summary.json key and doc word
  KeyType type = KeyType::number;
  std::string unit{};          ///< dimension in the scene's units ("time", "length", "stress", ...), "–" for none
  KeyRange range{};            ///< number and integer keys
  std::vector<std::string> choices{};  ///< choice keys
  std::string required{};      ///< non-empty: the key is required; what to give, for the message
  std::string default_text{};  ///< the default, as docs/reference/scene-format.md states it
  std::string meaning{};       ///< one table cell of docs/reference/scene-format.md
  std::size_t count = 0;     ///< numbers keys: how many
  std::string submap{};        ///< map keys: the declared map of its keys (default `<map>.<name>`)
  /// A key of the top level (a section of the file): its keys are in a table of their
  /// own, not listed in this key's meaning.
  bool own_table = false;
  /// summary.json's inputs echo the key (false only for keys it never echoed, so that
  /// every summary.json stays as it was: materials' damping_ratio, joint sets' restitution).
  bool echoed = true;
};

/// One key of a map whose entries are `Entry`s: its declaration and how it reads and
/// writes its field. A key without `set` is read by its section's reader (a map,
/// a list, a reference, a point whose block it must lie on); its `get` may still
/// give its value.
template <class Entry>
struct EntryKey : KeyInfo {
  /// The value of the key in a read entry (std::monostate: not set or not applicable).
  std::function<KeyValue(const Entry&)> get;
  /// Stores a value read from the file (of the key's type) into its field.
  std::function<void(Entry&, const KeyValue&)> set;
};

/// A key of `analysis:` or `analysis.settle`.
using KeySpec = EntryKey<Analysis>;

/// The key `name` of `analysis:` (not of `analysis.settle`); std::logic_error if none is declared.
const KeySpec& analysis_key(const std::string& name);

/// The declaration of one of the scene's own `analysis.accept_*` settings (Acceptances,
/// scene.hpp), in the declaration type of the engine's settings: the keys of the same names
/// are read from them (keys.cpp).
using AcceptanceSpec = laws::SettingSpec<Acceptances>;

/// Every declared acceptance, in the order of the docs.
const std::vector<AcceptanceSpec>& acceptance_specs();

/// The declaration of one of the run's own `analysis:` numbers and flags (RunControls,
/// scene.hpp: duration, output_interval, frames, max_travel_ratio, max_output_size).
using RunControlSpec = laws::SettingSpec<RunControls>;

/// Every declared run control, in the order of the docs.
const std::vector<RunControlSpec>& run_control_specs();

/// The value of a number, integer or flag key as a double (a flag as 0 or 1);
/// std::logic_error for a value of another kind.
double key_number(const KeyValue& v);

/// The value of a number, integer or flag key (`type`) that is `v`.
KeyValue key_value_of(KeyType type, double v);

/// A number or integer key's valid values as text: "(0, 1]", "[1, ∞)"; "" for other keys.
std::string key_range_text(const KeyInfo& k);

/// `rectangle:` or `grid:` of a block as written: the lower-left corner and size
/// [length], the rotation [deg], a grid's counts.
struct BlockShape {
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0, angle = 0.0;
  int columns = 1, rows = 1;
};

// The declared keys of each map, in the order of the docs. Mutable so that a test (or
// an extension) can declare one more key and find it in every listing; the program
// itself only reads them.
std::vector<EntryKey<SceneDescription>>& top_keys();                 ///< top (the file's sections)
std::vector<EntryKey<Units>>& units_keys();                          ///< units
std::vector<KeySpec>& analysis_keys();                               ///< analysis, analysis.settle
std::vector<EntryKey<Material>>& material_keys();                    ///< materials
std::vector<EntryKey<JointSetDescription>>& joint_set_keys();        ///< joint_sets
std::vector<EntryKey<LawChoice>>& law_keys();                        ///< law (of a joint set, bolt, stage)
std::vector<EntryKey<BlockDescription>>& block_keys();               ///< blocks
std::vector<EntryKey<BlockShape>>& rectangle_keys();                 ///< blocks.rectangle
std::vector<EntryKey<BlockShape>>& grid_keys();                      ///< blocks.grid
std::vector<EntryKey<RockMassDescription>>& rock_mass_keys();        ///< rock_mass
std::vector<EntryKey<rockmass::JointSetGeneration>>& rock_mass_joint_set_keys();  ///< rock_mass.joint_sets
std::vector<EntryKey<rockmass::Trace>>& rock_mass_trace_keys();      ///< rock_mass.traces
std::vector<EntryKey<BlockPoint>>& fixed_point_keys();               ///< fixed_points
std::vector<EntryKey<LoadDescription>>& load_keys();                 ///< loads
std::vector<EntryKey<MeasurementPoint>>& measurement_point_keys();   ///< measurement_points
std::vector<EntryKey<WaterDescription>>& water_keys();               ///< water
std::vector<EntryKey<WaterDescription::Sample>>& water_sample_keys();  ///< water.surface_history
std::vector<EntryKey<BoltDescription>>& bolt_keys();                 ///< bolts
std::vector<EntryKey<BlockPoint>>& bolt_end_keys();                  ///< bolts.from
std::vector<EntryKey<BlockPoint>>& bolt_to_keys();                   ///< bolts.to
std::vector<EntryKey<StageDescription>>& stage_keys();               ///< stages
std::vector<EntryKey<StageDescription>>& stage_remove_blocks_keys();  ///< stages.remove_blocks
std::vector<EntryKey<StagePoint>>& stage_fixed_point_keys();         ///< stages.add_fixed_points
std::vector<EntryKey<StagePoint>>& stage_load_keys();                ///< stages.add_loads
std::vector<EntryKey<StageJointSet>>& stage_joint_set_keys();        ///< stages.joint_sets
std::vector<EntryKey<StageDescription>>& stage_analysis_keys();      ///< stages.analysis

/// One declared map: its name (as `rheodda keys` and the docs' markers name it), the
/// schema paths it stands at (a law stands under joint sets, bolts and stages) and its keys.
struct DeclaredMap {
  std::string name;
  std::vector<std::string> schema_paths;
  std::function<std::vector<KeyInfo>()> keys;
};

/// Every declared map, in the order of the docs.
const std::vector<DeclaredMap>& declared_maps();

/// The declarations of the keys of the map `map`, in order (empty for an undeclared map).
std::vector<KeyInfo> declared_keys(const std::string& map);

/// The names of the keys declared for the map `map`, in order.
std::vector<std::string> declared_key_names(const std::string& map);

/// A value as text in the scene's units: "0.01 d", "static", "(0, -9.81) m/s^2", "none".
std::string key_value_text(const KeyInfo& k, const KeyValue& v, const Units& u);

/// The key's value as text in the scene's units.
inline std::string key_value_text(const KeySpec& k, const Analysis& a, const Units& u) {
  return key_value_text(k, k.get(a), u);
}

/// The unit of a key written with the scene's unit labels ("m", "N/m^2", "N*s^2/m^4"); "" for none.
std::string unit_text(const std::string& unit, const Units& u);

/// `rheodda check`'s words for the keys of `map` declared in `keys` that are set in `e`:
/// "density 2700 N*s^2/m^4, young_modulus 1e+10 N/m^2, ...". A key its section's reader
/// reads (no setter: a point on its block, a reference, a list) is in the words `other`
/// gives ("" or no `other`: left out; maps and lists are their reader's to describe).
template <class E>
std::string key_values_text(const std::vector<EntryKey<E>>& keys, const std::string& map, const E& e,
                            const Units& u, const std::function<std::string(const KeyInfo&)>& other = {}) {
  std::string out;
  auto add = [&out](const std::string& name, const std::string& value) {
    out += (out.empty() ? "" : ", ") + name + " " + value;
  };
  for (const EntryKey<E>& k : keys) {
    if (k.map != map) continue;
    if (!k.set && other) {
      if (const std::string t = other(k); !t.empty()) add(k.name, t);
      continue;
    }
    if (k.type == KeyType::map || k.type == KeyType::list || k.type == KeyType::reference ||
        k.type == KeyType::named)
      continue;
    const KeyValue v = k.get(e);
    if (std::holds_alternative<std::monostate>(v)) continue;
    add(k.name, key_value_text(k, v, u));
  }
  return out;
}

/// The keys of `keys` but those named in `described`: what `key_values_text` lists of
/// an entry whose other keys its section describes in words of its own (a joint set's
/// residual strength and stiffnesses, the water's surface).
template <class E>
std::vector<EntryKey<E>> keys_except(const std::vector<EntryKey<E>>& keys, const std::vector<std::string>& described) {
  std::vector<EntryKey<E>> out;
  for (const EntryKey<E>& k : keys)
    if (std::find(described.begin(), described.end(), k.name) == described.end()) out.push_back(k);
  return out;
}

/// The Markdown key table of one map (`| key | unit | range | meaning | default |`), as
/// docs/reference/scene-format.md holds it between `<!-- keys-MAP:begin/end -->` markers.
/// A map key's meaning starts with its keys, `{a, b, ...}`, from their declarations.
std::string key_table_markdown(const std::string& map);

}  // namespace rheodda::scene
