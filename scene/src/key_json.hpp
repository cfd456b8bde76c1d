// The declared keys (keys.hpp) of an entry as summary.json's "inputs" echo them
// (scene_json.cpp, bolts_text.cpp). Internal to scene/; not installed.
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

/// What summary.json writes for a plain key its entry does not set: null (`analysis`,
/// materials, joint sets, bolts: every key, null where it does not apply) or nothing
/// (the sections whose keys are alternatives: a water's one surface form, a stage's
/// changes, a point's optional name).
enum class Unset { null, omit };

/// The echoed keys of one entry of the declared map `map`, in their order. A key its
/// section's reader reads (no setter: a law, a bolt's end, a block's polygon or
/// material, a point that must lie on its block) is as `other` gives it, in the words of
/// what the reader built; a discarded JSON value from `other` leaves the key out (a
/// block's `rectangle`, expanded into its `polygon`).
template <class E>
nlohmann::ordered_json entry_json(const std::vector<EntryKey<E>>& keys, const std::string& map, const E& e,
                                  const std::function<nlohmann::ordered_json(const KeyInfo&)>& other = {},
                                  Unset unset = Unset::null) {
  nlohmann::ordered_json o = nlohmann::ordered_json::object();
  for (const EntryKey<E>& k : keys) {
    if (k.map != map || !k.echoed) continue;
    if (!k.set && other) {
      nlohmann::ordered_json v = other(k);
      if (!v.is_discarded()) o[k.name] = std::move(v);
      continue;
    }
    const KeyValue v = k.get(e);
    if (unset == Unset::omit && std::holds_alternative<std::monostate>(v)) continue;
    o[k.name] = key_json(v);
  }
  return o;
}

/// A key left out of summary.json (entry_json's `other`).
inline nlohmann::ordered_json left_out() { return nlohmann::ordered_json(nlohmann::ordered_json::value_t::discarded); }

/// A law as summary.json echoes it: its declared keys (keys_joints.cpp; `name`, and what a
/// fit says of it where the scene gives it) and every parameter; null for none.
inline nlohmann::ordered_json law_json(const std::optional<LawChoice>& law) {
  if (!law) return nullptr;
  nlohmann::ordered_json o = entry_json(
      law_keys(), "law", *law,
      [&](const KeyInfo& k) -> nlohmann::ordered_json {
        if (k.name == "name") return nlohmann::ordered_json(law->name);
        if (k.name == "unidentified" && !law->unidentified.empty()) return nlohmann::ordered_json(law->unidentified);
        return left_out();
      },
      Unset::omit);
  for (const auto& [k, v] : law->parameters) o[k] = v;
  return o;
}

}  // namespace rheodda::scene::detail
