// The scene loader: YAML -> SceneDescription, checking as it goes.
//
// Where each concern lives:
//   scene_file.cpp      the file before parsing: a regular file, size, UTF-8, no tabs
//   yaml_reader.hpp     the map reader (valid keys, duplicates, "did you mean") and the
//                       typed readers (numbers with range and unit, words, points...)
//   keys*.cpp           every key of every map, declared once (keys.hpp); schema.cpp publishes them
//   read_analysis.cpp   `units:`, `analysis:`
//   read_joint_sets.cpp `materials:`, `joint_sets:` and their laws
//   read_blocks.cpp     `blocks:`; read_rock_mass.cpp `rock_mass:`
//   read_points.cpp     `fixed_points:`, `loads:`, `measurement_points:`
//   load_water.cpp      `water:`
//   scene_checks.cpp    the blocks' geometry checks
//   this file           parse_scene: the sections in order, then the defaults
// Each YAML map is read through a MapReader that knows the map's valid keys, so
// an unknown (mistyped) key is reported before anything else, with a "did you
// mean" hint (laws::nearest_name). Duplicated keys are refused too: yaml-cpp
// would silently keep one of them.
#include "rheodda/scene/loader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "rheodda/core/defaults.hpp"
#include "read_keys.hpp"
#include "scene_readers.hpp"
#include "yaml_document.hpp"

namespace rheodda::scene {

SceneError::SceneError(std::string file, SourceLocation where, std::string key, std::string message)
    : std::runtime_error(where.line > 0 ? fmt::format("{}:{}:{}: {}{}", file, where.line, where.column,
                                                      key.empty() ? "" : key + ": ", message)
                                        : fmt::format("{}: {}{}", file, key.empty() ? "" : key + ": ", message)),
      file_(std::move(file)),
      where_(where),
      key_(std::move(key)),
      message_(std::move(message)) {}

using namespace detail;

SceneDescription parse_scene(const std::string& text_in, const std::string& file) {
  Ctx ctx{file};
  YAML::Node root;
  try {
    root = load_yaml_document(text_in);  // libyaml: yaml-cpp's scanner is 8x slower on large files
  } catch (const YamlSyntaxError& e) {
    throw SceneError(file, {e.line() + 1, e.column() + 1}, "", std::string("YAML syntax: ") + e.what());
  }
  try {
    SceneDescription s;
    s.file = file;
    // The sections (keys_top.cpp): each read by its reader; a required one asked for
    // with its declaration's words.
    const std::vector<EntryKey<SceneDescription>>& sections = top_keys();
    const MapReader top = declared_reader(ctx, root, "", sections, "top");
    auto section = [&](KeyName name) { return required_key(top, sections, name); };
    s.title = file.substr(file.find_last_of('/') == std::string::npos ? 0 : file.find_last_of('/') + 1);
    read_declared(ctx, top, sections, s);  // title
    s.units = read_units(ctx, section(key::top::units));
    ctx.units = &s.units;  // from here a value may carry a unit of its own (read_quantity.cpp)
    ctx.given = &s.given_quantities;
    s.analysis = read_analysis(ctx, section(key::top::analysis));
    s.materials = read_materials(ctx, section(key::top::materials), s.analysis.has_dynamic_steps());
    s.joint_sets = read_joint_sets(ctx, section(key::top::joint_sets), s.analysis.has_dynamic_steps());
    std::vector<RawBlock> raw;
    // With `rock_mass:`, `blocks:` is optional (blocks besides the generated ones).
    const YAML::Node rock_mass = top.find(key::top::rock_mass);
    if (!rock_mass.IsDefined() || top.has(key::top::blocks))
      read_blocks(ctx, top.required(key::top::blocks, "the list of blocks"), s, raw);
    if (rock_mass.IsDefined()) read_rock_mass(ctx, rock_mass, s, raw);
    check_geometry(ctx, raw, s);
    read_points(ctx, top, s);
    if (YAML::Node v = top.find(key::top::water); v.IsDefined()) s.water = read_water(ctx, v, s);
    read_bolts(ctx, top, s);
    if (YAML::Node v = top.find(key::top::stages); v.IsDefined()) read_stages(ctx, v, s);  // docs/reference/stages.md
    // The model's defaults, as the engine would take them (core/defaults.hpp): the
    // penalty k1 E (the seed's eq. 17), the fixed-point spring 100 E.
    const double e_max = core::largest_young_modulus(s.materials, [](const Material& m) { return m.young_modulus; });
    if (s.analysis.penalty == 0.0) s.analysis.penalty = core::default_penalty(e_max);
    if (s.analysis.fixed_point_stiffness == 0.0) s.analysis.fixed_point_stiffness = core::default_fixed_point_stiffness(e_max);
    return s;
  } catch (const YAML::Exception& e) {
    // Anything yaml-cpp raises past parsing is still a fault of the file.
    throw SceneError(file, {e.mark.line + 1, e.mark.column + 1}, "", e.msg);
  }
}

SceneDescription load_scene(const std::string& path) { return parse_scene(read_scene_text(path), path); }

}  // namespace rheodda::scene
