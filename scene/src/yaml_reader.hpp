// Reading a scene file's YAML: the map reader that knows each map's valid keys (which
// its reader looks up by handle, key_names.hpp), and the typed readers of numbers (with
// their range and unit), words, flags, choices, points and polygons, each failing with
// file:line:col and the key (SceneError).
// Internal to the loader (scene/src/read_*.cpp) and study/src/study_file.cpp; not installed.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "key_names.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene::detail {

// Guards against absurd sizes (a typo such as `columns: 1e9`): generous for real scenes.
constexpr std::size_t kMaxBlocks = 200000;
constexpr std::size_t kMaxVertices = 10000;
constexpr std::size_t kMaxSamples = 1000000;

/// The line and column (1-based) of a node; {} for an undefined node.
SourceLocation location(const YAML::Node& n);

/// The file being read: every error names it.
struct Ctx {
  std::string file;
  /// The scene's units once `units:` is read: a value written with a unit of its own is
  /// converted into them (read_quantity.cpp); null before, or where no scene is read.
  const Units* units = nullptr;
  /// Where the values written with a unit are recorded (`rheodda check` shows them); may be null.
  std::vector<GivenQuantity>* given = nullptr;
  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& msg) const {
    throw SceneError(file, location(n), key, msg);
  }
  [[noreturn]] void fail(SourceLocation where, const std::string& key,
                         const std::string& msg) const {
    throw SceneError(file, where, key, msg);
  }
};

/// "a, b, c".
std::string join(const std::vector<std::string>& v);
/// What a node is, in words ("a list", "a map", ...), for messages.
const char* type_word(const YAML::Node& n);

/// One YAML map with a fixed set of valid keys.
class MapReader {
 public:
  /// The map at `path` in the file ("stages[2].water"), whose keys are `allowed`: those
  /// of the declared map `map` (keys.hpp: "water", "analysis.settle", ...), which the
  /// handles of that map look up (key_names.hpp); or, `map` empty, names the file gives
  /// (the materials, the joint sets) or keys of another file (a study's), which no
  /// handle names and the reader asks for by name (find_named, child_named).
  MapReader(const Ctx& ctx, const YAML::Node& node, std::string path, std::string map,
            std::vector<std::string> allowed)
      : ctx_(ctx), node_(node), path_(std::move(path)), map_(std::move(map)), allowed_(std::move(allowed)) {
    if (!node.IsMap())
      ctx.fail(node, path_, fmt::format("expected a map of keys ({}), got {}", join(allowed_),
                                        type_word(node)));
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node k = it->first;
      if (!k.IsScalar()) ctx.fail(k, path_, "a key must be a plain word");
      const std::string key = k.Scalar();
      if (std::find(allowed_.begin(), allowed_.end(), key) == allowed_.end()) {
        const std::string hint = laws::nearest_name(key, allowed_);
        ctx.fail(k, path_of(key),
                 fmt::format("unknown key '{}'{}; valid keys here: {}", key,
                             hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                             join(allowed_)));
      }
      for (const auto& e : entries_)
        if (e.key == key)
          ctx.fail(k, path_of(key), fmt::format("key '{}' is given twice (first at line {})", key,
                                                location(e.key_node).line));
      entries_.push_back({key, k, it->second});
    }
  }

  const YAML::Node& node() const { return node_; }
  SourceLocation where() const { return location(node_); }
  /// The declared map whose keys this map holds ("" for a map of names).
  const std::string& map() const { return map_; }

  // A reader's cross-key checks look keys up by handle (key_names.hpp), so that a word
  // the map does not declare cannot be written; a handle of another map throws
  // std::logic_error (the word may name another key there, or none).

  /// The path of the key `key` of this map ("analysis.dt").
  std::string child(KeyName key) const { return child_named(word_of(key)); }
  /// The value of `key`, or an undefined node.
  YAML::Node find(KeyName key) const { return find_named(word_of(key)); }
  bool has(KeyName key) const { return find(key).IsDefined(); }
  /// The value of `key`, refused with `what` to give when the file does not give it.
  YAML::Node required(KeyName key, const std::string& what) const { return required_named(word_of(key), what); }

  // The same by a name known only at run time: what the generic readers ask for (each
  // declared key of a map in turn, read_keys.hpp; an engine setting by its name), and
  // the maps of names the file gives (a material, a law's parameter, a key an error
  // names). `key` must be one of the map's keys (its declared keys, or a name the file
  // gave): another word throws std::logic_error instead of finding nothing.

  std::string child_named(std::string_view key) const {
    check_declared(key);
    return path_of(key);
  }
  YAML::Node find_named(std::string_view key) const {
    check_declared(key);
    for (const auto& e : entries_)
      if (e.key == key) return e.value;
    return YAML::Node(YAML::NodeType::Undefined);
  }
  bool has_named(std::string_view key) const { return find_named(key).IsDefined(); }
  YAML::Node required_named(std::string_view key, const std::string& what) const {
    YAML::Node v = find_named(key);
    if (!v.IsDefined())
      ctx_.fail(node_, child_named(key), fmt::format("missing required key '{}' ({})", key, what));
    return v;
  }
  /// Key nodes in file order (for maps of named items).
  const auto& entries() const { return entries_; }

 private:
  std::string path_of(std::string_view key) const {
    return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
  }
  std::string_view word_of(KeyName key) const {
    if (key.map() != map_)
      throw std::logic_error(fmt::format("{}: the reader asks for '{}' by a handle of the map '{}', not of this "
                                         "map ('{}')",
                                         path_.empty() ? "the file" : path_, key.word(), key.map(), map_));
    return key.word();
  }
  void check_declared(std::string_view key) const {
    if (std::find(allowed_.begin(), allowed_.end(), key) == allowed_.end())
      throw std::logic_error(fmt::format("{}: the reader asks for '{}', which is not a key of this map ({})",
                                         path_.empty() ? "the file" : path_, key, join(allowed_)));
  }
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };
  const Ctx& ctx_;
  YAML::Node node_;
  std::string path_;
  std::string map_;
  std::vector<std::string> allowed_;
  std::vector<Entry> entries_;
};

