// The declared keys of `blocks:` (with a block's `rectangle:` and `grid:`) and of
// `rock_mass:` (with its `joint_sets:` and `traces:`) (keys.hpp), one entry per key, in
// the order of docs/reference/scene-format.md. The geometry (polygons, the region, the
// cut), the names of materials and joint sets, and the checks that tie keys together
// stay in read_blocks.cpp and read_rock_mass.cpp.
#include "key_builders.hpp"
#include "yaml_reader.hpp"

namespace rheodda::scene {

using detail::kNonNegative;
using detail::kPositive;

std::vector<EntryKey<BlockDescription>>& block_keys() {
  static std::vector<EntryKey<BlockDescription>> keys = [] {
    using E = BlockDescription;
    std::vector<EntryKey<E>> k;
    k.push_back(detail::field_key(
        KeyInfo{.map = "blocks", .name = "name", .type = KeyType::name, .unit = "–",
                .default_text = "`block<k>` (k = 1-based position); grids: `<name>.r<row>.c<col>`",
                .meaning = "unique block name (for points, outputs)"},
        &E::name));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "blocks", .name = "material", .type = KeyType::reference, .unit = "–",
                .default_text = "the only material, if there is exactly one", .meaning = "a material name"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "blocks", .name = "polygon", .type = KeyType::list, .unit = "length",
                .default_text = "one of polygon, rectangle, grid",
                .meaning = "`[[x, y], ...]`, ≥ 3 vertices, first not repeated, either orientation"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "blocks", .name = "rectangle", .type = KeyType::map, .unit = "length, deg",
                .default_text = "one of polygon, rectangle, grid",
                .meaning = "lower-left corner (x, y), rotated by `angle` (default 0) counter-clockwise about it "
                           "(keys: `blocks.rectangle` below)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "blocks", .name = "grid", .type = KeyType::map, .unit = "length, deg",
                .default_text = "one of polygon, rectangle, grid",
                .meaning = "columns × rows rectangles of width × height from (x, y) (keys: `blocks.grid` below)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "blocks", .name = "joint_set", .type = KeyType::reference, .unit = "–",
                .default_text = "the only joint set, if there is exactly one",
                .meaning = "the joint set of every edge"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "blocks", .name = "edge_joint_sets", .type = KeyType::list, .unit = "–",
                .default_text = "– (use `joint_set`)",
                .meaning = "one joint set per edge: polygon edge k runs from vertex k to k+1; rectangles and "
                           "grids: `[bottom, right, top, left]`"}));
    k.push_back(detail::field_key(
        KeyInfo{.map = "blocks", .name = "fixed", .type = KeyType::flag, .unit = "–", .default_text = "`false`",
                .meaning = "`true`: a fixed point at every vertex"},
        &E::fixed));
    auto triple = [](std::array<double, 3> E::*field) {
      return std::pair{[field](const E& b) -> KeyValue { return std::vector<double>((b.*field).begin(), (b.*field).end()); },
                       [field](E& b, const KeyValue& v) {
                         const auto& x = std::get<std::vector<double>>(v);
                         b.*field = {x[0], x[1], x[2]};
                       }};
    };
    const auto stress = triple(&E::initial_stress);
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "blocks", .name = "initial_stress", .type = KeyType::numbers, .unit = "stress",
                .default_text = "`[0, 0, 0]`", .meaning = "`[sigma_x, sigma_y, tau_xy]`, tension > 0", .count = 3},
        stress.first, stress.second));
    const auto velocity = triple(&E::initial_velocity);
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "blocks", .name = "initial_velocity", .type = KeyType::numbers, .unit = "length/time, 1/time",
                .default_text = "`[0, 0, 0]`", .meaning = "`[vx, vy, omega]` (dynamic analysis only)", .count = 3},
        velocity.first, velocity.second));
    return k;
  }();
  return keys;
}

