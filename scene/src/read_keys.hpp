// Reading the declared keys of a map (keys.hpp) from the scene file: which keys the map
// accepts, each plain value read and checked against its declaration (type, range,
// unit, choices), required keys present. Internal to the loader; not installed.
#pragma once

#include <string>
#include <vector>

#include "rheodda/scene/keys.hpp"
#include "yaml_reader.hpp"

namespace rheodda::scene::detail {

/// A declared key's value from its node, checked against its declaration; the error
/// names the file, line, column, the key `path`, and the range and unit.
KeyValue read_value(const Ctx& ctx, const YAML::Node& v, const std::string& path, const KeyInfo& k);

/// The names of the keys of `map` declared in `keys`: what its MapReader accepts.
template <class E>
std::vector<std::string> key_names(const std::vector<EntryKey<E>>& keys, const std::string& map) {
  std::vector<std::string> names;
  for (const EntryKey<E>& k : keys)
    if (k.map == map) names.push_back(k.name);
  return names;
}

/// The reader of a map whose keys are those of the declared map `map` in `keys`.
template <class E>
MapReader declared_reader(const Ctx& ctx, const YAML::Node& n, std::string path, const std::vector<EntryKey<E>>& keys,
                          const std::string& map) {
  return MapReader(ctx, n, std::move(path), map, key_names(keys, map));
}

/// Every declared key of the map `m` reads (m.map()) with a setter that the file gives,
/// in order: read, checked and stored into `e`; a required one must be given. The keys
/// without a setter are their reader's (required_key()). The keys are asked for by
/// their declared names (MapReader::find_named): these are the map's keys by definition.
template <class E>
void read_declared(const Ctx& ctx, const MapReader& m, const std::vector<EntryKey<E>>& keys, E& e) {
  for (const EntryKey<E>& k : keys) {
    if (k.map != m.map() || !k.set) continue;
    const YAML::Node v = k.required.empty() ? m.find_named(k.name) : m.required_named(k.name, k.required);
    if (v.IsDefined()) k.set(e, read_value(ctx, v, m.child_named(k.name), k));
  }
}

/// The value of the key `key` that its reader reads, refused as its declaration says
/// when it is required and not given (an undefined node when optional and not given).
template <class E>
YAML::Node required_key(const MapReader& m, const std::vector<EntryKey<E>>& keys, KeyName key) {
  for (const EntryKey<E>& k : keys)
    if (k.map == key.map() && k.name == key.word() && !k.required.empty()) return m.required(key, k.required);
  return m.find(key);
}

}  // namespace rheodda::scene::detail
