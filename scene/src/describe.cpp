#include "rheodda/scene/describe.hpp"

#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/memory.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/core/defaults.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/geometry.hpp"
#include "bolts_text.hpp"
#include "describe_parts.hpp"

namespace rheodda::scene {

double search_distance(const SceneDescription& s) {
  return s.analysis.search_factor * s.analysis.max_displacement_ratio * half_model_size(s.blocks);
}


std::string exact_number(double v) {
  for (int digits : {6, 10}) {
    const std::string t = fmt::format("{:.{}g}", v, digits);
    if (std::strtod(t.c_str(), nullptr) == v) return t;  // (std::stod throws on denormals)
  }
  return fmt::format("{:.17g}", v);
}

std::string scheme_text(const Analysis& a) {
  return a.scheme ? std::string(laws::scheme_name(*a.scheme)) : std::string("automatic");
}

std::string describe_scene(const SceneDescription& s) {
  const Units& u = s.units;
  const Analysis& a = s.analysis;
  const std::string stress = u.stress();
  std::string out;
  auto line = [&out](const std::string& t) { out += t + '\n'; };

  line(fmt::format("scene: {} ({})", s.title, s.file));
  line(fmt::format("units: {}; stress {}", key_values_text(units_keys(), "units", u, u), stress));  // keys_top.cpp
  out += detail::describe_given_quantities(s);  // describe_quantities.cpp
  out += detail::describe_analysis(s);  // describe_analysis.cpp

  line(fmt::format("materials ({}):", s.materials.size()));
  for (const auto& m : s.materials)
    line(fmt::format("  {}: {}", m.name, key_values_text(material_keys(), "materials", m, u)));  // keys_joints.cpp

  line(fmt::format("joint sets ({}):", s.joint_sets.size()));
  for (const auto& j : s.joint_sets) {
    auto stiff = [&](const std::optional<double>& k, const char* fallback) {
      return k ? fmt::format("{:g} {}/{}", *k, stress, u.length) : std::string(fallback);
    };
    // The declared keys (keys_joints.cpp) but those the lines below describe in words of their own.
    line(fmt::format("  {}: {}", j.name,
                     key_values_text(keys_except(joint_set_keys(), {"residual_friction_angle", "residual_cohesion",
                                                                    "normal_stiffness", "shear_stiffness",
                                                                    "restitution", "record"}),
                                     "joint_sets", j, u)));
    line(fmt::format("    once slid, opened or failed: residual_friction_angle {:g} deg, residual_cohesion {:g} {}, "
                     "tensile_strength 0",
                     j.residual_friction_angle.value_or(j.friction_angle), j.residual_cohesion, stress));
    line(fmt::format("    normal_stiffness {}, shear_stiffness {}{}",
                     stiff(j.normal_stiffness, "penalty"),
                     j.law && j.law->parameters.count("E1")
                         ? fmt::format("E1 of the law ({} {}/{})", exact_number(j.law->parameters.at("E1")), stress, u.length)
                         : stiff(j.shear_stiffness, "penalty / shear_normal_ratio"),
                     j.record ? ", recorded in history.csv" : ""));
    if (j.restitution)
      line(fmt::format("    restitution {:g} (contact dashpots, damping ratio {:.4g})", *j.restitution,
                       contact::restitution_damping_ratio(*j.restitution)));
    if (j.law) {
      std::string params;
      for (const auto& [k, v] : j.law->parameters) params += fmt::format(" {}={}", k, exact_number(v));
      line(fmt::format("    law {}:{} (scheme {})", j.law->name, params, scheme_text(a)));
      // What a fit says of it (keys_joints.cpp; the warnings: law_choice.cpp).
      if (!j.law->unidentified.empty() || j.law->tested_stress || j.law->tested_duration)
        line(fmt::format("    fitted law: unidentified {}; tested_stress {}; tested_duration {}",
                         j.law->unidentified.empty() ? std::string("none") : fmt::format("{}", fmt::join(j.law->unidentified, ", ")),
                         j.law->tested_stress ? fmt::format("[{:g}, {:g}] {}", (*j.law->tested_stress)[0],
                                                            (*j.law->tested_stress)[1], stress)
                                              : std::string("not stated"),
                         j.law->tested_duration ? fmt::format("{:g} {}", *j.law->tested_duration, u.time)
                                                : std::string("not stated")));
    } else {
      line("    law: none (no creep)");
    }
  }

  double area = 0.0;
  int fixed_blocks = 0;
  for (const auto& b : s.blocks) {
    area += signed_area(b.polygon);
    fixed_blocks += b.fixed ? 1 : 0;
  }
  line(fmt::format("blocks ({}): total area {:g} {}^2, {} fixed", s.blocks.size(), area, u.length, fixed_blocks));
  constexpr std::size_t kListed = 40;
  for (std::size_t i = 0; i < s.blocks.size() && i < kListed; ++i) {
    const auto& b = s.blocks[i];
    std::string sets;
    for (std::size_t k = 0; k < b.edge_joint_set.size(); ++k)
      sets += (k ? "," : "") + s.joint_sets[b.edge_joint_set[k]].name;
    line(fmt::format("  {}: {} vertices, area {:g} {}^2, material {}, edges [{}]{}", b.name, b.polygon.size(),
                     signed_area(b.polygon), u.length, s.materials[b.material].name, sets,
                     b.fixed ? ", fixed" : ""));
  }
  if (s.blocks.size() > kListed) line(fmt::format("  ... and {} more", s.blocks.size() - kListed));
  if (s.rock_mass) out += detail::describe_rock_mass(s, *s.rock_mass);  // describe_rock_mass.cpp

  // The points (keys_points.cpp): every key given, the block by its name.
  auto on_block = [&](const KeyInfo& k, const Point& p, int block) -> std::string {
    if (k.name == "point") return key_value_text(k, p, u);
    if (k.name == "block") return s.blocks[static_cast<std::size_t>(block)].name;
    return "";
  };
  line(fmt::format("fixed points: {}", s.fixed_points.size()));
  for (const auto& p : s.fixed_points) {
    std::string text = "  " + key_values_text(fixed_point_keys(), "fixed_points", p, u,
                                              [&](const KeyInfo& k) { return on_block(k, p.point, p.block); });
    if (p.hold == "rotation") {  // its spring k_r = p J/S (core/include/rheodda/core/defaults.hpp)
      std::vector<core::Vec2> polygon;
      for (const Point& v : s.blocks[static_cast<std::size_t>(p.block)].polygon) polygon.emplace_back(v[0], v[1]);
      text += fmt::format(" (a rotational spring of {:.4g} {}·{}/rad)",
                          core::rotation_hold_stiffness(s.analysis.fixed_point_stiffness, polygon), u.force, u.length);
    }
    line(text);
  }
  line(fmt::format("loads: {}", s.loads.size()));
  for (const auto& l : s.loads)
    line("  " + key_values_text(load_keys(), "loads", l, u, [&](const KeyInfo& k) -> std::string {
           const auto& h = l.history;
           if (k.name != "history") return on_block(k, l.at.point, l.at.block);
           if (h.size() == 1) return "";  // a constant force: `force` says it
           return fmt::format("of {} samples, t = {:g} .. {:g} {}", h.size(), h.front()[0], h.back()[0], u.time);
         }));
  line(fmt::format("measurement points: {}", s.measurement_points.size()));
  for (const auto& m : s.measurement_points)
    line("  " + key_values_text(measurement_point_keys(), "measurement_points", m, u,
                                [&](const KeyInfo& k) { return on_block(k, m.at.point, m.at.block); }));
  if (s.water) out += describe_water(*s.water, u);  // water.hpp
  if (!s.stages.empty()) {  // docs/reference/stages.md
    line(fmt::format("stages: {}", s.stages.size()));
    for (const StageDescription& st : s.stages) {
      std::vector<std::string> did;
      if (!st.remove_fixed_points.empty())
        did.push_back(fmt::format("remove fixed points {}", fmt::join(st.remove_fixed_points, ", ")));
      if (!st.remove_loads.empty()) did.push_back(fmt::format("remove loads {}", fmt::join(st.remove_loads, ", ")));
      if (!st.remove_blocks.empty()) {
        std::vector<std::string> names;
        for (int b : st.remove_blocks) names.push_back(s.blocks[static_cast<std::size_t>(b)].name);
        did.push_back(names.size() <= 8 ? fmt::format("remove {} blocks ({})", names.size(), fmt::join(names, ", "))
                                        : fmt::format("remove {} blocks ({}, ...)", names.size(),
                                                      fmt::join(names.begin(), names.begin() + 8, ", ")));
      }
      if (!st.add_fixed_points.empty()) did.push_back(fmt::format("add {} fixed points", st.add_fixed_points.size()));
      if (!st.add_loads.empty()) did.push_back(fmt::format("add {} loads", st.add_loads.size()));
      if (!st.add_bolts.empty()) {
        std::vector<std::string> names;
        for (const BoltDescription& b : st.add_bolts) names.push_back(b.name);
        did.push_back(fmt::format("install {} bolts ({})", names.size(), fmt::join(names, ", ")));
      }
      for (const StageJointSet& c : st.joint_sets)
        did.push_back(fmt::format("change joint set {}", s.joint_sets[static_cast<std::size_t>(c.joint_set)].name));
      if (st.dynamic_ratio)
        did.push_back(*st.dynamic_ratio > 0.0 ? fmt::format("dynamic analysis (dynamic_ratio {:g})", *st.dynamic_ratio)
                                              : std::string("static analysis"));
      if (st.settle) did.push_back("open a settling stage");
      if (st.water) did.push_back("change the water (times from the stage's start)");
      line(fmt::format("  {} {}: {}", st.name,
                       st.start == StageStart::at ? fmt::format("at t = {:g} {}", st.at, u.time)
                                                  : std::string("after the settling stage ends at rest"),
                       fmt::join(did, "; ")));
      for (const BoltDescription& b : st.add_bolts) line("    " + bolt_text(s, b));  // bolts_text.cpp
    }
  }
  out += describe_bolts(s);  // bolts_text.cpp; nothing without bolts

  // Contacts at the start are the touching vertex-edge pairs: count those within a
  // twentieth of the median block size (or the search distance, if smaller).
  std::vector<double> sizes;
  for (const auto& b : s.blocks) sizes.push_back(std::sqrt(std::abs(signed_area(b.polygon))));
  std::nth_element(sizes.begin(), sizes.begin() + static_cast<long>(sizes.size() / 2), sizes.end());
  const double search = search_distance(s);
  const double d = std::min(search, 0.05 * sizes[sizes.size() / 2]);
  const ContactEstimate est = estimate_contacts(s.blocks, d);
  line(fmt::format("estimated contacts at the start: {} between {} block pairs (vertex-edge pairs closer than {:g} {})",
                   est.vertex_edge, est.block_pairs, d, u.length));
  line(fmt::format("contact search distance: up to {:g} {} (search_factor x max_displacement_ratio x half model size;"
                   " in large models as far as the motion needs, docs/reference/engine.md)",
                   search, u.length));
  {
    const MemoryEstimate need = estimate_memory(s);
    const auto available = available_memory();
    line(fmt::format("estimated memory of a run: {} (solver {}){}", format_bytes(need.bytes), need.solver,
                     available ? fmt::format("; {} available{}", format_bytes(*available),
                                             need.bytes > *available ? ": `run` will refuse it" : "")
                               : std::string()));
  }
  const auto warnings = scene_warnings(s);
  if (!warnings.empty()) {
    line(fmt::format("warnings ({}):", warnings.size()));
    for (const auto& w : warnings) line("  " + w);
  }
  return out;
}

}  // namespace rheodda::scene