namespace {

/// The keys of a block's `rectangle:` (map "blocks.rectangle") or `grid:` ("blocks.grid").
std::vector<EntryKey<BlockShape>> shape_keys(const std::string& map, bool grid) {
  using E = BlockShape;
  std::vector<EntryKey<E>> k;
  k.push_back(detail::field_key(
      KeyInfo{.map = map, .name = "x", .type = KeyType::number, .unit = "length",
              .required = "x of the lower-left corner [length]", .default_text = "required",
              .meaning = "x of the lower-left corner"},
      &E::x));
  k.push_back(detail::field_key(
      KeyInfo{.map = map, .name = "y", .type = KeyType::number, .unit = "length",
              .required = "y of the lower-left corner [length]", .default_text = "required",
              .meaning = "y of the lower-left corner"},
      &E::y));
  k.push_back(detail::field_key(
      KeyInfo{.map = map, .name = "width", .type = KeyType::number, .unit = "length", .range = kPositive,
              .required = "[length]", .default_text = "required",
              .meaning = grid ? "width of each block, > 0" : "> 0"},
      &E::width));
  k.push_back(detail::field_key(
      KeyInfo{.map = map, .name = "height", .type = KeyType::number, .unit = "length", .range = kPositive,
              .required = "[length]", .default_text = "required",
              .meaning = grid ? "height of each block, > 0" : "> 0"},
      &E::height));
  if (grid) {
    const KeyRange counts{1.0, false, double(detail::kMaxBlocks), false};
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "columns", .type = KeyType::integer, .unit = "–", .range = counts,
                .required = "number of blocks along x", .default_text = "required",
                .meaning = "number of blocks along x, 1 to 200000"},
        &E::columns));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "rows", .type = KeyType::integer, .unit = "–", .range = counts,
                .required = "number of blocks along y", .default_text = "required",
                .meaning = "number of blocks along y, 1 to 200000"},
        &E::rows));
  }
  k.push_back(detail::field_key(
      KeyInfo{.map = map, .name = "angle", .type = KeyType::number, .unit = "deg", .range = {-360.0, false, 360.0, false},
              .default_text = "0", .meaning = "counter-clockwise rotation about (x, y), in [-360, 360]"},
      &E::angle));
  return k;
}

}  // namespace

std::vector<EntryKey<BlockShape>>& rectangle_keys() {
  static std::vector<EntryKey<BlockShape>> keys = shape_keys("blocks.rectangle", false);
  return keys;
}

std::vector<EntryKey<BlockShape>>& grid_keys() {
  static std::vector<EntryKey<BlockShape>> keys = shape_keys("blocks.grid", true);
  return keys;
}

std::vector<EntryKey<RockMassDescription>>& rock_mass_keys() {
  static std::vector<EntryKey<RockMassDescription>> keys = [] {
    using E = RockMassDescription;
    std::vector<EntryKey<E>> k;
    k.push_back(detail::field_key(
        KeyInfo{.map = "rock_mass", .name = "name", .type = KeyType::name, .unit = "–", .default_text = "`rock`",
                .meaning = "prefix of the block names"},
        &E::name));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "rock_mass", .name = "material", .type = KeyType::reference, .unit = "–",
                .default_text = "the only material, if there is exactly one", .meaning = "a material name"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "rock_mass", .name = "region", .type = KeyType::list, .unit = "length",
                .required = "the polygon to cut, [[x, y], ...] [length]", .default_text = "required",
                .meaning = "`[[x, y], ...]`: the simple polygon to cut, either orientation"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "rock_mass", .name = "holes", .type = KeyType::list, .unit = "length", .default_text = "none",
                .meaning = "list of polygons strictly inside the region, not touching each other (a tunnel, an "
                           "opening)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "rock_mass", .name = "boundary_joint_set", .type = KeyType::reference, .unit = "–",
                .default_text = "the only joint set, if there is exactly one",
                .meaning = "the joint set of the edges on the region's boundary (and holes)"}));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "rock_mass", .name = "seed", .type = KeyType::integer, .unit = "–",
                .range = {0.0, false, 9007199254740992.0, false}, .default_text = "`1`",
                .meaning = "whole number in [0, 2^53]: seed of the random generation"},
        [](const E& r) -> KeyValue { return static_cast<std::int64_t>(r.seed); },
        [](E& r, const KeyValue& v) { r.seed = static_cast<std::uint64_t>(std::get<std::int64_t>(v)); }));
    k.push_back(detail::field_key(
        KeyInfo{.map = "rock_mass", .name = "sliver_area", .type = KeyType::number, .unit = "length^2",
                .range = kNonNegative, .default_text = "`0` (none)",
                .meaning = "blocks smaller than this are merged into the neighbour they share the longest joint "
                           "with"},
        &E::sliver_area));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "rock_mass", .name = "joint_sets", .type = KeyType::list, .unit = "–", .default_text = "none",
                .meaning = "list of joint sets to generate (keys: `rock_mass.joint_sets` below)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "rock_mass", .name = "traces", .type = KeyType::list, .unit = "–", .default_text = "none",
                .meaning = "list of explicit traces (keys: `rock_mass.traces` below): mapped faults, bedding "
                           "planes"}));
    return k;
  }();
  return keys;
}

