// How the declarations of keys*.cpp are written: a KeyInfo (designated initializers)
// and how the key reaches its field. Internal to scene/; not installed.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "rheodda/laws/choice_spec.hpp"
#include "rheodda/laws/setting_spec.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::scene::detail {

constexpr double kInf = std::numeric_limits<double>::max();
inline constexpr KeyRange kPositive{0.0, true, kInf, false};     ///< > 0
inline constexpr KeyRange kNonNegative{0.0, false, kInf, false};  ///< >= 0

/// The key `name` of `map` that is a joint set's property of the same name: its type (a
/// number), unit, range, default and meaning are the property's declaration
/// (contact/joint_set_specs.hpp; keys_joints.cpp).
KeyInfo joint_property_info(const std::string& map, const std::string& name);

/// The key `s.name()` of `map` that is a declared setting or property (laws::SettingSpec:
/// of the engine, core/settings.hpp; of the contact layer, contact/contact_settings_specs.hpp;
/// of a material, a bolt or the water, core/property_specs.hpp): its type, unit, range,
/// default and meaning are the declaration's.
template <class S>
KeyInfo declared_info(const std::string& map, const laws::SettingSpec<S>& s) {
  const KeyType type = s.type == laws::SettingType::number    ? KeyType::number
                       : s.type == laws::SettingType::integer ? KeyType::integer
                                                              : KeyType::flag;
  const laws::ParameterSpec& p = s.parameter;
  const KeyRange range = type == KeyType::flag ? KeyRange{} : KeyRange{p.min, p.min_exclusive, p.max, p.max_exclusive};
  return KeyInfo{.map = map, .name = s.name(), .type = type, .unit = p.unit, .range = range,
                 .default_text = s.default_text(), .meaning = p.meaning};
}

/// The key of the declared property `s` of an entry E that is an S (derives from it): read
/// into and from its member; a default that is a mark outside the range ("never yields")
/// reads as not set. `s` must outlive the key (the declarations are static).
template <class E, class S>
EntryKey<E> declared_key(const std::string& map, const laws::SettingSpec<S>& s) {
  static_assert(std::is_base_of_v<S, E>);
  EntryKey<E> k;
  static_cast<KeyInfo&>(k) = declared_info(map, s);
  k.get = [&s, type = k.type](const E& e) -> KeyValue {
    const double v = s.value(e);
    if (!s.default_meaning.empty() && v == *s.parameter.default_value) return std::monostate{};
    return key_value_of(type, v);
  };
  k.set = [&s](E& e, const KeyValue& v) { s.set(e, key_number(v)); };
  return k;
}

/// The keys of the declarations `specs` in `map`, in their order.
template <class E, class S>
std::vector<EntryKey<E>> declared_keys_of(const std::string& map, const std::vector<laws::SettingSpec<S>>& specs) {
  std::vector<EntryKey<E>> k;
  for (const laws::SettingSpec<S>& s : specs) k.push_back(declared_key<E>(map, s));
  return k;
}

/// The key `name` in `keys`; std::logic_error if there is none.
template <class E>
EntryKey<E>& key_named(std::vector<EntryKey<E>>& keys, const std::string& name) {
  for (EntryKey<E>& k : keys)
    if (k.name == name) return k;
  throw std::logic_error("no declared key " + name);
}

/// A key that reads and writes the field `field` of its entry as is.
template <class E, class T>
EntryKey<E> field_key(KeyInfo info, T E::*field) {
  EntryKey<E> k;
  static_cast<KeyInfo&>(k) = std::move(info);
  k.get = [field](const E& e) -> KeyValue { return e.*field; };
  k.set = [field](E& e, const KeyValue& v) { e.*field = std::get<T>(v); };
  return k;
}

/// A key of an optional field: not set (std::monostate) until the file gives it.
template <class E, class T>
EntryKey<E> optional_key(KeyInfo info, std::optional<T> E::*field) {
  EntryKey<E> k;
  static_cast<KeyInfo&>(k) = std::move(info);
  k.get = [field](const E& e) -> KeyValue {
    if (!(e.*field)) return std::monostate{};
    return *(e.*field);
  };
  k.set = [field](E& e, const KeyValue& v) { e.*field = std::get<T>(v); };
  return k;
}

/// An optional name kept as text (`field`): not set (std::monostate) while empty.
template <class E>
EntryKey<E> optional_name_key(KeyInfo info, std::string E::*field) {
  EntryKey<E> k = field_key(std::move(info), field);
  k.get = [field](const E& e) -> KeyValue {
    if ((e.*field).empty()) return std::monostate{};
    return e.*field;
  };
  return k;
}

/// The KeyInfo of the declared choice `c` (laws::ChoiceSpec) in `map`: its words, default
/// and meaning.
template <class S>
KeyInfo choice_info(const std::string& map, const laws::ChoiceSpec<S>& c) {
  return KeyInfo{.map = map, .name = c.name(), .type = KeyType::choice, .unit = "–", .choices = c.words,
                 .default_text = c.default_text(), .meaning = c.meaning};
}

/// A key with its own getter and setter (a choice kept as an enum, a field of a member).
template <class E>
EntryKey<E> custom_key(KeyInfo info, std::function<KeyValue(const E&)> get, std::function<void(E&, const KeyValue&)> set) {
  EntryKey<E> k;
  static_cast<KeyInfo&>(k) = std::move(info);
  k.get = std::move(get);
  k.set = std::move(set);
  return k;
}

/// `force: [fx, fy]` of a load: the one sample (0, fx, fy) of its history `field`
/// (not set when the history has other samples).
template <class E>
EntryKey<E> constant_force_key(KeyInfo info, std::vector<std::array<double, 3>> E::*field) {
  return custom_key<E>(
      std::move(info),
      [field](const E& e) -> KeyValue {
        if ((e.*field).size() != 1) return std::monostate{};
        return std::vector<double>{(e.*field)[0][1], (e.*field)[0][2]};
      },
      [field](E& e, const KeyValue& v) {
        const auto& f = std::get<std::vector<double>>(v);
        e.*field = {{0.0, f[0], f[1]}};
      });
}

/// A key its section's reader reads (a map, a list, a reference, a point that must lie
/// on its block): declared for the schema, the docs and the required check; no setter.
template <class E>
EntryKey<E> reader_key(KeyInfo info, std::function<KeyValue(const E&)> get = {}) {
  EntryKey<E> k;
  static_cast<KeyInfo&>(k) = std::move(info);
  k.get = get ? std::move(get) : [](const E&) -> KeyValue { return std::monostate{}; };
  return k;
}

}  // namespace rheodda::scene::detail
