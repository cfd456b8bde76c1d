// The declared keys of `water:` and its `surface_history:` samples (keys.hpp), one
// entry per key, in the order of docs/reference/scene-format.md. One form of the
// surface, the surfaces' x-span and increasing times stay in load_water.cpp.
#include "key_builders.hpp"
#include "rheodda/core/property_specs.hpp"

namespace rheodda::scene {

std::vector<EntryKey<WaterDescription>>& water_keys() {
  static std::vector<EntryKey<WaterDescription>> keys = [] {
    using E = WaterDescription;
    // unit_weight: the key of its declaration (core/property_specs.hpp), read into and from
    // the core::WaterProperties a WaterDescription is.
    std::vector<EntryKey<E>> k = detail::declared_keys_of<E>("water", core::water_specs());
    detail::key_named(k, "unit_weight").required = "the water's unit weight gamma_w [force/length^3]";
    detail::key_named(k, "unit_weight").default_text = "required";
    k.push_back(detail::custom_key<E>(
        KeyInfo{.map = "water", .name = "level", .type = KeyType::number, .unit = "length", .default_text = "–",
                .meaning = "a horizontal surface at this height, constant in time"},
        [](const E& w) -> KeyValue {
          if (w.form != E::Form::level) return std::monostate{};
          return w.history.front().level;
        },
        [](E& w, const KeyValue& v) {
          w.form = E::Form::level;
          E::Sample s;
          s.level = std::get<double>(v);
          w.history = {s};
        }));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "water", .name = "surface", .type = KeyType::list, .unit = "length", .default_text = "–",
                .meaning = "a polyline `[[x, y], ...]`: at least 2 points, x strictly increasing, spanning the "
                           "blocks' x-range at the start; linear between the points, held level beyond its ends"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "water", .name = "level_history", .type = KeyType::list, .unit = "time, length",
                .default_text = "–",
                .meaning = "a level in time `[[t, level], ...]`: times ≥ 0, strictly increasing, linear in "
                           "between, held before the first and after the last sample (a reservoir drawdown and "
                           "refill)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "water", .name = "surface_history", .type = KeyType::list, .unit = "–", .default_text = "–",
                .meaning = "a surface in time: a list of `{time, surface}` (keys: `water.surface_history` below), "
                           "linear in time between them at every x, held before the first and after the last"}));
    return k;
  }();
  return keys;
}

std::vector<EntryKey<WaterDescription::Sample>>& water_sample_keys() {
  static std::vector<EntryKey<WaterDescription::Sample>> keys{
      detail::field_key(KeyInfo{.map = "water.surface_history", .name = "time", .type = KeyType::number,
                                .unit = "time", .required = "[time]", .default_text = "required",
                                .meaning = "the sample's time, ≥ 0, after the previous sample's"},
                        &WaterDescription::Sample::time),
      detail::reader_key<WaterDescription::Sample>(
          KeyInfo{.map = "water.surface_history", .name = "surface", .type = KeyType::list, .unit = "length",
                  .required = "[[x, y], ...] [length]", .default_text = "required",
                  .meaning = "the surface then, as `surface` above"}),
  };
  return keys;
}

}  // namespace rheodda::scene
