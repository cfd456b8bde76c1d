#include "rheodda/scene/describe.hpp"

#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/memory.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "rheodda/contact/joint_set.hpp"
#include "rheodda/core/solver.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/geometry.hpp"
#include "bolts_text.hpp"

namespace rheodda::scene {

double search_distance(const SceneDescription& s) {
  return s.analysis.search_factor * s.analysis.max_displacement_ratio * half_model_size(s.blocks);
}

namespace {

/// The solver, with what `automatic` picks for this scene's block count and
/// the stop of the iterative ones.
std::string solver_text(const SceneDescription& s) {
  const Analysis& a = s.analysis;
  const int n = static_cast<int>(s.blocks.size());
  const core::SolverKind used = core::LinearSolver::resolve(
      a.solver == SolverKind::automatic ? core::SolverKind::automatic : core::SolverKind::cholmod, n);
  std::string name(solver_name(a.solver));
  bool iterative = a.solver == SolverKind::pcg || a.solver == SolverKind::amg;
  if (a.solver == SolverKind::automatic) {
    iterative = used == core::SolverKind::amg;
    name += fmt::format(" ({} for {} blocks; amg from {})", iterative ? "amg" : "cholmod", n,
                        core::LinearSolver::kAmgBlocks);
  }
  if (iterative)
    name += fmt::format(", solver_tolerance {:g}, solver_max_iterations {}, solver_iterate_tolerance {:g}",
                        a.solver_tolerance, a.solver_max_iterations, a.solver_iterate_tolerance);
  return name;
}

}  // namespace

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
  // Every declared key with its value (keys.hpp), wrapped; what they add up to follows.
  std::string settings = "analysis:";
  std::size_t width = settings.size();
  for (const KeySpec& k : analysis_keys()) {
    if (k.type == KeyType::map) continue;
    if (k.map != "analysis" && !a.settle) continue;
    const std::string name = k.map == "analysis" ? k.name : k.map.substr(std::string("analysis.").size()) + "." + k.name;
    const std::string item = fmt::format(" {} {}", name, key_value_text(k, a, u));
    if (width + item.size() > 100) {
      settings += ",\n ";
      width = 1;
    } else if (width > std::string("analysis:").size()) {
      settings += ",";
      ++width;
    }
    settings += item;
    width += item.size();
  }
  line(settings);
  line(fmt::format("  solver {}", solver_text(s)));
  if (a.contact_solver == ContactSolverKind::newton)
    line(fmt::format("  contact_solver newton: open-close iterates accepted when the residual of the step's equations "
                     "is at most {:g} of the contact forces (docs/reference/contacts.md, \"Contact solves\")",
                     a.contact_residual_tolerance));
  line(fmt::format("  open_close_limit {}, penetration_ratio {:g}, angle_tolerance {:g} deg, search_factor {:g}",
                   a.open_close_limit, a.penetration_ratio, a.angle_tolerance, a.search_factor));
  line(fmt::format("  friction_tolerance {:g}, force_resolution {:g}, max_flips {}, max_refinements {}, "
                   "penalty_raise {:g}, penalty_max_factor {:g}",
                   a.friction_tolerance, a.force_resolution, a.max_flips, a.max_refinements,
                   a.penalty_raise, a.penalty_max_factor));
  if (a.stick_keeps_force)
    line("  stick_keeps_force: a sliding contact that sticks keeps its friction force");
  if (a.step_tolerance > 0.0)
    line(fmt::format("  time step: step doubling, step_tolerance {:g} {} ({}), dt_max {}", a.step_tolerance,
                     u.length,
                     a.step_extrapolation ? "extrapolated: second order" : "not extrapolated: first order",
                     a.dt_max > 0.0 ? fmt::format("{:g} {}", a.dt_max, u.time) : std::string("none")));
  else if (a.creep_tolerance > 0.0)
    line(fmt::format("  time step: adaptive creep stepping, creep_tolerance {:g} {}, dt_max {}{}",
                     a.creep_tolerance, u.length,
                     a.dt_max > 0.0 ? fmt::format("{:g} {}", a.dt_max, u.time) : std::string("none"),
                     a.creep_restart_on_contact_change ? ", restart on contact change" : ""));
  else
    line(fmt::format("  time step: fixed dt {:g} {} (cut by dt_cut {:g} when a step fails, then grown back by "
                     "dt_growth {:g} per step)",
                     a.dt, u.time, a.dt_cut, a.dt_growth));
  if (a.settle && a.settle->rest_tolerance > 0.0)
    line(fmt::format("  settling stage (dynamic): until at rest (kinetic energy below {:g} of the stage's work of "
                     "gravity and loads), at most {:g} {}, steps of at most {:g} {}, max_displacement_ratio {:g} "
                     "(docs/reference/engine.md, \"Dynamic stages\")",
                     a.settle->rest_tolerance, a.settle->until, u.time, a.settle->dt, u.time,
                     a.settle->max_displacement_ratio));
  else if (a.settle)
    line(fmt::format("  settling stage ({}): until {:g} {}, steps of at most {:g} {}, max_displacement_ratio {:g} "
                     "(docs/reference/engine.md, \"Settling stage\")",
                     a.settle->dynamic ? "dynamic" : "static", a.settle->until, u.time, a.settle->dt, u.time,
                     a.settle->max_displacement_ratio));
  if (a.settle && a.settle->open_close_limit > 0)
    line(fmt::format("  stage steps: cut after {} open-close iterates (the analysis's steps after {}; docs/reference/engine.md, "
                     "\"Dynamic stages\")",
                     a.settle->open_close_limit, a.open_close_limit));
  if (a.settle && a.settle->gravity_ramp > 0.0)
    line(fmt::format("  gravity ramp: gravity rises linearly from zero to its full value over the first {:g} {} of "
                     "the stage (docs/reference/engine.md, \"Gravity ramp\")",
                     a.settle->gravity_ramp, u.time));
  if (a.settle && a.settle->collapse_dt > 0.0 && a.settle->rest_tolerance > 0.0)
    line(fmt::format("  collapse stages: a static step that moves as a mechanism is cut down to {:g} {}, then taken "
                     "as a dynamic stage until at rest, at most {:g} {} (docs/reference/engine.md, \"Dynamic stages\")",
                     a.settle->collapse_dt, u.time, a.settle->until, u.time));
  else if (a.settle && a.settle->collapse_dt > 0.0)
    line(fmt::format("  collapse stages: a static step that moves as a mechanism is cut down to {:g} {}, then taken "
                     "as a dynamic stage of {:g} {} (docs/reference/engine.md, \"Collapse stages\")",
                     a.settle->collapse_dt, u.time, a.settle->until, u.time));
  line(fmt::format("  output every {:g} {}: {} frames", a.output_interval, u.time,
                   static_cast<long long>(std::ceil(a.duration / a.output_interval - 1e-9)) + 1));
  line(fmt::format("  run guards: stop when a block moves more than {} or the outputs exceed {}",
                   a.max_travel_ratio > 0.0 ? fmt::format("{:g} x the model size", a.max_travel_ratio)
                                            : std::string("(no limit)"),
                   a.max_output_size > 0.0 ? fmt::format("{:g} MB", a.max_output_size) : std::string("(no limit)")));

