// The declared keys of `stages:` and of a stage's `remove_blocks:`, `add_fixed_points:`,
// `add_loads:`, `joint_sets:` entries and `analysis:` (keys.hpp), one entry per key, in
// the order of docs/reference/scene-format.md. What exists when a stage comes (names,
// blocks removed before, a fixed point left), stage times and the checks that tie keys
// together stay in load_stages.cpp.
#include "key_builders.hpp"
#include "rheodda/contact/joint_set_specs.hpp"

namespace rheodda::scene {

std::vector<EntryKey<StageDescription>>& stage_keys() {
  static std::vector<EntryKey<StageDescription>> keys = [] {
    using E = StageDescription;
    const std::string map = "stages";
    auto list = [&](const std::string& name, const std::string& unit, const std::string& meaning) {
      return detail::reader_key<E>(
          KeyInfo{.map = map, .name = name, .type = KeyType::list, .unit = unit, .default_text = "none",
                  .meaning = meaning});
    };
    std::vector<EntryKey<E>> k;
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "name", .type = KeyType::name, .unit = "–",
                .required = "the stage's name (history.csv's stage column)", .default_text = "required",
                .meaning = "the stage's name, unique: history.csv's `stage` column and summary.json's `stages`"},
        &E::name));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = map, .name = "at", .type = KeyType::number, .unit = "time", .range = detail::kPositive,
                .default_text = "one of `at`, `after`",
                .meaning = "time at which the stage begins, in (0, `duration`), after the stage before; a step ends "
                           "exactly there"},
        [](const E& st) -> KeyValue {
          if (st.start != StageStart::at) return std::monostate{};
          return st.at;
        },
        [](E& st, const KeyValue& v) {
          st.start = StageStart::at;
          st.at = std::get<double>(v);
        }));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = map, .name = "after", .type = KeyType::choice, .unit = "–", .choices = {"settled"},
                .default_text = "one of `at`, `after`",
                .meaning = "`settled`: when the settling stage before it ended at rest (the analysis's, or the one "
                           "the stage before opened with `settle: true`)"},
        [](const E& st) -> KeyValue {
          if (st.start != StageStart::settled) return std::monostate{};
          return std::string("settled");
        },
        [](E& st, const KeyValue&) { st.start = StageStart::settled; }));
    k.push_back(list("remove_fixed_points", "–", "list of names of fixed points to remove"));
    k.push_back(list("remove_loads", "–", "list of names of loads to remove"));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = map, .name = "remove_blocks", .type = KeyType::map, .unit = "–", .default_text = "none",
                .meaning = "blocks to remove by name, by a polygon holding their initial centroid, or by a polygon "
                           "holding the initial centroid of `rock_mass` blocks (their union); the fixed points and "
                           "loads on them go with them"}));
    k.push_back(list("add_fixed_points", "–", "list of fixed points to add (keys: `stages.add_fixed_points` below)"));
    k.push_back(list("add_loads", "–", "list of point loads to add (keys: `stages.add_loads` below)"));
    k.push_back(list("add_bolts", "–", "list of rock bolts to install (keys: `stages.add_bolts` below)"));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = map, .name = "joint_sets", .type = KeyType::named, .unit = "–", .default_text = "none",
                .meaning = "map of joint sets to change (keys: `stages.joint_sets` below)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = map, .name = "analysis", .type = KeyType::map, .unit = "–",
                .default_text = "unchanged; `dynamic_ratio` 1 with `dynamic`",
                .meaning = "`static` or `dynamic` from now on; `dynamic_ratio` in (0, 1] (dynamic only)"}));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "settle", .type = KeyType::flag, .unit = "–", .default_text = "`false`",
                .meaning = "`true`: a settling stage opens at the stage, with `analysis.settle`'s values (which must "
                           "be given)"},
        &E::settle));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = map, .name = "water", .type = KeyType::map, .unit = "–", .default_text = "unchanged",
                .meaning = "the water from the stage on: the keys of `water` (above), its times counted from the "
                           "stage's start (as `add_loads`' histories); a level below the model drains it",
                .submap = "water"}));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<StageDescription>>& stage_remove_blocks_keys() {
  static std::vector<EntryKey<StageDescription>> keys = [] {
    const std::string map = "stages.remove_blocks";
    auto list = [&](const std::string& name, const std::string& unit, const std::string& meaning) {
      return detail::reader_key<StageDescription>(
          KeyInfo{.map = map, .name = name, .type = KeyType::list, .unit = unit, .default_text = "none",
                  .meaning = meaning});
    };
    return std::vector<EntryKey<StageDescription>>{
        list("names", "–", "list of block names"),
        list("region", "length", "`[[x, y], ...]`: a polygon; the blocks whose initial centroid it holds"),
        list("rock_mass_inside", "length",
             "`[[x, y], ...]`: a polygon; the `rock_mass` blocks whose initial centroid it holds"),
    };
  }();
  return keys;
}

