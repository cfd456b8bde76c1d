// The `units:` and `analysis:` sections of a scene file (docs/reference/scene-format.md).
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <unordered_set>

#include "scene_readers.hpp"

namespace rheodda::scene::detail {

Units read_units(const Ctx& ctx, const YAML::Node& n) {
  MapReader m(ctx, n, "units", keys::units);
  Units u;
  u.length = text(ctx, m.required("length", "label of the length unit, e.g. m"), m.child("length"));
  u.force = text(ctx, m.required("force", "label of the force unit, e.g. N"), m.child("force"));
  u.time = text(ctx, m.required("time", "label of the time unit, e.g. s"), m.child("time"));
  return u;
}

Analysis read_analysis(const Ctx& ctx, const YAML::Node& n) {
  MapReader m(ctx, n, "analysis", keys::analysis);
  Analysis a;
  a.where = m.where();
  auto num = [&](const char* key, double& field, const Range& r) {
    if (YAML::Node v = m.find(key); v.IsDefined()) field = number(ctx, v, m.child(key), r);
  };
  if (YAML::Node v = m.find("type"); v.IsDefined())
    a.type = choice(ctx, v, m.child("type"), {"static", "dynamic"}) == "static"
                 ? AnalysisType::static_analysis
                 : AnalysisType::dynamic_analysis;
  a.duration = number(ctx, m.required("duration", "simulated time [time]"), m.child("duration"),
                      positive("time"));
  YAML::Node dt = m.required("dt", "first and largest time step [time]");
  a.dt = number(ctx, dt, m.child("dt"), positive("time"));
  if (a.dt > a.duration)
    ctx.fail(dt, m.child("dt"), fmt::format("dt = {:g} is longer than duration = {:g}", a.dt, a.duration));
  if (YAML::Node v = m.find("max_cuts"); v.IsDefined())
    a.max_cuts = integer(ctx, v, m.child("max_cuts"), 0, 200);
  num("dt_cut", a.dt_cut, {0.0, true, 1.0, true, ""});
  num("max_displacement_ratio", a.max_displacement_ratio, {0.0, true, 1.0, false, ""});
  if (YAML::Node v = m.find("settle"); v.IsDefined()) {
    // The settling stage (docs/reference/engine.md, "Settling stage").
    MapReader sm(ctx, v, m.child("settle"), keys::settle);
    Analysis::Settle st;
    // A stage that ends at rest (docs/reference/engine.md, "Dynamic stages") needs no
    // length: `until` is then its longest, by default the analysis's duration.
    YAML::Node rest = sm.find("rest_tolerance");
    YAML::Node until = rest.IsDefined() ? sm.find("until") : sm.required("until", "end of the settling stage [time]");
    if (until.IsDefined()) {
      st.until = number(ctx, until, sm.child("until"), positive("time"));
      if (st.until > a.duration || (!rest.IsDefined() && st.until >= a.duration))
        ctx.fail(until, sm.child("until"),
                 fmt::format("the settling stage ends at {:g}, not before the analysis does (duration = {:g})",
                             st.until, a.duration));
    } else {
      st.until = a.duration;
    }
    if (YAML::Node ol = sm.find("open_close_limit"); ol.IsDefined())
      st.open_close_limit = integer(ctx, ol, sm.child("open_close_limit"), 1, 1000);
    if (rest.IsDefined()) {
      st.rest_tolerance = number(ctx, rest, sm.child("rest_tolerance"), {0.0, true, 1.0, true, ""});
      if (!sm.find("type").IsDefined() || sm.find("type").as<std::string>() != "dynamic")
        ctx.fail(rest, sm.child("rest_tolerance"),
                 "a stage ends at rest when its kinetic energy has decayed: give `type: dynamic`");
    }
    YAML::Node sdt = sm.required("dt", "largest step of the settling stage [time]");
    st.dt = number(ctx, sdt, sm.child("dt"), positive("time"));
    if (st.dt > st.until)
      ctx.fail(sdt, sm.child("dt"),
               fmt::format("dt = {:g} is longer than the settling stage (until = {:g})", st.dt, st.until));
    st.max_displacement_ratio = a.max_displacement_ratio;
    if (YAML::Node g = sm.find("max_displacement_ratio"); g.IsDefined())
      st.max_displacement_ratio = number(ctx, g, sm.child("max_displacement_ratio"), {0.0, true, 1.0, false, ""});
    if (YAML::Node t = sm.find("type"); t.IsDefined()) {
      // A dynamic settling stage in a static analysis (docs/reference/engine.md, "Settling stage").
      st.dynamic = choice(ctx, t, sm.child("type"), {"static", "dynamic"}) == "dynamic";
      if (!st.dynamic && a.type == AnalysisType::dynamic_analysis)
        ctx.fail(t, sm.child("type"),
                 "the settling stage of a dynamic analysis is dynamic; a static stage before dynamic steps "
                 "is not modelled");
    }
    if (YAML::Node c = sm.find("collapse_dt"); c.IsDefined()) {
      // Collapse stages (docs/reference/engine.md, "Collapse stages").
      st.collapse_dt = number(ctx, c, sm.child("collapse_dt"), positive("time"));
      if (!st.dynamic || a.type != AnalysisType::static_analysis)
        ctx.fail(c, sm.child("collapse_dt"),
                 "collapse stages are dynamic stages within a static analysis: give `type: dynamic` in the "
                 "settling stage of a static analysis");
      if (st.collapse_dt >= a.dt)
        ctx.fail(c, sm.child("collapse_dt"),
                 fmt::format("collapse_dt = {:g} is not below the analysis's dt = {:g}", st.collapse_dt, a.dt));
    }
    if (YAML::Node r = sm.find("gravity_ramp"); r.IsDefined()) {
      // Gravity ramped up over the stage's start (docs/reference/engine.md, "Gravity ramp").
      st.gravity_ramp = number(ctx, r, sm.child("gravity_ramp"), positive("time"));
      if (st.gravity_ramp > st.until)
        ctx.fail(r, sm.child("gravity_ramp"),
                 fmt::format("the gravity ramp ends at {:g}, after the settling stage (until = {:g}): the creep "
                             "would start under part of gravity",
                             st.gravity_ramp, st.until));
    }
    a.settle = st;
  }
  a.dynamic_ratio = a.type == AnalysisType::dynamic_analysis ? 1.0 : 0.0;
  if (YAML::Node v = m.find("dynamic_ratio"); v.IsDefined()) {
    if (a.type == AnalysisType::static_analysis)
      ctx.fail(v, m.child("dynamic_ratio"),
               "a static analysis carries no velocity; dynamic_ratio needs `type: dynamic`");
    a.dynamic_ratio = number(ctx, v, m.child("dynamic_ratio"), {0.0, false, 1.0, false, ""});
  }
  if (YAML::Node v = m.find("time_integration"); v.IsDefined()) {
    a.time_integration = choice(ctx, v, m.child("time_integration"), {"shi", "trapezoidal"}) == "trapezoidal"
                             ? TimeIntegration::trapezoidal
                             : TimeIntegration::shi;
    // The trapezoidal rule carries velocity and acceleration from step to step;
    // a static analysis (or dynamic_ratio 0) carries neither. The engine refuses
    // it too (settings.time_integration), but only at `run` and at the analysis map.
    if (a.time_integration == TimeIntegration::trapezoidal && a.type == AnalysisType::static_analysis)
      ctx.fail(v, m.child("time_integration"),
               "a static analysis carries no velocity; time_integration: trapezoidal needs `type: dynamic`");
    if (a.time_integration == TimeIntegration::trapezoidal && a.dynamic_ratio == 0.0)
      ctx.fail(v, m.child("time_integration"),
               "dynamic_ratio = 0 carries no velocity; time_integration: trapezoidal needs dynamic_ratio > 0");
  }
  if (YAML::Node v = m.find("scheme"); v.IsDefined()) {
    const std::string name =
        choice(ctx, v, m.child("scheme"), {"automatic", "lagged", "implicit", "exponential-linear"});
    if (name != "automatic") a.scheme = laws::parse_scheme(name);
  }
  num("creep_tolerance", a.creep_tolerance, non_negative("length"));
  if (YAML::Node v = m.find("step_tolerance"); v.IsDefined()) {
    a.step_tolerance = number(ctx, v, m.child("step_tolerance"), non_negative("length"));
    if (a.step_tolerance > 0.0 && a.creep_tolerance > 0.0)
      ctx.fail(v, m.child("step_tolerance"),
               "give step_tolerance (step doubling) or creep_tolerance (creep error estimate), "
               "not both: they are two step controls");
    if (a.step_tolerance > 0.0 && a.settle && a.settle->collapse_dt > 0.0)
      ctx.fail(v, m.child("step_tolerance"),
               "step doubling takes no collapse stage: give step_tolerance or settle.collapse_dt, not both");
  }
  if (YAML::Node v = m.find("step_extrapolation"); v.IsDefined()) {
    a.step_extrapolation = flag(ctx, v, m.child("step_extrapolation"));
    if (!(a.step_tolerance > 0.0))
      ctx.fail(v, m.child("step_extrapolation"),
               "step_extrapolation applies under step_tolerance only (give step_tolerance > 0)");
  }
  if (YAML::Node v = m.find("dt_max"); v.IsDefined()) {
    a.dt_max = number(ctx, v, m.child("dt_max"), non_negative("time"));
    if (a.dt_max > 0.0 && !(a.creep_tolerance > 0.0 || a.step_tolerance > 0.0))
      ctx.fail(v, m.child("dt_max"),
               "dt_max applies under creep_tolerance or step_tolerance only (a fixed-step run "
               "takes dt)");
    if (a.dt_max > 0.0 && a.dt_max < a.dt)
      ctx.fail(v, m.child("dt_max"),
               fmt::format("dt_max = {:g} is shorter than dt = {:g} (the first step)", a.dt_max, a.dt));
  }
  if (YAML::Node v = m.find("dt_growth"); v.IsDefined()) {
    a.dt_growth = number(ctx, v, m.child("dt_growth"), {1.0, false, std::numeric_limits<double>::max(), false, ""});
    // Only a fixed-step run grows its step back by dt_growth after a cut; an
    // adaptive control sizes every step itself, so the value would be ignored.
    if (a.creep_tolerance > 0.0 || a.step_tolerance > 0.0)
      ctx.fail(v, m.child("dt_growth"),
               "dt_growth applies to a fixed-step run only (under creep_tolerance or step_tolerance "
               "the control sizes the steps)");
  }
  if (YAML::Node v = m.find("creep_restart_on_contact_change"); v.IsDefined())
    a.creep_restart_on_contact_change = flag(ctx, v, m.child("creep_restart_on_contact_change"));
  num("penalty", a.penalty, positive("stress"));
  num("shear_normal_ratio", a.shear_normal_ratio, positive(""));
  num("search_factor", a.search_factor, positive(""));
  num("angle_tolerance", a.angle_tolerance, {0.0, true, 45.0, false, "deg"});
  num("penetration_ratio", a.penetration_ratio, {0.0, true, 1.0, false, ""});
  // Default by analysis type (docs/notes/contact-solves.md, "Stick and slip"): in a dynamic
  // analysis Shi's stick rule ratchets a slope that stands down its friction
  // limit, the more the smaller dt; in a static creep analysis the kept force
  // makes the creep run depend on dt. With collapse stages (docs/reference/engine.md,
  // "Collapse stages") the static steps keep the stages' rule: with Shi's rule
  // there, the contacts a stage left sliding stuck in the first static step
  // with their friction dropped, and the slope slid again (measured: a stage
  // every 0.007 d, 23 in 4 d of the seed's slope against 4 with the force kept).
  a.stick_keeps_force =
      a.type == AnalysisType::dynamic_analysis || (a.settle && a.settle->collapse_dt > 0.0);
  if (YAML::Node v = m.find("stick_keeps_force"); v.IsDefined()) {
    a.stick_keeps_force = flag(ctx, v, m.child("stick_keeps_force"));
    a.stick_keeps_force_given = true;
  }
  // The open-close iteration's settings (contact::ContactSettings; docs/reference/contacts.md).
  num("friction_tolerance", a.friction_tolerance, positive(""));
  num("force_resolution", a.force_resolution, {0.0, false, 1.0, true, ""});
  if (YAML::Node v = m.find("max_flips"); v.IsDefined())
    a.max_flips = integer(ctx, v, m.child("max_flips"), 1, 1000);
  if (YAML::Node v = m.find("max_refinements"); v.IsDefined())
    a.max_refinements = integer(ctx, v, m.child("max_refinements"), 0, 1000);
  num("penalty_raise", a.penalty_raise, {1.0, false, std::numeric_limits<double>::max(), false, ""});
  num("penalty_max_factor", a.penalty_max_factor, {1.0, false, std::numeric_limits<double>::max(), false, ""});
  // Static: Shi's 8, so that a step whose contacts do not settle is cut and retaken
  // smaller rather than settled into a sliding state at a large dt; dynamic: 30
  // (brick walls). Measured in docs/notes/contact-solves.md, "The iteration limit in static analysis".
  a.open_close_limit = a.type == AnalysisType::dynamic_analysis ? 30 : 8;
  if (YAML::Node v = m.find("open_close_limit"); v.IsDefined())
    a.open_close_limit = integer(ctx, v, m.child("open_close_limit"), 1, 1000);
  num("fixed_point_stiffness", a.fixed_point_stiffness, positive("force/length"));
  if (YAML::Node v = m.find("solver"); v.IsDefined()) {
    const std::string name = choice(ctx, v, m.child("solver"), {"automatic", "cholmod", "pcg", "amg"});
    for (SolverKind k : {SolverKind::automatic, SolverKind::cholmod, SolverKind::pcg, SolverKind::amg})
      if (solver_name(k) == name) a.solver = k;
  }
  num("solver_tolerance", a.solver_tolerance, {0.0, true, 1.0, true, ""});
  if (YAML::Node v = m.find("solver_max_iterations"); v.IsDefined())
    a.solver_max_iterations = integer(ctx, v, m.child("solver_max_iterations"), 1, 1000000000);
  num("solver_iterate_tolerance", a.solver_iterate_tolerance, {0.0, false, 1.0, true, ""});
  if (YAML::Node v = m.find("contact_solver"); v.IsDefined()) {
    // docs/reference/contacts.md, "Contact solves".
    const std::string name = choice(ctx, v, m.child("contact_solver"), {"open-close", "newton"});
    a.contact_solver = name == "newton" ? ContactSolverKind::newton : ContactSolverKind::open_close;
  }
  num("contact_residual_tolerance", a.contact_residual_tolerance, {0.0, true, 1.0, true, ""});
  a.output_interval = a.duration / 100.0;
  if (YAML::Node v = m.find("output_interval"); v.IsDefined()) {
    a.output_interval = number(ctx, v, m.child("output_interval"), positive("time"));
    if (a.output_interval > a.duration)
      ctx.fail(v, m.child("output_interval"),
               fmt::format("output_interval = {:g} is longer than duration = {:g}", a.output_interval, a.duration));
  }
  num("max_travel_ratio", a.max_travel_ratio, non_negative(""));
  num("max_output_size", a.max_output_size, non_negative("MB"));
  const auto g = numbers(ctx, m.required("gravity", "gravity acceleration [gx, gy] [length/time^2]"),
                         m.child("gravity"), 2, any("length/time^2"));
  a.gravity = {g[0], g[1]};
  return a;
}

}  // namespace rheodda::scene::detail
