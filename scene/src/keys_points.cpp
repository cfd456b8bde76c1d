// The declared keys of `fixed_points:`, `loads:` and `measurement_points:` (keys.hpp),
// one entry per key, in the order of docs/reference/scene-format.md. Which block a point
// lies on, unique names and a load's history stay in read_points.cpp.
#include "key_builders.hpp"

namespace rheodda::scene {

namespace {

/// `point:` of an entry: read with its block by read_block_point (it must lie on it).
template <class E>
EntryKey<E> point_key(const std::string& map) {
  return detail::reader_key<E>(KeyInfo{.map = map, .name = "point", .type = KeyType::point, .unit = "length",
                                       .required = "[x, y] [length]", .default_text = "required",
                                       .meaning = "`[x, y]`: the initial position of a material point"});
}

/// `block:` of an entry.
template <class E>
EntryKey<E> block_key(const std::string& map) {
  return detail::reader_key<E>(KeyInfo{.map = map, .name = "block", .type = KeyType::reference, .unit = "–",
                                       .default_text = "the only block the point lies on",
                                       .meaning = "the block the point belongs to (needed for a point on a joint "
                                                  "between two blocks)"});
}

/// `name:` by which a stage removes a fixed point or load (docs/reference/stages.md).
KeyInfo removable_name(const std::string& map) {
  return KeyInfo{.map = map, .name = "name", .type = KeyType::name, .unit = "–", .default_text = "none",
                 .meaning = "unique: what a stage removes it by"};
}

}  // namespace

std::vector<EntryKey<BlockPoint>>& fixed_point_keys() {
  static std::vector<EntryKey<BlockPoint>> keys{
      detail::optional_name_key(removable_name("fixed_points"), &BlockPoint::name),
      point_key<BlockPoint>("fixed_points"),
      block_key<BlockPoint>("fixed_points"),
      detail::field_key(KeyInfo{.map = "fixed_points", .name = "hold", .type = KeyType::choice, .unit = "–",
                                .choices = {"both", "x", "y", "rotation"}, .default_text = "`both`",
                                .meaning = "what the point holds: `both` directions, or `x` or `y` only (a penalty "
                                           "spring in that direction alone; the point moves freely in the other), or "
                                           "`rotation`: the block's rotation alone (a rotational spring p J/S "
                                           "[force·length/rad], J/S the block's polar radius of gyration squared; "
                                           "the point only names the block). Several entries on a block combine "
                                           "(`x` and `rotation`: free in y only)"},
                        &BlockPoint::hold),
  };
  return keys;
}

std::vector<EntryKey<LoadDescription>>& load_keys() {
  static std::vector<EntryKey<LoadDescription>> keys = [] {
    using E = LoadDescription;
    std::vector<EntryKey<E>> k;
    k.push_back(detail::custom_key<E>(
        removable_name("loads"),
        [](const E& l) -> KeyValue {
          if (l.at.name.empty()) return std::monostate{};
          return l.at.name;
        },
        [](E& l, const KeyValue& v) { l.at.name = std::get<std::string>(v); }));
    k.push_back(point_key<E>("loads"));
    k.push_back(block_key<E>("loads"));
    k.push_back(detail::constant_force_key(
        KeyInfo{.map = "loads", .name = "force", .type = KeyType::numbers, .unit = "force",
                .default_text = "one of force, history", .meaning = "`[fx, fy]`, constant from t = 0", .count = 2},
        &E::history));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "loads", .name = "history", .type = KeyType::list, .unit = "time, force, force",
                .default_text = "one of force, history",
                .meaning = "`[[t, fx, fy], ...]`: times ≥ 0, strictly increasing, linear in between, held before "
                           "the first and after the last sample"}));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<MeasurementPoint>>& measurement_point_keys() {
  static std::vector<EntryKey<MeasurementPoint>> keys{
      detail::field_key(KeyInfo{.map = "measurement_points", .name = "name", .type = KeyType::name, .unit = "–",
                                .required = "column prefix in history.csv", .default_text = "required",
                                .meaning = "unique; the history.csv column prefix"},
                        &MeasurementPoint::name),
      point_key<MeasurementPoint>("measurement_points"),
      block_key<MeasurementPoint>("measurement_points"),
  };
  return keys;
}

}  // namespace rheodda::scene
