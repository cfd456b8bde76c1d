// The bolts of a scene as `rheodda check` prints them (describe.cpp) and as
// summary.json's "inputs" hold them (scene_json.cpp); scenes with bolts only.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "bolts_text.hpp"

namespace rheodda::scene {

namespace {

/// "block 'B' at (x, y)" or "fixed at (x, y)".
std::string end_text(const SceneDescription& s, const BlockPoint& p, bool fixed) {
  return fixed ? fmt::format("fixed at ({:g}, {:g})", p.point[0], p.point[1])
               : fmt::format("({:g}, {:g}) on {}", p.point[0], p.point[1], s.blocks[p.block].name);
}

}  // namespace

std::string describe_bolts(const SceneDescription& s) {
  if (s.bolts.empty()) return "";
  const Units& u = s.units;
  std::string out = fmt::format("bolts: {}\n", s.bolts.size());
  for (const auto& b : s.bolts) {
    out += fmt::format("  {}: {} to {}, axial_stiffness {:g} {}/{}, pretension {:g} {}", b.name,
                       end_text(s, b.from, false), end_text(s, b.to, b.to_fixed), b.axial_stiffness, u.force,
                       u.length, b.pretension, u.force);
    out += b.yield_force ? fmt::format(", yield_force {:g} {}", *b.yield_force, u.force) : ", never yields";
    out += b.rupture_elongation ? fmt::format(", rupture_elongation {:g} {}", *b.rupture_elongation, u.length)
                                : ", never ruptures";
    if (b.law) {
      out += fmt::format(", law {}", b.law->name);
      for (const auto& [k, v] : b.law->parameters) out += fmt::format(" {}={:g}", k, v);
    } else {
      out += ", no creep";
    }
    out += '\n';
  }
  return out;
}

void add_bolts_json(const SceneDescription& s, nlohmann::ordered_json& j) {
  if (s.bolts.empty()) return;  // a scene without bolts: its "inputs" as before
  j["bolts"] = nlohmann::ordered_json::array();
  for (const auto& b : s.bolts) {
    nlohmann::ordered_json e;
    e["name"] = b.name;
    e["from"] = {{"point", b.from.point}, {"block", s.blocks[b.from.block].name}};
    if (b.to_fixed)
      e["to"] = {{"fixed", b.to.point}};
    else
      e["to"] = {{"point", b.to.point}, {"block", s.blocks[b.to.block].name}};
    e["axial_stiffness"] = b.axial_stiffness;
    e["pretension"] = b.pretension;
    e["yield_force"] = b.yield_force ? nlohmann::ordered_json(*b.yield_force) : nlohmann::ordered_json(nullptr);
    e["rupture_elongation"] =
        b.rupture_elongation ? nlohmann::ordered_json(*b.rupture_elongation) : nlohmann::ordered_json(nullptr);
    if (b.law) {
      nlohmann::ordered_json law = {{"name", b.law->name}};
      for (const auto& [k, v] : b.law->parameters) law[k] = v;
      e["law"] = law;
    } else {
      e["law"] = nullptr;
    }
    j["bolts"].push_back(e);
  }
}

}  // namespace rheodda::scene
