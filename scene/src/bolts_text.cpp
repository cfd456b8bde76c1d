// The bolts of a scene as `rheodda check` prints them (describe.cpp) and as
// summary.json's "inputs" hold them (scene_json.cpp), with a stage's bolts;
// scenes with bolts only.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>

#include "bolts_text.hpp"
#include "key_json.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::scene {

namespace {

/// "block 'B' at (x, y)" or "fixed at (x, y)".
std::string end_text(const SceneDescription& s, const BlockPoint& p, bool fixed) {
  if (fixed) return fmt::format("fixed at ({:g}, {:g})", p.point[0], p.point[1]);
  if (p.block < 0)  // a stage's end without `block:` (stages.hpp)
    return fmt::format("({:g}, {:g}) on the block standing there", p.point[0], p.point[1]);
  return fmt::format("({:g}, {:g}) on {}", p.point[0], p.point[1], s.blocks[p.block].name);
}

}  // namespace

std::string describe_bolts(const SceneDescription& s) {
  if (s.bolts.empty()) return "";
  std::string out = fmt::format("bolts: {}\n", s.bolts.size());
  for (const auto& b : s.bolts) out += "  " + bolt_text(s, b) + '\n';
  return out;
}

std::string bolt_text(const SceneDescription& s, const BoltDescription& b) {
  const Units& u = s.units;
  std::string out =
      fmt::format("{}: {} to {}", b.name, end_text(s, b.from, false), end_text(s, b.to, b.to_fixed));
  // The declared plain keys (keys_bolts.cpp), in order; one not set as its default says ("never yields").
  for (const EntryKey<BoltDescription>& k : bolt_keys()) {
    if (k.map != "bolts" || k.type == KeyType::name || k.type == KeyType::map) continue;
    const KeyValue v = k.get(b);
    out += std::holds_alternative<std::monostate>(v) ? ", " + k.default_text
                                                     : fmt::format(", {} {}", k.name, key_value_text(k, v, u));
  }
  if (b.law) {
    out += fmt::format(", law {}", b.law->name);
    for (const auto& [k, v] : b.law->parameters) out += fmt::format(" {}={:g}", k, v);
  } else {
    out += ", no creep";
  }
  return out;
}

nlohmann::ordered_json bolt_json(const SceneDescription& s, const BoltDescription& b) {
  // The declared keys (keys_bolts.cpp); the ends (their declared keys, the block by its
  // name; left out: a stage's end found where it stands) and the law as their readers read them.
  auto end_json = [&](const std::vector<EntryKey<BlockPoint>>& keys, const std::string& map, const BlockPoint& p,
                      bool fixed) {
    return detail::entry_json(keys, map, p, [&](const KeyInfo& k) -> nlohmann::ordered_json {
      if (k.name == "fixed") return fixed ? nlohmann::ordered_json(p.point) : detail::left_out();
      if (k.name == "point") return fixed ? detail::left_out() : nlohmann::ordered_json(p.point);
      if (k.name == "block" && p.block >= 0) return s.blocks[static_cast<std::size_t>(p.block)].name;
      return detail::left_out();
    }, detail::Unset::omit);
  };
  return detail::entry_json(bolt_keys(), "bolts", b, [&](const KeyInfo& k) -> nlohmann::ordered_json {
    if (k.name == "law") return detail::law_json(b.law);
    if (k.name == "from") return end_json(bolt_end_keys(), "bolts.from", b.from, false);
    if (k.name == "to") return end_json(bolt_to_keys(), "bolts.to", b.to, b.to_fixed);
    return detail::left_out();
  });
}

std::vector<const BoltDescription*> all_bolts(const SceneDescription& s) {
  std::vector<const BoltDescription*> out;
  for (const auto& b : s.bolts) out.push_back(&b);
  for (const auto& st : s.stages)
    for (const auto& b : st.add_bolts) out.push_back(&b);
  return out;
}

bool has_bolts(const SceneDescription& s) {  // asked per history row: no list built
  return !s.bolts.empty() ||
         std::any_of(s.stages.begin(), s.stages.end(), [](const StageDescription& st) { return !st.add_bolts.empty(); });
}

}  // namespace rheodda::scene
