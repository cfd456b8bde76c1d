// The declared keys of `analysis:` and `analysis.settle` (keys.hpp), one entry per key.
//
// Each entry: map, key, unit, range (or choices), the field it fills, the default and the
// meaning as docs/reference/scene-format.md shows them (its tables are generated from here
// by scripts/scene-format-tables.sh, through `rheodda keys --markdown MAP`). Checks that tie
// several keys together stay in the loader (scene/src/read_analysis.cpp).
#include "rheodda/scene/keys.hpp"

#include "key_builders.hpp"
#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/core/defaults.hpp"
#include "rheodda/core/settings.hpp"
#include "rheodda/laws/choice_spec.hpp"
#include "rheodda/laws/spec_lookup.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace rheodda::scene {

namespace {

using detail::kInf;

KeyInfo info(const std::string& map, const std::string& name, KeyType type, const std::string& unit, KeyRange range,
             std::string default_text, std::string meaning) {
  return KeyInfo{.map = map, .name = name, .type = type, .unit = unit, .range = range,
                 .default_text = std::move(default_text), .meaning = std::move(meaning)};
}

/// The key `s.name()` of `map` that is a declared setting of a struct S that Analysis is
/// (the engine's core::Settings, core/settings.hpp; the contact layer's ContactSettings,
/// contact/contact_settings_specs.hpp; the scene's Acceptances): its type, unit, range,
/// default and meaning are the declaration's, and it reads into and from the member.
template <class S>
KeySpec setting_key(const laws::SettingSpec<S>& s) {
  static_assert(std::is_base_of_v<S, Analysis>);
  KeySpec k;
  static_cast<KeyInfo&>(k) = detail::declared_info("analysis", s);
  k.get = [&s, type = k.type](const Analysis& a) -> KeyValue { return key_value_of(type, s.value(a)); };
  k.set = [&s](Analysis& a, const KeyValue& v) { s.set(a, key_number(v)); };
  return k;
}

/// The key of the engine's setting `name` (core/settings.hpp).
KeySpec setting_key(const std::string& name) { return setting_key(core::setting_spec(name)); }

/// The key of the contact layer's setting `name` (contact/contact_settings_specs.hpp).
KeySpec contact_setting_key(const std::string& name) { return setting_key(contact::contact_setting_spec(name)); }

/// The key of the run's control `name` (RunControls, run_control_specs).
KeySpec run_control_key(const std::string& name) {
  return setting_key(laws::spec_named(run_control_specs(), name, "scene::RunControls", "setting"));
}

/// The key of the scene's acceptance `name` (Acceptances, acceptance_specs).
KeySpec acceptance_key(const std::string& name) {
  return setting_key(laws::spec_named(acceptance_specs(), name, "scene::Acceptances", "setting"));
}

/// The key `name` of `analysis.settle`: the settling stage's declared number of that name
/// (core::SettleStage, core/settings.hpp: settle_specs), not applicable without `settle:`.
KeySpec settle_key(const std::string& name) {
  const core::SettleSpec& s = core::settle_spec(name);
  KeySpec k;
  static_cast<KeyInfo&>(k) = detail::declared_info("analysis.settle", s);
  k.get = [&s, type = k.type](const Analysis& a) -> KeyValue {
    if (!a.has_settle()) return std::monostate{};
    return key_value_of(type, s.value(a.settle));
  };
  k.set = [&s](Analysis& a, const KeyValue& v) { s.set(a.settle, key_number(v)); };
  return k;
}

std::vector<RunControlSpec> declare_run_controls() {
  using R = RunControls;
  constexpr laws::ParameterRange kAbove0 = laws::kPositiveRange, kFrom0 = laws::kNonNegativeRange;
  std::vector<RunControlSpec> out;
  out.push_back(laws::declare_setting("duration", "time", kAbove0, &R::duration, "simulated time, > 0"));
  out.push_back(laws::declare_setting("output_interval", "time", kAbove0, &R::output_interval,
      "time between output times, ≤ duration: at k × `output_interval` (and at the end) a step "
         "ends, a frame is written and history.csv has a row (docs/reference/outputs.md); shorter "
         "than `dt`, it shortens the steps to it"));
  out.back().default_meaning = "duration / 100, `dt` when longer";  // the loader's (read_analysis.cpp)
  out.push_back(laws::declare_setting("frames", "–", {}, &R::frames,
      "`true`: contacts.csv, bolts.csv and the VTK frames at each output time; `false`: history.csv, "
         "events.csv and summary.json only (what a study's cases write unless the study asks for "
         "`frames`); `true` or `false`"));
  out.push_back(laws::declare_setting("max_travel_ratio", "–", kFrom0, &R::max_travel_ratio,
      "run guard: the run stops (exit 1, outputs kept, summary.json says why) when a block "
         "vertex has moved more than this × the model size (the larger extent of the initial "
         "blocks), as unbounded motion (no friction, a near-zero viscosity, an unsupported block) "
         "would; ≥ 0, 0 = no limit"));
  out.push_back(laws::declare_setting("max_output_size", "MB", kFrom0, &R::max_output_size,
      "run guard: the run stops when history.csv, contacts.csv and the frames written together "
         "exceed this size; ≥ 0, 0 = no limit"));
  return out;
}

std::vector<AcceptanceSpec> declare_acceptances() {
  std::vector<AcceptanceSpec> out;
  out.push_back(laws::declare_setting("accept_unresolved_impacts", "–", {}, &Acceptances::accept_unresolved_impacts,
      "`true`: no warning that the dynamic steps (`dt`, or `settle.dt`) are above a tenth of the "
         "contacts' vibration period, where a joint set's `restitution` does not act as given and "
         "impacts are left to the time integration. For scenes whose answer was shown not to "
         "depend on it (`rheodda check --refine`; docs/reference/contacts.md, \"Contact damping\"); "
         "`true` or `false`"));
  out.push_back(laws::declare_setting("accept_other_gravity", "–", {}, &Acceptances::accept_other_gravity,
      "`true`: no warning that the magnitude of `gravity` is not 9.81 m/s² within 2 % in the "
         "scene's units (a gravity of 0 is never warned about); for a deliberate other gravity; "
         "`true` or `false`"));
  return out;
}

/// The scene's own choices (`type`, `history`): their words and Analysis{}'s values as defaults.
std::vector<laws::ChoiceSpec<Analysis>> declare_scene_choices() {
  static constexpr std::array<laws::ChoiceWord<AnalysisType>, 2> kTypes{
      {{AnalysisType::static_analysis, "static"}, {AnalysisType::dynamic_analysis, "dynamic"}}};
  static constexpr std::array<laws::ChoiceWord<HistoryRows>, 2> kRows{
      {{HistoryRows::outputs, "outputs"}, {HistoryRows::steps, "steps"}}};
  std::vector<laws::ChoiceSpec<Analysis>> out;
  out.push_back(laws::declare_choice("type", kTypes, &Analysis::type,
      "`static` (no velocity carried between steps) or `dynamic`"));
  out.push_back(laws::declare_choice("history", kRows, &Analysis::history,
      "the rows of history.csv: `outputs` (at t = 0, at each output time, and at the steps that end a "
         "dynamic stage, open a collapse stage or bring a contact's damage law to failure) or `steps` "
         "(after every accepted step: for a step-by-step look at the step control; large)"));
  return out;
}

const laws::ChoiceSpec<Analysis>& scene_choice(const std::string& name) {
  static const std::vector<laws::ChoiceSpec<Analysis>> specs = declare_scene_choices();
  return laws::spec_named(specs, name, "scene::Analysis", "choice");
}

/// The key of `analysis:` that is the declared choice `c` of a struct S that Analysis is
/// (core::Settings: core/settings.hpp; ContactSettings: contact/contact_settings_specs.hpp;
/// the scene's own, above): read into and from the member by its words.
template <class S>
KeySpec choice_key(const laws::ChoiceSpec<S>& c) {
  static_assert(std::is_base_of_v<S, Analysis>);  // Analysis itself too
  return detail::custom_key<Analysis>(
      detail::choice_info("analysis", c), [&c](const Analysis& a) -> KeyValue { return c.word_of(a); },
      [&c](Analysis& a, const KeyValue& v) { c.set(a, std::get<std::string>(v)); });
}

/// The key `name` of `analysis.settle` that is the settling stage's declared choice of that
/// name (core/settings.hpp: settle_choice_specs), not applicable without `settle:`.
KeySpec settle_choice_key(const std::string& name) {
  const core::SettleChoiceSpec& c = core::settle_choice_spec(name);
  return detail::custom_key<Analysis>(
      detail::choice_info("analysis.settle", c),
      [&c](const Analysis& a) -> KeyValue {
        if (!a.has_settle()) return std::monostate{};
        return c.word_of(a.settle);
      },
      [&c](Analysis& a, const KeyValue& v) { c.set(a.settle, std::get<std::string>(v)); });
}

/// The key of the engine's declared vector setting `s` (gravity: core/settings.hpp).
KeySpec vector_key(const core::VectorSettingSpec& s) {
  const core::Vec2 d = s.default_value();
  return detail::custom_key<Analysis>(
      info("analysis", s.name(), KeyType::point, s.unit, {}, fmt::format("`[{:g}, {:g}]`", d[0], d[1]), s.meaning),
      [&s](const Analysis& a) -> KeyValue { return Point{(a.*s.field)[0], (a.*s.field)[1]}; },
      [&s](Analysis& a, const KeyValue& v) {
        const Point& p = std::get<Point>(v);
        a.*s.field = core::Vec2(p[0], p[1]);
      });
}

/// A sub-map (`settle`): read by read_analysis.cpp.
KeySpec map_key(const std::string& map, const std::string& name, std::string default_text, std::string meaning) {
  return detail::reader_key<Analysis>(info(map, name, KeyType::map, "–", {}, std::move(default_text), std::move(meaning)));
}

std::vector<KeySpec> declare_analysis_keys() {
  std::vector<KeySpec> keys;
  keys.push_back(choice_key(scene_choice("type")));
  keys.push_back(run_control_key("duration"));
  keys.back().required = "simulated time [time]";
  keys.back().default_text = "required";
  keys.push_back(setting_key("dt"));
  keys.back().required = "first and largest time step [time]";
  keys.back().default_text = "required";
  keys.push_back(setting_key("dt_growth"));
  keys.push_back(setting_key("dt_cut"));
  keys.push_back(setting_key("max_cuts"));
  keys.push_back(setting_key("max_displacement_ratio"));
  keys.push_back(map_key("analysis", "settle",
      "none",
      "a settling stage at the start of the run (docs/reference/engine.md, \"Settling "
         "stage\"); its keys are in the table `analysis.settle` below. For a static model that "
         "settles as a mechanism when gravity comes on: every run, whatever its `dt`, starts its "
         "creep from the same settled state"));
  keys.push_back(setting_key("dynamic_ratio"));
  keys.push_back(choice_key(core::choice_spec("time_integration")));
  keys.push_back(choice_key(contact::contact_choice_spec("scheme")));
  keys.push_back(setting_key("creep_tolerance"));
  keys.push_back(setting_key("step_tolerance"));
  keys.push_back(setting_key("step_extrapolation"));
  keys.push_back(setting_key("dt_max"));
  keys.push_back(setting_key("creep_restart_on_contact_change"));
  keys.push_back(contact_setting_key("penalty"));
  keys.back().default_text = fmt::format("{:g} × the largest `young_modulus`", core::kPenaltyFactor);  // the loader's
  keys.push_back(contact_setting_key("shear_normal_ratio"));
  keys.push_back(contact_setting_key("search_factor"));
  keys.push_back(contact_setting_key("angle_tolerance"));
  keys.push_back(contact_setting_key("penetration_ratio"));
  keys.push_back(contact_setting_key("friction_tolerance"));
  keys.push_back(contact_setting_key("force_resolution"));
  keys.push_back(contact_setting_key("max_flips"));
  keys.push_back(contact_setting_key("max_refinements"));
  keys.push_back(contact_setting_key("penalty_raise"));
  keys.push_back(contact_setting_key("penalty_max_factor"));
  keys.push_back(contact_setting_key("stick_keeps_force"));
  keys.push_back(acceptance_key("accept_unresolved_impacts"));
  keys.push_back(setting_key("open_close_limit"));
  keys.push_back(setting_key("fixed_point_stiffness"));
  keys.push_back(choice_key(core::choice_spec("solver")));
  keys.push_back(setting_key("solver_tolerance"));
  keys.push_back(setting_key("solver_max_iterations"));
  keys.push_back(setting_key("solver_iterate_tolerance"));
  keys.push_back(choice_key(core::choice_spec("contact_solver")));
  keys.push_back(choice_key(core::choice_spec("integrator")));
  keys.push_back(setting_key("explicit_safety"));
  keys.push_back(setting_key("explicit_damping"));
  keys.push_back(setting_key("stage_local_damping"));
  keys.push_back(setting_key("stage_cycles"));
  keys.push_back(setting_key("static_force_ratio"));
  keys.push_back(setting_key("static_max_cycles"));
  keys.push_back(setting_key("static_local_damping"));
  keys.push_back(setting_key("contact_residual_tolerance"));
  keys.push_back(run_control_key("output_interval"));
  keys.push_back(detail::reader_key<Analysis>(
      info("analysis", "output_times", KeyType::list, "time", {}, "none",
           "`[t1, t2, ...]`: output times besides those of `output_interval`, strictly increasing, in "
              "(0, `duration`]; a step ends on each (a study adds its `times` here)"),
      [](const Analysis& a) -> KeyValue {
        if (a.output_times.empty()) return std::monostate{};
        return a.output_times;
      }));
  keys.push_back(choice_key(scene_choice("history")));
  keys.push_back(run_control_key("frames"));
  keys.push_back(run_control_key("max_travel_ratio"));
  keys.push_back(run_control_key("max_output_size"));
  keys.push_back(vector_key(core::gravity_spec()));
  keys.back().default_text = "required";
  keys.back().required = "gravity acceleration [gx, gy] [length/time^2]";
  keys.push_back(acceptance_key("accept_other_gravity"));
  keys.back().echoed = false;  // summary.json's inputs stay as they were

  // analysis.settle: the settling stage (docs/reference/engine.md, "Settling stage").
  keys.push_back(settle_key("until"));
  keys.back().default_text = "required; with `rest_tolerance`: `duration`";  // read_analysis.cpp
  keys.push_back(settle_key("dt"));
  keys.back().default_text = "required";
  keys.back().required = "largest step of the settling stage [time]";
  keys.push_back(settle_key("max_displacement_ratio"));
  keys.push_back(settle_choice_key("type"));
  keys.push_back(settle_key("collapse_dt"));
  keys.push_back(settle_key("gravity_ramp"));
  keys.push_back(settle_key("rest_tolerance"));
  keys.push_back(settle_key("force_ratio"));
  keys.push_back(settle_key("open_close_limit"));
  return keys;
}

}  // namespace

Analysis::Analysis() {
  // A static analysis's defaults where the engine's declarations say they differ
  // (dynamic_ratio, open_close_limit; the loader gives a dynamic one the others).
  for (const core::SettingSpec& s : core::setting_specs())
    if (s.static_default) s.set(*this, *s.static_default);
  gravity = core::Vec2::Zero();  // required: none until the file gives it
}

const std::vector<RunControlSpec>& run_control_specs() {
  static const std::vector<RunControlSpec> specs = declare_run_controls();
  return specs;
}

const std::vector<AcceptanceSpec>& acceptance_specs() {
  static const std::vector<AcceptanceSpec> specs = declare_acceptances();
  return specs;
}

std::vector<KeySpec>& analysis_keys() {
  static std::vector<KeySpec> keys = declare_analysis_keys();
  return keys;
}

}  // namespace rheodda::scene