/// Valid range of a number; `unit` goes into messages.
struct Range {
  double min = std::numeric_limits<double>::lowest();
  bool min_exclusive = false;
  double max = std::numeric_limits<double>::max();
  bool max_exclusive = false;
  const char* unit = "";
};

inline Range positive(const char* unit) { return {0.0, true, std::numeric_limits<double>::max(), false, unit}; }
inline Range non_negative(const char* unit) { return {0.0, false, std::numeric_limits<double>::max(), false, unit}; }
inline Range any(const char* unit) { return {std::numeric_limits<double>::lowest(), false, std::numeric_limits<double>::max(), false, unit}; }

/// "[min, max)" with inf for the open ends.
std::string range_text(const Range& r);
/// A plain decimal number read by std::from_chars, or nullopt (then yaml-cpp reads it).
std::optional<double> plain_number(const std::string& s);
/// A finite number in range r; the error names the key and the unit. A bare number is in
/// the scene's units; "2600 kg/m^3" (a number and a unit) is converted into them from the
/// unit it is written in when r.unit names a dimension ("mass/length^3"; read_quantity).
double number(const Ctx& ctx, const YAML::Node& n, const std::string& key, const Range& r);
/// The number of "VALUE UNIT" (`text`, as written) of `dimension` ("stress", "" for none)
/// in the scene's units, recorded in ctx.given; refused at the node, naming both
/// dimensions, when its unit is of another dimension (read_quantity.cpp).
double quantity(const Ctx& ctx, const YAML::Node& n, const std::string& key, const std::string& text,
                const std::string& dimension);
/// A whole number in [min, max].
int integer(const Ctx& ctx, const YAML::Node& n, const std::string& key, int min, int max);
/// A non-empty word.
std::string text(const Ctx& ctx, const YAML::Node& n, const std::string& key);
/// A name that can head a CSV column: letters, digits, '_', '-', '.'.
std::string name_text(const Ctx& ctx, const YAML::Node& n, const std::string& key);
/// true or false.
bool flag(const Ctx& ctx, const YAML::Node& n, const std::string& key);
/// One of `values`, with a "did you mean" hint otherwise.
std::string choice(const Ctx& ctx, const YAML::Node& n, const std::string& key,
                   const std::vector<std::string>& values);
/// A list of exactly `count` numbers in range r; r.unit "time, force, force" gives each
/// item its own dimension.
std::vector<double> numbers(const Ctx& ctx, const YAML::Node& n, const std::string& key,
                            std::size_t count, const Range& r);
/// (x, y) [length, or `dimension`: "length/time^2" for gravity].
Point point(const Ctx& ctx, const YAML::Node& n, const std::string& key, const char* dimension = "length");
/// A polygon `[[x, y], ...]` of 3 to kMaxVertices vertices [length].
std::vector<Point> polygon_points(const Ctx& ctx, const YAML::Node& v, const std::string& key);

/// Index of `name` among items with a `.name`; error with a hint if absent.
template <class T>
int resolve(const Ctx& ctx, const YAML::Node& n, const std::string& key, const std::vector<T>& items,
            const char* what) {
  const std::string s = text(ctx, n, key);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == s) return static_cast<int>(i);
    names.push_back(items[i].name);
  }
  const std::string hint = laws::nearest_name(s, names);
  ctx.fail(n, key, fmt::format("unknown {} '{}'{}; defined: {}", what, s,
                               hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                               join(names)));
}

}  // namespace rheodda::scene::detail
