// How the declarations of keys*.cpp are written: a KeyInfo (designated initializers)
// and how the key reaches its field. Internal to apps/scene; not installed.
#pragma once

#include <limits>
#include <optional>
#include <utility>

#include "rheodda/scene/keys.hpp"

namespace rheodda::scene::detail {

constexpr double kInf = std::numeric_limits<double>::max();
inline constexpr KeyRange kPositive{0.0, true, kInf, false};     ///< > 0
inline constexpr KeyRange kNonNegative{0.0, false, kInf, false};  ///< >= 0

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

/// A key with its own getter and setter (a choice kept as an enum, a field of a member).
template <class E>
EntryKey<E> custom_key(KeyInfo info, std::function<KeyValue(const E&)> get, std::function<void(E&, const KeyValue&)> set) {
  EntryKey<E> k;
  static_cast<KeyInfo&>(k) = std::move(info);
  k.get = std::move(get);
  k.set = std::move(set);
  return k;
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
