// The declaration of each `analysis:` key of a scene file, once: its type, unit,
// range, default and meaning, with how it reads and writes its field of
// scene::Analysis. Everything that lists these keys is driven from here: the
// loader (which keys a map accepts, how each value is read and checked), the
// schema (scene_schema()), `rheodda check`'s description, the scene echoed in
// summary.json, the Python module's `Scene.analysis`, and the key tables of
// docs/reference/scene-format.md (`rheodda schema --markdown`, checked by a test).
//
// Why a table of declarations (in the spirit of MOOSE's validParams()): a key
// written in six places drifts; adding one meant finding all six. Adding a key
// now is one entry in keys.cpp (and its field in scene.hpp); checks that tie
// several keys together (dt <= duration, dt_max under a step control, ...)
// stay in the loader's read_analysis.cpp, after every key has been read.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// What a key's value is in the file.
enum class KeyType {
  number,   ///< a finite number within `range`
  integer,  ///< a whole number within `range`
  flag,     ///< true or false
  choice,   ///< one of `choices`
  point,    ///< [x, y]
  map,      ///< a map of keys declared under the path `<map>.<name>`
};

/// A key's value: what a number, integer, flag, choice or point reads as; monostate
/// for a map, or a key of a map the scene does not give (settle without `settle:`).
using KeyValue = std::variant<std::monostate, double, int, bool, std::string, Point>;

/// Valid values of a number or integer key.
struct KeyRange {
  double min = std::numeric_limits<double>::lowest();
  bool min_exclusive = false;
  double max = std::numeric_limits<double>::max();
  bool max_exclusive = false;
};

/// One key of a map of the scene file.
struct KeySpec {
  std::string map;           ///< dotted path of its map: "analysis", "analysis.settle"
  std::string name;          ///< the key: also the C++ field, summary.json key and doc word
  KeyType type = KeyType::number;
  std::string unit;          ///< dimension in the scene's units ("time", "length", "stress", ...), "–" for none
  KeyRange range;            ///< number and integer keys
  std::vector<std::string> choices;  ///< choice keys
  std::string required;      ///< non-empty: the key is required; what to give, for the message
  std::string default_text;  ///< the default, as docs/reference/scene-format.md states it
  std::string meaning;       ///< one table cell of docs/reference/scene-format.md
  /// The value of the key in a read scene (std::monostate: not applicable).
  std::function<KeyValue(const Analysis&)> get;
  /// Stores a value read from the file (of the key's type) into its field.
  std::function<void(Analysis&, const KeyValue&)> set;
};

/// The declared keys of `analysis:` and `analysis.settle`, in the order of the docs.
/// Mutable so that a test (or an extension) can declare one more key and find it in
/// every listing; the program itself only reads it.
std::vector<KeySpec>& analysis_keys();

/// The names of the keys declared for the map `map`, in order.
std::vector<std::string> declared_key_names(const std::string& map);

/// The key's value as text in the scene's units: "0.01 d", "static", "(0, -9.81) m/s^2", "none".
std::string key_value_text(const KeySpec& k, const Analysis& a, const Units& u);

/// The Markdown key table of one map (`| key | unit | meaning | default |`), as
/// docs/reference/scene-format.md holds it between `<!-- keys: MAP -->` markers.
std::string key_table_markdown(const std::string& map);

}  // namespace rheodda::scene