  line(fmt::format("materials ({}):", s.materials.size()));
  for (const auto& m : s.materials)
    line(fmt::format("  {}: {}", m.name, key_values_text(material_keys(), "materials", m, u)));  // keys_joints.cpp

  line(fmt::format("joint sets ({}):", s.joint_sets.size()));
  for (const auto& j : s.joint_sets) {
    auto stiff = [&](const std::optional<double>& k, const char* fallback) {
      return k ? fmt::format("{:g} {}/{}", *k, stress, u.length) : std::string(fallback);
    };
    line(fmt::format("  {}: friction_angle {:g} deg, cohesion {:g} {}, tensile_strength {:g} {}", j.name,
                     j.friction_angle, j.cohesion, stress, j.tensile_strength, stress));
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
  if (s.rock_mass) {
    // What the cut gave (docs/guide/rockmass.md): block count, size distribution, joint lengths.
    const RockMassDescription& r = *s.rock_mass;
    double region = std::abs(signed_area(r.region.outer));
    for (const auto& h : r.region.holes) region -= std::abs(signed_area(h));
    line(fmt::format("rock mass '{}': {} blocks ({} .. {}) cut from a region of {:g} {}^2 ({} vertices, {} holes), "
                     "material {}, seed {}",
                     r.name, r.block_count, r.block_count ? s.blocks[r.first_block].name : "-",
                     r.block_count ? s.blocks[r.first_block + r.block_count - 1].name : "-", region, u.length,
                     r.region.outer.size(), r.region.holes.size(), s.materials[r.material].name, r.seed));
    std::vector<double> areas;
    for (std::size_t i = r.first_block; i < r.first_block + r.block_count; ++i)
      areas.push_back(signed_area(s.blocks[i].polygon));
    std::sort(areas.begin(), areas.end());
    if (!areas.empty()) {
      auto q = [&](double f) { return areas[static_cast<std::size_t>(f * double(areas.size() - 1) + 0.5)]; };
      double sum = 0.0;
      for (double x : areas) sum += x;
      line(fmt::format("  block area [{}^2]: min {:.4g}, 10% {:.4g}, median {:.4g}, mean {:.4g}, 90% {:.4g}, max {:.4g}; "
                       "sum - region area: {:.2g} relative",
                       u.length, areas.front(), q(0.1), q(0.5), sum / double(areas.size()), q(0.9), areas.back(),
                       r.area_error));
    }
    line(fmt::format("  estimated before cutting: {:.3g} trace crossings, up to {:.3g} blocks, {} of memory",
                     r.estimate.crossings, r.estimate.pieces, format_bytes(r.estimate.bytes)));
    line(fmt::format("  slivers merged (sliver_area {:g} {}^2): {}; dead-end trace segments removed: {}",
                     r.sliver_area, u.length, r.merged_slivers, r.dangling_removed));
    if (r.extended_traces > 0)
      line(fmt::format("  traces extended so that every block is a simple polygon: {} ({} of them parallel to a "
                       "block's joints, from a hole no trace reached)",
                       r.extended_traces, r.added_traces));
    if (r.collapsed_blocks > 0)
      line(fmt::format("  blocks of rounding size dropped (vertices closer than 1e-9 of the region welded): {}",
                       r.collapsed_blocks));
    for (std::size_t k = 0; k < r.joint_sets.size(); ++k) {
      const auto& g = r.joint_sets[k];
      line(fmt::format("  joint set {}: dip {:g} deg to the {}, spacing {:g} {} ({}{}), {}{}; {} traces drawn",
                       s.joint_sets[g.tag].name, g.dip, g.dips_right ? "right" : "left", g.spacing, u.length,
                       rockmass::spacing_distribution_name(g.spacing_distribution),
                       g.spacing_deviation > 0.0 ? fmt::format(", deviation {:g}", g.spacing_deviation) : "",
                       g.trace_length ? fmt::format("trace_length {:g} {}, gap {:g} {} (persistence {:.3g})",
                                                    *g.trace_length, u.length, g.gap, u.length,
                                                    *g.trace_length / (*g.trace_length + g.gap))
                                      : std::string("persistent"),
                       g.dip_spread > 0.0 ? fmt::format(", dip_spread {:g} deg", g.dip_spread) : "",
                       r.traces_generated[k]));
    }
    if (!r.traces.empty()) line(fmt::format("  explicit traces: {}", r.traces.size()));
    for (const auto& [tag, length] : r.joint_length)
      line(fmt::format("  joint length in the blocks, {}: {:g} {}",
                       tag < 0 ? fmt::format("region boundary (joint set {})", s.joint_sets[r.boundary_joint_set].name)
                               : s.joint_sets[tag].name,
                       length, u.length));
  }

  // The points (keys_points.cpp): every key given, the block by its name.
  auto on_block = [&](const KeyInfo& k, const Point& p, int block) -> std::string {
    if (k.name == "point") return key_value_text(k, p, u);
    if (k.name == "block") return s.blocks[static_cast<std::size_t>(block)].name;
    return "";
  };
  line(fmt::format("fixed points: {}", s.fixed_points.size()));
  for (const auto& p : s.fixed_points)
    line("  " + key_values_text(fixed_point_keys(), "fixed_points", p, u,
                                [&](const KeyInfo& k) { return on_block(k, p.point, p.block); }));
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