namespace {

/// `joint_set:` of a rock mass's generated set or trace: a name of the scene's joint sets.
template <class E>
EntryKey<E> joint_set_reference(const std::string& map) {
  return detail::reader_key<E>(KeyInfo{.map = map, .name = "joint_set", .type = KeyType::reference, .unit = "–",
                                       .required = "a name of the scene's joint_sets", .default_text = "required",
                                       .meaning = "a name of the scene's `joint_sets`"});
}

}  // namespace

std::vector<EntryKey<rockmass::JointSetGeneration>>& rock_mass_joint_set_keys() {
  static std::vector<EntryKey<rockmass::JointSetGeneration>> keys = [] {
    using E = rockmass::JointSetGeneration;
    const std::string map = "rock_mass.joint_sets";
    std::vector<EntryKey<E>> k;
    k.push_back(joint_set_reference<E>(map));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "dip", .type = KeyType::number, .unit = "deg", .range = {0.0, false, 90.0, false},
                .required = "angle below the horizontal [deg], 0 to 90", .default_text = "required",
                .meaning = "angle of the traces below the horizontal, 0 to 90"},
        &E::dip));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = map, .name = "dip_direction", .type = KeyType::choice, .unit = "–",
                .choices = {"right", "left"}, .default_text = "`right`",
                .meaning = "`right` (the traces descend towards +x) or `left`"},
        [](const E& g) -> KeyValue { return std::string(g.dips_right ? "right" : "left"); },
        [](E& g, const KeyValue& v) { g.dips_right = std::get<std::string>(v) == "right"; }));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "spacing", .type = KeyType::number, .unit = "length", .range = kPositive,
                .required = "mean spacing normal to the joints [length]", .default_text = "required",
                .meaning = "mean spacing, measured normal to the traces, > 0"},
        &E::spacing));
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = map, .name = "spacing_distribution", .type = KeyType::choice, .unit = "–",
                .choices = {"constant", "normal", "exponential", "log-normal"}, .default_text = "`constant`",
                .meaning = "`constant`, `normal`, `exponential` or `log-normal`"},
        [](const E& g) -> KeyValue { return std::string(rockmass::spacing_distribution_name(g.spacing_distribution)); },
        [](E& g, const KeyValue& v) {
          for (auto d : {rockmass::SpacingDistribution::constant, rockmass::SpacingDistribution::normal,
                         rockmass::SpacingDistribution::exponential, rockmass::SpacingDistribution::log_normal})
            if (std::get<std::string>(v) == rockmass::spacing_distribution_name(d)) g.spacing_distribution = d;
        }));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "spacing_deviation", .type = KeyType::number, .unit = "length", .range = kPositive,
                .default_text = "–",
                .meaning = "standard deviation of the spacing, > 0 (normal and log-normal only, required there)"},
        &E::spacing_deviation));
    k.push_back(detail::optional_key(
        KeyInfo{.map = map, .name = "trace_length", .type = KeyType::number, .unit = "length", .range = kPositive,
                .default_text = "persistent: each line crosses the region",
                .meaning = "length of each trace along a line (non-persistent joints); with `gap`"},
        &E::trace_length));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "gap", .type = KeyType::number, .unit = "length", .range = kNonNegative,
                .default_text = "with `trace_length`",
                .meaning = "rock bridge between two traces of a line, ≥ 0; persistence = trace_length / "
                           "(trace_length + gap)"},
        &E::gap));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "dip_spread", .type = KeyType::number, .unit = "deg",
                .range = {0.0, false, 45.0, false}, .default_text = "`0`",
                .meaning = "standard deviation of each line's dip about `dip`, 0 to 45"},
        &E::dip_spread));
    k.push_back(detail::optional_key(
        KeyInfo{.map = map, .name = "origin", .type = KeyType::point, .unit = "length", .default_text = "random offset",
                .meaning = "`[x, y]`: a point one line passes through"},
        &E::origin));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<rockmass::Trace>>& rock_mass_trace_keys() {
  static std::vector<EntryKey<rockmass::Trace>> keys = [] {
    using E = rockmass::Trace;
    const std::string map = "rock_mass.traces";
    std::vector<EntryKey<E>> k;
    k.push_back(joint_set_reference<E>(map));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "from", .type = KeyType::point, .unit = "length", .required = "[x, y] [length]",
                .default_text = "required", .meaning = "`[x, y]`: one end"},
        &E::a));
    k.push_back(detail::field_key(
        KeyInfo{.map = map, .name = "to", .type = KeyType::point, .unit = "length", .required = "[x, y] [length]",
                .default_text = "required",
                .meaning = "`[x, y]`: the other end (traces beyond the region are clipped by the cut)"},
        &E::b));
    return k;
  }();
  return keys;
}

}  // namespace rheodda::scene
