// The `units:` and `analysis:` sections of a scene file (docs/reference/scene-format.md).
//
// The keys of `analysis:` and `analysis.settle` are declared once, in keys.cpp: each
// is read and checked alone from its declaration (type, range, unit); what follows
// here are the defaults that depend on other keys and the checks that tie keys
// together, after every key has been read.
#include <fmt/format.h>
#include <algorithm>
#include <yaml-cpp/yaml.h>

#include "read_keys.hpp"
#include "rheodda/core/settings.hpp"
#include "scene_readers.hpp"

namespace rheodda::scene::detail {

Units read_units(const Ctx& ctx, const YAML::Node& n) {
  const MapReader m = declared_reader(ctx, n, "units", units_keys(), "units");
  Units u;
  read_declared(ctx, m, units_keys(), u);  // keys_top.cpp
  return u;
}

namespace {

/// `settle:` (docs/reference/engine.md, "Settling stage"), after the analysis's own keys.
void read_settle(const Ctx& ctx, const MapReader& m, Analysis& a) {
  const MapReader sm =
      declared_reader(ctx, m.find(key::analysis::settle), m.child(key::analysis::settle), analysis_keys(),
                      "analysis.settle");
  read_declared(ctx, sm, analysis_keys(), a);
  core::SettleStage& st = a.settle;
  if (!sm.has(key::settle::max_displacement_ratio)) st.max_displacement_ratio = a.max_displacement_ratio;
  // A stage that ends at rest (docs/reference/engine.md, "Dynamic stages") needs no length:
  // `until` is then its longest, by default the analysis's duration.
  const YAML::Node rest = sm.find(key::settle::rest_tolerance);
  if (const YAML::Node until = sm.find(key::settle::until); until.IsDefined()) {
    if (st.until > a.duration || (!rest.IsDefined() && st.until >= a.duration))
      ctx.fail(until, sm.child(key::settle::until),
               fmt::format("the settling stage ends at {:g}, not before the analysis does (duration = {:g})",
                           st.until, a.duration));
  } else if (rest.IsDefined()) {
    st.until = a.duration;
  } else {
    sm.required(key::settle::until, "end of the settling stage [time]");
  }
  if (const YAML::Node f = sm.find(key::settle::force_ratio); f.IsDefined() && !rest.IsDefined())
    ctx.fail(f, sm.child(key::settle::force_ratio),
             "the unbalanced-force test decides when a stage that ends at rest is at rest: give "
             "`rest_tolerance` too");
  if (rest.IsDefined() && !st.dynamic)
    ctx.fail(rest, sm.child(key::settle::rest_tolerance),
             "a stage ends at rest when its kinetic energy has decayed: give `type: dynamic`");
  if (st.dt > st.until)
    ctx.fail(sm.find(key::settle::dt), sm.child(key::settle::dt),
             fmt::format("dt = {:g} is longer than the settling stage (until = {:g})", st.dt, st.until));
  if (const YAML::Node t = sm.find(key::settle::type); t.IsDefined() && !st.dynamic && a.type == AnalysisType::dynamic_analysis)
    ctx.fail(t, sm.child(key::settle::type),
             "the settling stage of a dynamic analysis is dynamic; a static stage before dynamic steps "
             "is not modelled");
  if (const YAML::Node c = sm.find(key::settle::collapse_dt); c.IsDefined()) {
    // Collapse stages (docs/reference/engine.md, "Collapse stages").
    if (!st.dynamic || a.type != AnalysisType::static_analysis)
      ctx.fail(c, sm.child(key::settle::collapse_dt),
               "collapse stages are dynamic stages within a static analysis: give `type: dynamic` in the "
               "settling stage of a static analysis");
    if (st.collapse_dt >= a.dt)
      ctx.fail(c, sm.child(key::settle::collapse_dt),
               fmt::format("collapse_dt = {:g} is not below the analysis's dt = {:g}", st.collapse_dt, a.dt));
  }
  if (const YAML::Node r = sm.find(key::settle::gravity_ramp); r.IsDefined() && st.gravity_ramp > st.until)
    // Gravity ramped up over the stage's start (docs/reference/engine.md, "Gravity ramp").
    ctx.fail(r, sm.child(key::settle::gravity_ramp),
             fmt::format("the gravity ramp ends at {:g}, after the settling stage (until = {:g}): the creep "
                         "would start under part of gravity",
                         st.gravity_ramp, st.until));
}

}  // namespace

Analysis read_analysis(const Ctx& ctx, const YAML::Node& n) {
  const MapReader m = declared_reader(ctx, n, "analysis", analysis_keys(), "analysis");
  Analysis a;
  a.where = m.where();
  read_declared(ctx, m, analysis_keys(), a);
  const bool dynamic = a.type == AnalysisType::dynamic_analysis;
  if (a.dt > a.duration)
    ctx.fail(m.find(key::analysis::dt), m.child(key::analysis::dt),
             fmt::format("dt = {:g} is longer than duration = {:g}", a.dt, a.duration));
  if (m.has(key::analysis::settle)) read_settle(ctx, m, a);
  // The engine's settings whose default depends on the analysis type (core/settings.hpp:
  // dynamic_ratio, open_close_limit), where the scene does not give them.
  for (const core::SettingSpec& s : core::setting_specs())
    if (s.static_default && !m.has_named(s.name())) {
      const KeySpec& k = analysis_key(s.name());
      k.set(a, key_value_of(k.type, s.default_for(dynamic)));
    }
  if (const YAML::Node v = m.find(key::analysis::dynamic_ratio); v.IsDefined() && !dynamic)
    ctx.fail(v, m.child(key::analysis::dynamic_ratio),
             "a static analysis carries no velocity; dynamic_ratio needs `type: dynamic`");
  if (const YAML::Node v = m.find(key::analysis::time_integration);
      v.IsDefined() && a.time_integration == TimeIntegration::trapezoidal) {
    // The trapezoidal rule carries velocity and acceleration from step to step;
    // a static analysis (or dynamic_ratio 0) carries neither. The engine refuses
    // it too (settings.time_integration), but only at `run` and at the analysis map.
    if (!dynamic)
      ctx.fail(v, m.child(key::analysis::time_integration),
               "a static analysis carries no velocity; time_integration: trapezoidal needs `type: dynamic`");
    if (a.dynamic_ratio == 0.0)
      ctx.fail(v, m.child(key::analysis::time_integration),
               "dynamic_ratio = 0 carries no velocity; time_integration: trapezoidal needs dynamic_ratio > 0");
  }
  if (const YAML::Node v = m.find(key::analysis::integrator);
      v.IsDefined() && a.integrator == core::Integrator::explicit_step) {
    // The explicit step takes dynamic steps (docs/reference/explicit-step.md); the engine
    // refuses the same (settings.integrator), but only at `run`.
    if (!a.has_dynamic_steps() && a.static_force_ratio == 0.0)
      ctx.fail(v, m.child(key::analysis::integrator),
               "the explicit step integrates dynamic steps, and static ones with static_force_ratio; a static "
               "analysis without a dynamic settling stage (settle.dynamic: true) or static_force_ratio has none");
    if (a.step_tolerance > 0.0)
      ctx.fail(v, m.child(key::analysis::integrator),
               "step doubling (step_tolerance) estimates the implicit step's error: give the implicit integrator "
               "or no step_tolerance");
    if (a.time_integration == TimeIntegration::trapezoidal)
      ctx.fail(v, m.child(key::analysis::integrator),
               "time_integration chooses the implicit step's scheme; the explicit step is central difference");
  }
  // Static steps by cycles (docs/reference/explicit-step.md, "Static steps by cycles").
  if (const YAML::Node w = m.find(key::analysis::static_force_ratio); w.IsDefined() && a.static_force_ratio > 0.0) {
    if (a.integrator != core::Integrator::explicit_step)
      ctx.fail(w, m.child(key::analysis::static_force_ratio),
               "static steps by cycles are the explicit step's: give integrator: explicit");
    if (a.type == AnalysisType::dynamic_analysis)
      ctx.fail(w, m.child(key::analysis::static_force_ratio), "a dynamic analysis has no static steps");
  }
  for (const KeyName k : {key::analysis::static_max_cycles, key::analysis::static_local_damping})
    if (const YAML::Node w = m.find(k); w.IsDefined() && !(a.static_force_ratio > 0.0))
      ctx.fail(w, m.child(k),
               fmt::format("{} applies to the static steps by cycles; give static_force_ratio too", k.word()));
  if (a.integrator != core::Integrator::implicit) {  // explicit, or automatic (integrator_choice.cpp)
    if (const YAML::Node w = m.find(key::analysis::stage_local_damping);
        w.IsDefined() && a.stage_local_damping > 0.0 && a.type == AnalysisType::dynamic_analysis)
      ctx.fail(w, m.child(key::analysis::stage_local_damping),
               "local damping acts in the dynamic stages of a static analysis, where only the state at rest "
               "matters; a dynamic analysis never takes it");
    if (const YAML::Node w = m.find(key::analysis::stage_cycles);
        w.IsDefined() && a.stage_cycles > 0 && a.type == AnalysisType::dynamic_analysis)
      ctx.fail(w, m.child(key::analysis::stage_cycles),
               "density scaling acts in the dynamic stages of a static analysis, where only the state at rest "
               "matters; a dynamic analysis never takes it (its masses are its physics)");
  } else {
    for (const KeyName k : {key::analysis::explicit_safety, key::analysis::explicit_damping,
                            key::analysis::stage_local_damping, key::analysis::stage_cycles})
      if (const YAML::Node w = m.find(k); w.IsDefined())
        ctx.fail(w, m.child(k),
                 fmt::format("{} applies to the explicit step; give integrator: explicit or automatic", k.word()));
    if (const YAML::Node sm = m.find(key::analysis::settle); sm.IsDefined() && sm.IsMap())
      if (const YAML::Node f = sm[std::string(key::settle::force_ratio.word())]; f.IsDefined())
        ctx.fail(f, fmt::format("{}.{}", m.child(key::analysis::settle), key::settle::force_ratio.word()),
                 "force_ratio applies to the explicit step (only its cycles find the unbalanced force); give "
                 "integrator: explicit or automatic");
  }
  const bool adaptive = a.creep_tolerance > 0.0 || a.step_tolerance > 0.0;
  if (const YAML::Node v = m.find(key::analysis::step_tolerance); v.IsDefined() && a.step_tolerance > 0.0) {
    if (a.creep_tolerance > 0.0)
      ctx.fail(v, m.child(key::analysis::step_tolerance),
               "give step_tolerance (step doubling) or creep_tolerance (creep error estimate), "
               "not both: they are two step controls");
    if (a.has_settle() && a.settle.collapse_dt > 0.0)
      ctx.fail(v, m.child(key::analysis::step_tolerance),
               "step doubling takes no collapse stage: give step_tolerance or settle.collapse_dt, not both");
  }
  if (const YAML::Node v = m.find(key::analysis::step_extrapolation); v.IsDefined() && !(a.step_tolerance > 0.0))
    ctx.fail(v, m.child(key::analysis::step_extrapolation),
             "step_extrapolation applies under step_tolerance only (give step_tolerance > 0)");
  if (const YAML::Node v = m.find(key::analysis::dt_max); v.IsDefined() && a.dt_max > 0.0) {
    if (!adaptive)
      ctx.fail(v, m.child(key::analysis::dt_max),
               "dt_max applies under creep_tolerance or step_tolerance only (a fixed-step run takes dt)");
    if (a.dt_max < a.dt)
      ctx.fail(v, m.child(key::analysis::dt_max),
               fmt::format("dt_max = {:g} is shorter than dt = {:g} (the first step)", a.dt_max, a.dt));
  }
  // Only a fixed-step run grows its step back by dt_growth after a cut; an
  // adaptive control sizes every step itself, so the value would be ignored.
  if (const YAML::Node v = m.find(key::analysis::dt_growth); v.IsDefined() && adaptive)
    ctx.fail(v, m.child(key::analysis::dt_growth),
             "dt_growth applies to a fixed-step run only (under creep_tolerance or step_tolerance "
             "the control sizes the steps)");
  // Default by analysis type (docs/notes/contact-solves.md, "Stick and slip"): in a dynamic
  // analysis Shi's stick rule ratchets a slope that stands down its friction
  // limit, the more the smaller dt; in a static creep analysis the kept force
  // makes the creep run depend on dt. With collapse stages (docs/reference/engine.md,
  // "Collapse stages") the static steps keep the stages' rule: with Shi's rule
  // there, the contacts a stage left sliding stuck in the first static step
  // with their friction dropped, and the slope slid again (measured: a stage
  // every 0.007 d, 23 in 4 d of the seed's slope against 4 with the force kept).
  a.stick_keeps_force_given = m.has(key::analysis::stick_keeps_force);
  if (!a.stick_keeps_force_given) a.stick_keeps_force = dynamic || (a.has_settle() && a.settle.collapse_dt > 0.0);
  if (const YAML::Node v = m.find(key::analysis::output_interval); !v.IsDefined()) {
    // A step ends on each output time (docs/reference/outputs.md, "Output times"): the
    // default asks for no step shorter than dt.
    a.output_interval = std::max(a.duration / 100.0, a.dt);
  } else if (a.output_interval > a.duration) {
    ctx.fail(v, m.child(key::analysis::output_interval),
             fmt::format("output_interval = {:g} is longer than duration = {:g}", a.output_interval, a.duration));
  }
  if (const YAML::Node v = m.find(key::analysis::output_times); v.IsDefined()) {
    // Output times besides those of output_interval (docs/reference/outputs.md): a step ends on each.
    if (!v.IsSequence())
      ctx.fail(v, m.child(key::analysis::output_times),
               fmt::format("expected a list of times [{}], got {}", "time", type_word(v)));
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string item = fmt::format("{}[{}]", m.child(key::analysis::output_times), i);
      const double t = number(ctx, v[i], item, {0.0, true, a.duration, false, "time"});
      if (!a.output_times.empty() && t <= a.output_times.back())
        ctx.fail(v[i], item, fmt::format("{:g} does not follow {:g}: output times are strictly increasing", t,
                                        a.output_times.back()));
      a.output_times.push_back(t);
    }
  }
  return a;
}

}  // namespace rheodda::scene::detail
