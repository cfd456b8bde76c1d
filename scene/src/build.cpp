#include "rheodda/scene/build.hpp"


#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/core/settings.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/series_law.hpp"
#include "law_choice.hpp"
#include "rheodda/scene/geometry.hpp"
#include "gravity_check.hpp"
#include "rheodda/scene/integrator_choice.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::scene {

std::vector<std::string> scene_warnings(const SceneDescription& s) {
  // What a fitted law carries: its unidentified parameters, the duration it was tested for (law_choice.cpp).
  std::vector<std::string> out = detail::law_choice_warnings(s);
  const Analysis& a = s.analysis;
  if (auto w = detail::gravity_warning(s)) out.push_back(std::move(*w));  // gravity_check.cpp
  // The lagged scheme's stability limit (only when the scene asks for lagged:
  // the automatic choice and the other schemes are stable at any step). The
  // series stiffness per unit area is the joint set's shear_stiffness or the
  // law's E1; with a penalty shear spring it depends on each contact's length
  // and is not known here.
  if (a.scheme && *a.scheme == laws::Scheme::lagged) {
    const auto& registry = laws::LawRegistry::builtin();
    const bool adaptive = a.creep_tolerance > 0.0 || a.step_tolerance > 0.0;
    const double largest = adaptive ? (a.dt_max > 0.0 ? a.dt_max : std::numeric_limits<double>::infinity()) : a.dt;
    for (const auto& js : s.joint_sets) {
      if (!js.law) continue;
      std::optional<double> k = js.shear_stiffness;
      if (!k) {
        const auto e1 = js.law->parameters.find("E1");
        if (e1 != js.law->parameters.end()) k = e1->second;
      }
      if (!k) continue;
      const auto law = registry.create(js.law->name, js.law->parameters);
      const auto* series = dynamic_cast<const laws::SeriesLaw*>(law.get());
      if (!series) continue;
      const double limit = series->lagged_step_limit(*k);
      if (largest > limit)
        out.push_back(fmt::format(
            "joint set '{}': the lagged scheme is unstable for steps above {:g} {} with this law and a shear "
            "stiffness of {:g} (docs/reference/step-controls.md, \"Stability of the lagged scheme\"), and {} {:g} {}: give "
            "analysis.scheme implicit or exponential-linear (or leave it automatic), or {} below the limit",
            js.name, limit, s.units.time, *k, adaptive ? "steps may grow to" : "dt is", largest, s.units.time,
            adaptive ? "dt_max" : "dt"));
    }
  }
  // Slivers and needles: a block whose mean thickness 2A/P is a tiny share of the
  // model, or far below its own length, makes an ill-conditioned system.
  const double w0 = half_model_size(s.blocks);
  for (const auto& b : s.blocks) {
    double area = 0.0, perimeter = 0.0;
    const std::size_t n = b.polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = b.polygon[i];
      const auto& q = b.polygon[(i + 1) % n];
      area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
      perimeter += std::hypot(q[0] - p[0], q[1] - p[1]);
    }
    const double thickness = 2.0 * std::abs(area) / perimeter;  // 2A/P: half the width of a long strip
    if (thickness < 1e-6 * w0)
      out.push_back(fmt::format("block '{}' is a sliver: its mean thickness 2A/P = {:g} {} is below 1e-6 of the "
                                "half model size ({:g} {}); merge it with a neighbour or remove it",
                                b.name, thickness, s.units.length, w0, s.units.length));
    else if (perimeter / thickness > 1e4)
      out.push_back(fmt::format("block '{}' has an extreme aspect ratio (perimeter / mean thickness = {:.3g}); "
                                "its stiffness matrix is ill-conditioned: split it or thicken it",
                                b.name, perimeter / thickness));
  }
  // Contact dashpots act once a step resolves the contact's vibration: its
  // period on the penalty spring is T = 2 pi sqrt(m / p_n), shortest for the
  // lightest free block; at steps above about T/10 an impact is left to the
  // velocity update (docs/reference/contacts.md, "Contact damping": the drop on an
  // incline converges from T/10 on). Joint sets with a normal stiffness per
  // area have springs that depend on each contact's length: not estimated.
  // One warning for all the joint sets concerned (the period is the scene's),
  // saying what to do; none where the scene accepts it (accept_unresolved_impacts).
  if (a.has_dynamic_steps() && a.penalty > 0.0 && !a.accept_unresolved_impacts) {
    double lightest = std::numeric_limits<double>::infinity();
    for (const auto& b : s.blocks) {
      if (b.fixed) continue;
      double area = 0.0;
      for (std::size_t i = 0; i < b.polygon.size(); ++i) {
        const auto& p = b.polygon[i];
        const auto& q = b.polygon[(i + 1) % b.polygon.size()];
        area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
      }
      lightest = std::min(lightest, s.materials[b.material].density * std::abs(area));
    }
    const double period = 2.0 * std::numbers::pi * std::sqrt(lightest / a.penalty);
    const bool adaptive = a.creep_tolerance > 0.0 || a.step_tolerance > 0.0;
    // The dynamic steps: the analysis's, or a dynamic settling stage's in a static analysis.
    const bool settle = a.type == AnalysisType::static_analysis;
    const double largest = settle ? a.settle.dt : adaptive && a.dt_max > 0.0 ? a.dt_max : a.dt;
    const char* key = settle ? "settle.dt" : adaptive && a.dt_max > 0.0 ? "dt_max" : "dt";
    std::vector<std::string> sets;
    for (const auto& js : s.joint_sets)
      if (js.restitution && !js.normal_stiffness) sets.push_back("'" + js.name + "'");
    if (!sets.empty() && std::isfinite(period) && largest > 0.1 * period)
      out.push_back(fmt::format(
          "joint set{} {}: `restitution` acts as given only at dynamic steps below {:.3g} {} (a tenth of the "
          "contacts' vibration period), and {} is {:g} {}: give a smaller {} or, where `rheodda check --refine` "
          "shows no change, `analysis.accept_unresolved_impacts: true` (docs/reference/contacts.md)",
          sets.size() == 1 ? "" : "s", fmt::join(sets, ", "), 0.1 * period, s.units.time, key, largest, s.units.time,
          key));
  }
  return out;
}