namespace {

/// The keys of a point a stage adds: `name`, `point`, `block` (and a load's force or history).
std::vector<EntryKey<StagePoint>> stage_point_keys(const std::string& map, bool load) {
  using E = StagePoint;
  const char* what = load ? "loads" : "fixed points";
  std::vector<EntryKey<E>> k;
  k.push_back(detail::optional_name_key(
      KeyInfo{.map = map, .name = "name", .type = KeyType::name, .unit = "–", .default_text = "none",
              .meaning = std::string("what a later stage removes it by; unique among the ") + what},
      &E::name));
  k.push_back(detail::field_key(
      KeyInfo{.map = map, .name = "point", .type = KeyType::point, .unit = "length",
              .required = "[x, y] where the material point stands at the stage [length]", .default_text = "required",
              .meaning = load ? "`[x, y]` where the loaded material point stands at the stage"
                              : "`[x, y]` where the material point stands at the stage: it is held there"},
      &E::point));
  k.push_back(detail::reader_key<E>(
      KeyInfo{.map = map, .name = "block", .type = KeyType::reference, .unit = "–",
              .required = "the block it is on (required in a stage)", .default_text = "required",
              .meaning = "the block it is on"}));
  if (!load)
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "hold", .type = KeyType::choice, .unit = "–",
                .choices = {"both", "x", "y", "rotation"}, .default_text = "`both`",
                .meaning = "what it holds: `both` directions, `x` or `y` only, or `rotation`: the block's "
                           "rotation alone, at the one it has at the stage (as `fixed_points.hold`)"},
        &E::hold));
  if (load) {
    k.push_back(detail::constant_force_key(
        KeyInfo{.map = map, .name = "force", .type = KeyType::numbers, .unit = "force",
                .default_text = "one of `force`, `history`", .meaning = "`[fx, fy]`, constant from the stage on",
                .count = 2},
        &E::history));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = map, .name = "history", .type = KeyType::list, .unit = "time, force, force",
                .default_text = "one of `force`, `history`",
                .meaning = "`[[t, fx, fy], ...]`, t from the stage's start (≥ 0, strictly increasing)"}));
  }
  return k;
}

}  // namespace

std::vector<EntryKey<StagePoint>>& stage_fixed_point_keys() {
  static std::vector<EntryKey<StagePoint>> keys = stage_point_keys("stages.add_fixed_points", false);
  return keys;
}

std::vector<EntryKey<StagePoint>>& stage_load_keys() {
  static std::vector<EntryKey<StagePoint>> keys = stage_point_keys("stages.add_loads", true);
  return keys;
}

std::vector<EntryKey<StageJointSet>>& stage_joint_set_keys() {
  static std::vector<EntryKey<StageJointSet>> keys = [] {
    using E = StageJointSet;
    const std::string map = "stages.joint_sets";
    // The joint set's properties that may change between steps: each the key of its
    // declaration (contact/joint_set_specs.hpp, between_steps), unchanged when not given.
    std::vector<EntryKey<E>> k;
    for (const contact::JointPropertySpec& s : contact::joint_property_specs()) {
      if (!s.between_steps) continue;
      KeyInfo info = detail::joint_property_info(map, s.name());
      info.default_text = "unchanged";
      const std::string name = s.name();
      k.push_back(detail::custom_key<E>(
          std::move(info),
          [name](const E& c) -> KeyValue {
            const auto v = c.properties.find(name);
            if (v == c.properties.end()) return std::monostate{};
            return v->second;
          },
          [name](E& c, const KeyValue& v) { c.properties[name] = std::get<double>(v); }));
    }
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = map, .name = "law", .type = KeyType::map, .unit = "–", .default_text = "unchanged",
                .meaning = "the joint set's law with new parameters (below)", .submap = "law"}));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<StageDescription>>& stage_analysis_keys() {
  static std::vector<EntryKey<StageDescription>> keys = [] {
    using E = StageDescription;
    const std::string map = "stages.analysis";
    std::vector<EntryKey<E>> k;
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = map, .name = "type", .type = KeyType::choice, .unit = "–", .choices = {"static", "dynamic"},
                .required = "static or dynamic", .default_text = "required",
                .meaning = "`static` or `dynamic` from the stage on"},
        [](const E& st) -> KeyValue {
          if (!st.dynamic_ratio) return std::monostate{};
          return std::string(*st.dynamic_ratio > 0.0 ? "dynamic" : "static");
        },
        // static: no velocity carried; dynamic: all of it, unless dynamic_ratio (below) says less.
        [](E& st, const KeyValue& v) { st.dynamic_ratio = std::get<std::string>(v) == "static" ? 0.0 : 1.0; }));
    k.push_back(detail::optional_key(
        KeyInfo{.map = map, .name = "dynamic_ratio", .type = KeyType::number, .unit = "–",
                .range = {0.0, true, 1.0, false}, .default_text = "1 with `dynamic`",
                .meaning = "share of velocity carried to the next step, in (0, 1]; `dynamic` only"},
        &E::dynamic_ratio));
    return k;
  }();
  return keys;
}

}  // namespace rheodda::scene
