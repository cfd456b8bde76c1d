// `rheodda check`'s lines on the analysis (describe_parts.hpp): every declared key of
// `analysis:` with its value (keys.hpp), wrapped, then what they add up to.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "describe_parts.hpp"
#include "rheodda/core/solver.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/keys.hpp"

namespace rheodda::scene::detail {

namespace {

/// The solver, with what `automatic` picks for this scene's block count and
/// the stop of the iterative ones.
std::string solver_text(const SceneDescription& s) {
  const Analysis& a = s.analysis;
  const int n = static_cast<int>(s.blocks.size());
  const core::SolverKind used = core::LinearSolver::resolve(a.solver, n);
  std::string name(core::linear_solver_entry(a.solver).word);
  const bool iterative = used != core::SolverKind::cholmod;
  if (a.solver == core::SolverKind::automatic)
    name += fmt::format(" ({} for {} blocks; amg from {})", core::linear_solver_entry(used).word, n,
                        core::LinearSolver::kAmgBlocks);
  if (iterative)
    name += fmt::format(", solver_tolerance {:g}, solver_max_iterations {}, solver_iterate_tolerance {:g}",
                        a.solver_tolerance, a.solver_max_iterations, a.solver_iterate_tolerance);
  return name;
}

}  // namespace

namespace {

/// How many output times run_output_times(a) lists, without listing them (a scene may
/// ask for more than fit in memory: `check` describes it all the same).
long long output_time_count(const Analysis& a) {
  const double n = std::ceil(a.duration / a.output_interval - 1e-9);
  long long count = static_cast<long long>(std::min(n, 9.0e18)) + 1;
  const double same = 1e-9 * a.duration;
  for (const double t : a.output_times) {
    const double k = std::round(t / a.output_interval);
    if (std::abs(t - k * a.output_interval) > same && a.duration - t > same) ++count;
  }
  return count;
}

}  // namespace

std::string describe_analysis(const SceneDescription& s) {
  const Units& u = s.units;
  const Analysis& a = s.analysis;
  std::string out;
  auto line = [&out](const std::string& t) { out += t + '\n'; };
  // Every declared key with its value (keys.hpp), wrapped; what they add up to follows.
  std::string settings = "analysis:";
  std::size_t width = settings.size();
  for (const KeySpec& k : analysis_keys()) {
    if (k.type == KeyType::map) continue;
    if (k.map != "analysis" && !a.has_settle()) continue;
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
  if (a.contact_solver == core::ContactSolver::newton)
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
  if (a.has_settle() && a.settle.rest_tolerance > 0.0)
    line(fmt::format("  settling stage (dynamic): until at rest (kinetic energy below {:g} of the stage's work of "
                     "gravity and loads{}), at most {:g} {}, steps of at most {:g} {}, max_displacement_ratio {:g} "
                     "(docs/reference/engine.md, \"Dynamic stages\")",
                     a.settle.rest_tolerance,
                     a.settle.force_ratio > 0.0
                         ? fmt::format("; explicit steps: unbalanced-force ratio below {:g}", a.settle.force_ratio)
                         : std::string(),
                     a.settle.until, u.time, a.settle.dt, u.time, a.settle.max_displacement_ratio));
  else if (a.has_settle())
    line(fmt::format("  settling stage ({}): until {:g} {}, steps of at most {:g} {}, max_displacement_ratio {:g} "
                     "(docs/reference/engine.md, \"Settling stage\")",
                     a.settle.dynamic ? "dynamic" : "static", a.settle.until, u.time, a.settle.dt, u.time,
                     a.settle.max_displacement_ratio));
  if (a.has_settle() && a.settle.open_close_limit > 0)
    line(fmt::format("  stage steps: cut after {} open-close iterates (the analysis's steps after {}; docs/reference/engine.md, "
                     "\"Dynamic stages\")",
                     a.settle.open_close_limit, a.open_close_limit));
  if (a.has_settle() && a.settle.gravity_ramp > 0.0)
    line(fmt::format("  gravity ramp: gravity rises linearly from zero to its full value over the first {:g} {} of "
                     "the stage (docs/reference/engine.md, \"Gravity ramp\")",
                     a.settle.gravity_ramp, u.time));
  if (a.has_settle() && a.settle.collapse_dt > 0.0 && a.settle.rest_tolerance > 0.0)
    line(fmt::format("  collapse stages: a static step that moves as a mechanism is cut down to {:g} {}, then taken "
                     "as a dynamic stage until at rest, at most {:g} {} (docs/reference/engine.md, \"Dynamic stages\")",
                     a.settle.collapse_dt, u.time, a.settle.until, u.time));
  else if (a.has_settle() && a.settle.collapse_dt > 0.0)
    line(fmt::format("  collapse stages: a static step that moves as a mechanism is cut down to {:g} {}, then taken "
                     "as a dynamic stage of {:g} {} (docs/reference/engine.md, \"Collapse stages\")",
                     a.settle.collapse_dt, u.time, a.settle.until, u.time));
  line(fmt::format("  output every {:g} {}{}: {} output times, a step ends on each{}; history.csv {}; {}",
                   a.output_interval, u.time,
                   a.output_times.empty() ? "" : fmt::format(" and at {} output_times", a.output_times.size()),
                   output_time_count(a),
                   a.output_interval < a.dt ? fmt::format(" (output_interval is shorter than dt = {:g} {}: so are the steps)", a.dt, u.time) : "",
                   a.history == HistoryRows::steps ? "a row after every step" : "a row at each (and at the dynamic stages' ends)",
                   a.frames ? "a frame at each" : "no frames"));
  line(fmt::format("  run guards: stop when a block moves more than {} or the outputs exceed {}",
                   a.max_travel_ratio > 0.0 ? fmt::format("{:g} x the model size", a.max_travel_ratio)
                                            : std::string("(no limit)"),
                   a.max_output_size > 0.0 ? fmt::format("{:g} MB", a.max_output_size) : std::string("(no limit)")));
  return out;
}

}  // namespace rheodda::scene::detail