core::FixedPoint build_fixed_point(int block, double x, double y, const std::string& hold) {
  core::FixedPoint fp{block, {x, y}};
  // `hold: both | x | y | rotation` (docs/reference/scene-format.md, "fixed_points")
  fp.hold_x = hold == "both" || hold == "x";
  fp.hold_y = hold == "both" || hold == "y";
  fp.hold_rotation = hold == "rotation";
  return fp;
}

BuiltScene build_scene(const SceneDescription& s) {
  BuiltScene out;
  core::Model& m = out.model;
  const Analysis& a = s.analysis;

  m.materials.clear();
  for (const auto& mat : s.materials) m.materials.push_back(mat);  // the engine's Material, whole

  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    const BlockDescription& b = s.blocks[i];
    core::BlockDef def;
    for (const auto& p : b.polygon) def.vertices.emplace_back(p[0], p[1]);
    def.edge_joint_set = b.edge_joint_set;
    def.material = b.material;
    def.initial_stress = {b.initial_stress[0], b.initial_stress[1], b.initial_stress[2]};
    def.initial_velocity = {b.initial_velocity[0], b.initial_velocity[1]};
    def.initial_angular_velocity = b.initial_velocity[2];
    m.blocks.push_back(std::move(def));
    if (b.fixed)
      for (const auto& p : b.polygon) m.fixed_points.push_back({static_cast<int>(i), {p[0], p[1]}});
  }
  for (const auto& f : s.fixed_points)
    m.fixed_points.push_back(build_fixed_point(f.block, f.point[0], f.point[1], f.hold));
  for (const auto& l : s.loads) {
    core::PointLoad load;
    load.block = l.at.block;
    load.point = {l.at.point[0], l.at.point[1]};
    for (const auto& h : l.history) load.history.push_back({h[0], {h[1], h[2]}});
    m.point_loads.push_back(std::move(load));
  }
  for (const auto& mp : s.measurement_points)
    m.measurement_points.push_back({mp.at.block, {mp.at.point[0], mp.at.point[1]}});
  if (s.water) m.water = build_water(*s.water, s);  // water.hpp
  for (const auto& b : s.bolts) m.bolts.push_back(build_bolt(b));  // docs/reference/bolts.md

  // The scene's analysis is the engine's settings and the contact layer's (scene.hpp):
  // handed on whole; the integrator `automatic` is decided here (integrator_choice.cpp).
  core::Settings& st = m.settings;
  st = a;
  st.integrator = choose_integrator(s).integrator;
  contact::ContactSettings& cs = out.contact_settings;
  cs = a;
  // A dynamic settling stage of a static analysis keeps the dynamic default.
  if (a.type == AnalysisType::static_analysis && a.has_dynamic_steps() && !a.stick_keeps_force_given)
    cs.stick_keeps_force_dynamic = true;
  cs.lock_at_touch = a.has_dynamic_steps();  // the static steps turn it off (StepContext::dynamic)
  cs.reversal_at_normal_resolution = cs.lock_at_touch;

  const auto& registry = laws::LawRegistry::builtin();
  for (const auto& js : s.joint_sets) {
    contact::JointSet j;
    static_cast<contact::JointProperties&>(j) = js;  // the declared properties (contact/joint_set_specs.hpp), whole
    j.name = js.name;
    if (js.law) j.law = registry.create(js.law->name, js.law->parameters);
    out.joint_sets.push_back(std::move(j));
  }
  out.warnings = scene_warnings(s);
  return out;
}

core::Bolt build_bolt(const BoltDescription& b) {
  core::Bolt bolt;
  bolt.block_a = b.from.block;
  bolt.point_a = {b.from.point[0], b.from.point[1]};
  bolt.block_b = b.to_fixed ? -1 : b.to.block;
  bolt.point_b = {b.to.point[0], b.to.point[1]};
  static_cast<core::BoltProperties&>(bolt) = b;  // the declared properties (core/property_specs.hpp), whole
  if (b.law) bolt.law = laws::LawRegistry::builtin().create(b.law->name, b.law->parameters);
  return bolt;
}

}  // namespace rheodda::scene
