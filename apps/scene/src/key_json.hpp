// The declared keys (keys.hpp) of an entry as summary.json's "inputs" echo them
// (scene_json.cpp, bolts_text.cpp). Internal to apps/scene; not installed.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "rheodda/scene/keys.hpp"

namespace rheodda::scene::detail {

/// A declared key's value as JSON: null where it does not apply.
inline nlohmann::ordered_json key_json(const KeyValue& v) {
  return std::visit(
      [](const auto& x) -> nlohmann::ordered_json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>)
          return nlohmann::ordered_json(nullptr);
        else
          return nlohmann::ordered_json(x);
      },
      v);
}

/// The echoed keys of one entry of the declared map `map`, in their order; a map key (a
/// law, a bolt's end) as `submap` gives it.
template <class E>
nlohmann::ordered_json entry_json(const std::vector<EntryKey<E>>& keys, const std::string& map, const E& e,
                                  const std::function<nlohmann::ordered_json(const KeyInfo&)>& submap = {}) {
  nlohmann::ordered_json o = nlohmann::ordered_json::object();
  for (const EntryKey<E>& k : keys)
    if (k.map == map && k.echoed) o[k.name] = k.type == KeyType::map ? submap(k) : key_json(k.get(e));
  return o;
}

/// A law as summary.json echoes it: its name and every parameter; null for none.
inline nlohmann::ordered_json law_json(const std::optional<LawChoice>& law) {
  if (!law) return nullptr;
  nlohmann::ordered_json o = {{"name", law->name}};
  for (const auto& [k, v] : law->parameters) o[k] = v;
  return o;
}

}  // namespace rheodda::scene::detail
