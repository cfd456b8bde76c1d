#include "rheodda/study/refinement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"

namespace rheodda::study {
namespace fs = std::filesystem;

namespace {

/// "displacement" for the displacement outputs, "work" for the work columns: a
/// quantity is judged against the largest of its kind.
std::string kind_of(const std::string& output) {
  return output.rfind("work_", 0) == 0 ? "work" : "displacement";
}

}  // namespace

RefinementStudy refinement_study(const std::string& scene_path, const std::string& study_file,
                                 const RefinementOptions& o) {
  if (o.levels < 2 || o.levels > 12)
    throw std::invalid_argument(fmt::format("--refine {}: the levels must be 2 to 12 (each level costs twice "
                                            "the one before)", o.levels));
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw std::invalid_argument(fmt::format("--tolerance {}: must be in (0, 1)", o.tolerance));
  const scene::SceneDescription s = scene::load_scene(scene_path);
  const scene::Analysis& a = s.analysis;
  const double until = o.until.value_or(a.duration);
  if (!(until > 0.0) || until > a.duration * (1.0 + 1e-12))
    throw std::invalid_argument(fmt::format("--until {:g}: must be in (0, {:g}], the scene's duration [{}]", until,
                                            a.duration, s.units.time));
  // A settling stage that ends at rest (rest_tolerance) has `until` only as its longest:
  // where it ends is the run's to find.
  if (a.has_settle() && !(a.settle.rest_tolerance > 0.0) && until <= a.settle.until)
    throw std::invalid_argument(fmt::format("--until {:g}: must be after the end of the settling stage ({:g} {})",
                                            until, a.settle.until, s.units.time));

  RefinementStudy r;
  StudyDescription& st = r.study;
  st.file = study_file;
  st.scene = fs::absolute(scene_path).lexically_normal().string();
  st.title = fmt::format("Step refinement of {}", s.title);
  for (const auto& m : s.measurement_points) st.outputs.push_back(m.name + ".displacement");
  for (const auto& j : s.joint_sets)
    if (j.record) st.outputs.push_back(j.name + ".shear_displacement_magnitude");
  if (a.gravity[0] != 0.0 || a.gravity[1] != 0.0) st.outputs.push_back("work_gravity");
  if (!s.loads.empty()) st.outputs.push_back("work_loads");
  if (st.outputs.empty())
    throw std::invalid_argument(fmt::format(
        "{}: nothing to compare between the levels: the scene has no measurement point, no recorded joint set "
        "(record: true), no gravity and no load", scene_path));
  st.plot = st.outputs.front();
  st.times = {0.5 * until, until};
  if (a.has_settle() && st.times[0] <= a.settle.until) st.times.erase(st.times.begin());

  // The common `set`: the shorter duration, when asked for.
  std::vector<Override> common;
  if (o.until && *o.until < a.duration) {
    common.push_back({"analysis.duration", scene::exact_number(until), {}});
    if (a.output_interval > until) common.push_back({"analysis.output_interval", scene::exact_number(until), {}});
  }
  st.common_count = common.size();

  const std::string& tu = s.units.time;
  std::vector<std::string> used;  // the scene's step controls, as `--hold` names them
  auto held = [&](const std::string& name) { return std::find(o.hold.begin(), o.hold.end(), name) != o.hold.end(); };
  for (int k = 0; k < o.levels; ++k) {
    const double f = std::ldexp(1.0, -k);
    StudyCase c;
    c.name = fmt::format("L{}", k);
    std::vector<std::string> text;
    // Each control is multiplied by f (halved level by level), or by `by` where it refines upwards.
    auto control = [&](const std::string& key, double value, const std::string& shown, const std::string& unit,
                       double by = 0.0) {
      const double g = by > 0.0 ? by : f;
      const std::string name = key.substr(std::string("analysis.").size());
      if (k == 0) used.push_back(name);
      if (held(name)) {
        text.push_back(fmt::format("{} {:g}{} (held)", shown, value, unit.empty() ? "" : " " + unit));
        return;
      }
      if (k > 0) c.set.push_back({key, scene::exact_number(value * g), {}});
      text.push_back(fmt::format("{} {:g}{}", shown, value * g, unit.empty() ? "" : " " + unit));
    };
    const std::string& lu = s.units.length;
    control("analysis.dt", a.dt, "dt", tu);
    control("analysis.max_displacement_ratio", a.max_displacement_ratio, "g2", "");
    if (a.has_settle()) {
      control("analysis.settle.dt", a.settle.dt, "settle dt", tu);
      control("analysis.settle.max_displacement_ratio",
              a.settle.max_displacement_ratio > 0.0 ? a.settle.max_displacement_ratio : a.max_displacement_ratio,
              "settle g2", "");
      if (a.settle.collapse_dt > 0.0)
        control("analysis.settle.collapse_dt", a.settle.collapse_dt, "collapse_dt", tu);
    }
    if (a.integrator != core::Integrator::implicit)  // the explicit step's cycle (explicit-step.md);
      // under `automatic` each level decides for itself (its halved explicit_safety may tip it)
      control("analysis.explicit_safety", a.explicit_safety, "explicit_safety", "");
    if (a.stage_cycles > 0)  // density scaling (explicit-step.md): twice the cycles, so that the
      // stages' cycles shorten with their dt and explicit_safety instead of scaling more mass
      control("analysis.stage_cycles", a.stage_cycles, "stage_cycles", "", std::ldexp(1.0, k));
    if (a.static_force_ratio > 0.0)  // static steps by cycles (explicit-step.md): their equilibrium tolerance
      control("analysis.static_force_ratio", a.static_force_ratio, "static_force_ratio", "");
    if (a.step_tolerance > 0.0) control("analysis.step_tolerance", a.step_tolerance, "step_tolerance", lu);
    if (a.creep_tolerance > 0.0) control("analysis.creep_tolerance", a.creep_tolerance, "creep_tolerance", lu);
    if (a.dt_max > 0.0) control("analysis.dt_max", a.dt_max, "dt_max", tu);
    c.set.insert(c.set.end(), common.begin(), common.end());
    r.level_controls.push_back(fmt::format("{}", fmt::join(text, ", ")));
    st.cases.push_back(std::move(c));
  }
  for (const std::string& key : o.hold)
    if (std::find(used.begin(), used.end(), key) == used.end())
      throw std::invalid_argument(fmt::format("--hold {}: not a step control of {}; its step controls are {}",
                                              key, scene_path, fmt::join(used, ", ")));
  if (std::all_of(used.begin(), used.end(), held))
    throw std::invalid_argument(fmt::format("--hold {}: holds every step control of {}: nothing is refined",
                                            fmt::join(o.hold, ","), scene_path));
  // The common overrides go first in each case's `set` (StudyDescription::common_count).
  for (auto& c : st.cases) std::rotate(c.set.begin(), c.set.end() - static_cast<long>(common.size()), c.set.end());

  // The same study as a file: `rheodda study FILE` reruns it.
  std::string y = fmt::format("# Written by `rheodda check {} --refine {}`: the scene at its own step controls (L0)\n"
                              "# and with every step control halved, level by level (docs/guide/choosing-step-controls.md,\n"
                              "# \"Checking a scene's step controls\").\n",
                              scene_path, o.levels);
  std::vector<std::string> times;
  for (double x : st.times) times.push_back(scene::exact_number(x));
  y += fmt::format("title: \"{}\"\nscene: \"{}\"\noutputs: [{}]\ntimes: [{}]\nplot: {}\n", st.title, st.scene,
                   fmt::join(st.outputs, ", "), fmt::join(times, ", "), st.plot);
  if (!common.empty()) {
    y += "set:\n";
    for (const auto& ov : common) y += fmt::format("  {}: {}\n", ov.key, ov.value_yaml);
  }
  y += "cases:\n";
  for (std::size_t k = 0; k < st.cases.size(); ++k) {
    const auto& c = st.cases[k];
    y += fmt::format("  - name: {}   # {}\n", c.name, r.level_controls[k]);
    if (c.set.size() > common.size()) {
      y += "    set:\n";
      for (std::size_t i = common.size(); i < c.set.size(); ++i)
        y += fmt::format("      {}: {}\n", c.set[i].key, c.set[i].value_yaml);
    }
  }
  r.study_text = y;
  return r;
}

RefinementAssessment assess_refinement(const RefinementStudy& refinement, const std::vector<CaseResult>& results,
                                       const RefinementOptions& o) {
  const StudyDescription& st = refinement.study;
  const std::size_t n = st.cases.size();
  RefinementAssessment as;
  for (const auto& res : results)
    if (res.inertia_share) as.largest_inertia_share = std::max(as.largest_inertia_share, *res.inertia_share);

  // A level that failed, or did not reach a time, leaves nothing to compare.
  for (std::size_t k = 0; k < results.size() && k < n; ++k)
    if (results[k].status != "completed") {
      as.verdict = RefinementVerdict::incomplete;
      as.message = fmt::format("Level {} ({}) did not complete ({}{}): the levels cannot be compared.",
                               st.cases[k].name, refinement.level_controls[k], results[k].status,
                               results[k].message.empty() ? "" : ": " + results[k].message);
      return as;
    }

  std::map<std::string, double> largest_of_kind;
  for (std::size_t i = 0; i < st.outputs.size(); ++i)
    for (std::size_t j = 0; j < st.times.size(); ++j) {
      RefinementQuantity q;
      q.output = st.outputs[i];
      q.time = st.times[j];
      for (std::size_t k = 0; k < n; ++k) {
        const auto& v = k < results.size() ? results[k].values : std::vector<std::optional<double>>{};
        const std::size_t at = i * st.times.size() + j;
        q.values.push_back(at < v.size() ? v[at] : std::nullopt);
        if (q.values.back()) q.scale = std::max(q.scale, std::abs(*q.values.back()));
      }
      double& big = largest_of_kind[kind_of(q.output)];
      big = std::max(big, q.scale);
      as.quantities.push_back(std::move(q));
    }

  for (auto& q : as.quantities) {
    for (std::size_t k = 0; k < n; ++k)
      if (!q.values[k]) {
        as.verdict = RefinementVerdict::incomplete;
        as.message = fmt::format("Level {} has no value of {} at t = {:g} (the run stopped before it, or the "
                                 "column is empty there): the levels cannot be compared.",
                                 st.cases[k].name, q.output, q.time);
        return as;
      }
    // Below 1 % of the largest quantity of its kind (e.g. a point that hardly moves
    // beside one that moves metres), a relative difference is noise: shown, not judged.
    q.judged = q.scale > 0.0 && q.scale >= 0.01 * largest_of_kind[kind_of(q.output)];
    const double scale = q.scale > 0.0 ? q.scale : 1.0;
    for (std::size_t k = 1; k < n; ++k) q.differences.push_back(std::abs(*q.values[k] - *q.values[k - 1]) / scale);
    // The reference: the finest level, or, when the last three levels approach a limit
    // monotonically (increments of one sign, shrinking by a ratio rho < 0.9), the
    // Richardson limit v_last + (v_last - v_{last-1}) rho / (1 - rho).
    double finest = *q.values[n - 1];
    if (n >= 3) {
      const double d1 = *q.values[n - 2] - *q.values[n - 3];
      const double d2 = *q.values[n - 1] - *q.values[n - 2];
      const double rho = d1 != 0.0 ? d2 / d1 : 0.0;
      if (rho > 0.0 && rho < 0.9) {
        finest += d2 * rho / (1.0 - rho);
        q.extrapolated = true;
      }
    }
    q.reference = finest;
    q.error = std::abs(*q.values[0] - finest) / scale;
    const double last = q.differences.back();
    const double before = q.differences.size() >= 2 ? q.differences[q.differences.size() - 2] : last;
    // Converged: the last three levels agree within `converged` (two differences: two
    // levels alone can agree by chance where an event such as a slip happens at some
    // levels and not at others), and the last difference did not grow - unless it is
    // below half of `converged`: there the differences are the scatter of a converged
    // answer (contact events that fall in one step or the next), not a trend.
    q.converged = last <= o.converged && before <= o.converged && (last <= before || last <= 0.5 * o.converged);
    for (std::size_t k = n; k-- > 0;) {
      if (std::abs(*q.values[k] - q.reference) / scale > o.tolerance) break;
      q.first_within = static_cast<int>(k);
    }
  }

  const RefinementQuantity* worst_converged = nullptr;
  const RefinementQuantity* worst_error = nullptr;
  for (const auto& q : as.quantities) {
    if (!q.judged) continue;
    if (!q.converged && (!worst_converged || q.differences.back() > worst_converged->differences.back()))
      worst_converged = &q;
    if (!worst_error || q.error > worst_error->error) worst_error = &q;
    as.largest_error = std::max(as.largest_error, q.error);
    as.recommended_level = std::max(as.recommended_level, q.first_within);
  }
  const std::string finest = st.cases.back().name;
  const std::string mechanism =
      as.largest_inertia_share > 0.01
          ? fmt::format(" Parts of the model moved as a mechanism held only by the static steps' inertia "
                        "(inertia_share up to {:.3g}): how far they move is set by the step controls; a settling "
                        "stage (analysis.settle) or a dynamic analysis may be what the scene needs "
                        "(docs/reference/engine.md, \"Mechanisms in static analysis\").",
                        as.largest_inertia_share)
          : std::string();
  if (worst_converged) {
    const auto& q = *worst_converged;
    std::vector<std::string> d;
    for (double x : q.differences) d.push_back(fmt::format("{:.2g} %", 100.0 * x));
    as.verdict = RefinementVerdict::not_converged;
    as.recommended_level = -1;
    as.message = fmt::format(
        "The levels do not converge: {} at t = {:g} changes by {} from level to level (the last three levels must "
        "agree within {:g} % and the differences shrink). The answer depends on the step controls; refine "
        "further (--refine {}) or change the model.{}",
        q.output, q.time, fmt::join(d, ", "), 100.0 * o.converged, n + 2, mechanism);
  } else if (as.largest_error > o.tolerance) {
    const auto& q = *worst_error;
    as.verdict = RefinementVerdict::coarse;
    const int k = as.recommended_level;
    as.message = fmt::format(
        "The scene's step controls are coarser than {:g} %: {} at t = {:g} is {:.4g} at them and {:.4g} {}, "
        "{:.2g} % apart. {}",
        100.0 * o.tolerance, q.output, q.time, *q.values.front(), q.reference,
        q.extrapolated ? "extrapolated from the finest levels" : "at level " + finest, 100.0 * q.error,
        k > 0 && k < static_cast<int>(n) - 1
            ? fmt::format("Level L{} is the first within {:g} % of it: use its controls ({}).", k,
                          100.0 * o.tolerance, refinement.level_controls[static_cast<std::size_t>(k)])
            : fmt::format("Only the finest level is within {:g} %: refine further (--refine {}).",
                          100.0 * o.tolerance, n + 2));
  } else {
    double last = 0.0;
    for (const auto& q : as.quantities)
      if (q.judged)
        for (std::size_t k = q.differences.size() >= 2 ? q.differences.size() - 2 : 0; k < q.differences.size(); ++k)
          last = std::max(last, q.differences[k]);
    as.verdict = RefinementVerdict::fine;
    as.message = fmt::format(
        "The step controls are fine: every output at the scene's own controls (L0) is within {:.2g} % of the "
        "finest level {} or the limit extrapolated from the finest levels (tolerance {:g} %), and the levels "
        "converge (the last three within {:.2g} %).",
        100.0 * as.largest_error, finest, 100.0 * o.tolerance, 100.0 * last);
  }
  return as;
}

std::string refinement_report(const RefinementStudy& refinement, const std::vector<CaseResult>& results,
                              const RefinementAssessment& as, const RefinementOptions& o) {
  const StudyDescription& st = refinement.study;
  std::string out = fmt::format("{}\n", st.title);
  out += "level  steps  wall [s]  inertia_share  step controls\n";
  for (std::size_t k = 0; k < st.cases.size(); ++k) {
    const CaseResult* r = k < results.size() ? &results[k] : nullptr;
    out += fmt::format("{:<5}  {:>5}  {:>8.3f}  {:>13}  {}\n", st.cases[k].name, r ? r->steps : 0,
                       r ? r->wall_seconds : 0.0,
                       r && r->inertia_share ? fmt::format("{:.3g}", *r->inertia_share) : std::string("-"),
                       refinement.level_controls[k]);
  }
  if (!as.quantities.empty()) {
    out += fmt::format("\n{:<40} {:>8}", "output", "t");
    for (const auto& c : st.cases) out += fmt::format(" {:>12}", c.name);
    out += fmt::format("  {:>24}  {:>12}  {:>10}\n", "successive differences", "reference", "L0 error");
    for (const auto& q : as.quantities) {
      out += fmt::format("{:<40} {:>8g}", q.output, q.time);
      for (const auto& v : q.values) out += v ? fmt::format(" {:>12.6g}", *v) : fmt::format(" {:>12}", "-");
      std::vector<std::string> d;
      for (double x : q.differences) d.push_back(fmt::format("{:.2g}%", 100.0 * x));
      out += fmt::format("  {:>24}  {:>11.6g}{}  {:>9.2g}%{}\n", fmt::format("{}", fmt::join(d, " ")), q.reference,
                         q.extrapolated ? "*" : " ", 100.0 * q.error, q.judged ? "" : "  (too small to judge)");
    }
  }
  if (!as.quantities.empty())
    out += "(reference: the finest level, or * the Richardson limit of the last three levels; L0 error: "
           "|L0 - reference| / the largest value over the levels)\n";
  out += fmt::format("\nstep controls: {} (tolerance {:g} %, convergence {:g} %)\n{}\n", verdict_name(as.verdict),
                     100.0 * o.tolerance, 100.0 * o.converged, as.message);
  return out;
}

const char* verdict_name(RefinementVerdict v) {
  switch (v) {
    case RefinementVerdict::fine: return "fine";
    case RefinementVerdict::coarse: return "coarse";
    case RefinementVerdict::not_converged: return "not converged";
    case RefinementVerdict::incomplete: return "incomplete";
  }
  return "";
}

std::string refinement_json(const RefinementStudy& refinement, const std::vector<CaseResult>& results,
                            const RefinementAssessment& as, const RefinementOptions& o) {
  using nlohmann::json;
  const StudyDescription& st = refinement.study;
  auto number = [](std::optional<double> v) { return v ? json(*v) : json(nullptr); };
  json levels = json::array();
  for (std::size_t k = 0; k < st.cases.size(); ++k) {
    const CaseResult* r = k < results.size() ? &results[k] : nullptr;
    levels.push_back({{"name", st.cases[k].name},
                      {"controls", refinement.level_controls[k]},
                      {"status", r ? r->status : "not started"},
                      {"steps", r ? r->steps : 0},
                      {"wall_seconds", r ? r->wall_seconds : 0.0},
                      {"inertia_share", r ? number(r->inertia_share) : json(nullptr)}});
  }
  json quantities = json::array();
  for (const auto& q : as.quantities) {
    json values = json::array();
    for (const auto& v : q.values) values.push_back(number(v));
    quantities.push_back({{"output", q.output},
                          {"time", q.time},
                          {"values", values},
                          {"differences", q.differences},
                          {"reference", q.reference},
                          {"extrapolated", q.extrapolated},
                          {"error", q.error},
                          {"judged", q.judged},
                          {"converged", q.converged},
                          {"first_within", q.first_within}});
  }
  const json j{{"title", st.title},
               {"scene", st.scene},
               {"tolerance", o.tolerance},
               {"converged", o.converged},
               {"levels", levels},
               {"quantities", quantities},
               {"verdict", verdict_name(as.verdict)},
               {"largest_error", as.largest_error},
               {"largest_inertia_share", as.largest_inertia_share},
               {"recommended_level", as.recommended_level},
               {"message", as.message}};
  return j.dump(2) + "\n";
}

}  // namespace rheodda::study
