// The declared keys of the top level of a scene file (its sections) and of `units:`
// (keys.hpp), one entry per key, in the order of docs/reference/scene-format.md. Each
// section is read by its own reader (loader.cpp); `blocks` being required unless a
// `rock_mass` is given is the loader's to check.
#include <fmt/format.h>

#include <algorithm>

#include "key_builders.hpp"

namespace rheodda::scene {

namespace {

/// A section of the file, read by its reader; its keys are in a table of their own.
EntryKey<SceneDescription> section(const std::string& name, KeyType type, std::string required,
                                   std::string default_text, std::string meaning, std::string submap = {}) {
  return detail::reader_key<SceneDescription>(KeyInfo{.map = "top", .name = name, .type = type, .unit = "–",
                                                      .required = std::move(required),
                                                      .default_text = std::move(default_text),
                                                      .meaning = std::move(meaning), .submap = std::move(submap),
                                                      .own_table = true});
}

/// A unit's label (`examples` separated by ", "): any text, written after every number
/// of that dimension in the outputs.
EntryKey<Units> unit_label(const std::string& name, std::string Units::*field, const std::string& examples) {
  std::string quoted;
  for (std::size_t a = 0; a < examples.size();) {
    const std::size_t b = std::min(examples.find(", ", a), examples.size());
    quoted += (a ? ", `" : "`") + examples.substr(a, b - a) + "`";
    a = b + 2;
  }
  return detail::field_key(KeyInfo{.map = "units", .name = name, .type = KeyType::text, .unit = "–",
                                   .required = fmt::format("label of the {} unit, e.g. {}", name,
                                                           examples.substr(0, examples.find(','))),
                                   .default_text = "required",
                                   .meaning = fmt::format("label of the {} unit, e.g. {}", name, quoted)},
                           field);
}

}  // namespace

std::vector<EntryKey<SceneDescription>>& top_keys() {
  static std::vector<EntryKey<SceneDescription>> keys = [] {
    std::vector<EntryKey<SceneDescription>> k;
    k.push_back(detail::field_key(KeyInfo{.map = "top", .name = "title", .type = KeyType::text, .unit = "–",
                                          .default_text = "the file name",
                                          .meaning = "text naming the scene in outputs and pictures"},
                                  &SceneDescription::title));
    k.push_back(section("units", KeyType::map, "labels {length, force, time}", "required",
                        "unit labels (`units` below)", "units"));
    k.push_back(section("analysis", KeyType::map, "time stepping: duration, dt, gravity, ...", "required",
                        "time stepping, contact numerics, outputs (`analysis` below)", "analysis"));
    k.push_back(section("materials", KeyType::named, "named block materials", "required",
                        "named block materials (`materials` below)"));
    k.push_back(section("joint_sets", KeyType::named, "named joint sets", "required",
                        "named joint sets (`joint_sets` below)"));
    k.push_back(section("blocks", KeyType::list, {}, "required, unless `rock_mass` is given",
                        "the list of blocks (`blocks` below)"));
    k.push_back(section("rock_mass", KeyType::map, {}, "none",
                        "a region cut into blocks by joint sets (`rock_mass` below; docs/guide/rockmass.md)",
                        "rock_mass"));
    k.push_back(section("fixed_points", KeyType::list, {}, "empty", "points held fixed (`fixed_points` below)"));
    k.push_back(section("loads", KeyType::list, {}, "empty", "point loads on blocks (`loads` below)"));
    k.push_back(section("measurement_points", KeyType::list, {}, "empty",
                        "points whose motion history.csv records (`measurement_points` below)"));
    k.push_back(section("water", KeyType::map, {}, "none",
                        "water in the joints: a phreatic surface and the water's unit weight (`water` below; "
                        "docs/reference/water.md)",
                        "water"));
    k.push_back(section("bolts", KeyType::list, {}, "empty",
                        "rock bolts between two blocks or a block and a fixed point (`bolts` below; "
                        "docs/reference/bolts.md)"));
    k.push_back(section("stages", KeyType::list, {}, "none",
                        "changes to the model during the run (`stages` below; docs/reference/stages.md)"));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<Units>>& units_keys() {
  static std::vector<EntryKey<Units>> keys{
      unit_label("length", &Units::length, "m, mm"),
      unit_label("force", &Units::force, "N, MN"),
      unit_label("time", &Units::time, "s, h, d"),
  };
  return keys;
}

}  // namespace rheodda::scene
