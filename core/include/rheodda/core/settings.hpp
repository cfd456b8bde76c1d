// The engine's analysis settings (core::Settings, model.hpp) declared once: each by its
// scene word, unit, valid range, typed default and meaning, in the declaration type of
// the law parameters (laws::ParameterSpec, within laws::SettingSpec, which declares the
// contact layer's ContactSettings too), bound to its member of Settings.
//
// Everything that lists these settings reads them from here: the engine's range checks
// (model_checks.cpp), the scene's `analysis:` keys (scene/src/keys.cpp takes each
// key's unit, range, default and meaning from its declaration and reads into the member:
// the scene's Analysis is a Settings; the loader's defaults by analysis type go through
// it), Python's Simulation.set_settings, and the table of docs/reference/engine.md ("Parameters",
// `rheodda keys --markdown settings`, checked by a test).
//
// The default is Settings{}'s (the member's initializer in model.hpp is the one place
// it is written); where a static analysis (dynamic_ratio 0) defaults otherwise, the
// declaration says so (static_default), and the scene applies it.
//
// The settling stage's numbers (Settings::settle, a SettleStage: the scene's
// `analysis.settle` map) are declared the same way (settle_specs), each by its key's word;
// their default 0 is a mark ("none", "the analysis's"), not a value in the range.
//
// The choices (time_integration, solver, contact_solver, integrator, and the stage's
// `type`, SettleStage::dynamic) are declared here too, in laws::ChoiceSpec: each by its scene
// word, its words (the rows of its method table: time_integrations() below, core/methods.hpp's
// registries linear_solvers(), contact_solves(), integrators()), its meaning and its default,
// the word of Settings{}'s value; gravity (a vector) by gravity_spec(). Not declared here:
// threads (a command-line option, not a scene key).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "rheodda/core/model.hpp"
#include "rheodda/laws/choice_spec.hpp"
#include "rheodda/laws/setting_spec.hpp"

namespace rheodda::core {

/// What a setting's value is (number, integer, flag).
using SettingType = laws::SettingType;

/// One setting of core::Settings: `parameter` (name: the member of Settings and the key
/// of the scene's `analysis:` map; unit, meaning, range; default_value: Settings{}'s),
/// its type and member, the default of a static analysis where it differs, a default
/// mark's meaning, and whether it may change between steps (laws/setting_spec.hpp).
using SettingSpec = laws::SettingSpec<Settings>;

/// Every declared setting, in the order of the docs.
const std::vector<SettingSpec>& setting_specs();

/// The declaration of the setting `name`; std::out_of_range if there is none.
const SettingSpec& setting_spec(std::string_view name);

/// One number of the settling stage (SettleStage, model.hpp; the scene's `analysis.settle`).
using SettleSpec = laws::SettingSpec<SettleStage>;

/// Every declared number of the settling stage, in the order of the docs.
const std::vector<SettleSpec>& settle_specs();

/// The declaration of the settling stage's number `name`; std::out_of_range if there is none.
const SettleSpec& settle_spec(std::string_view name);

/// A choice of core::Settings (time_integration, solver, contact_solver, integrator): its
/// scene word, its words, meaning and default (laws/choice_spec.hpp).
using ChoiceSpec = laws::ChoiceSpec<Settings>;

/// Every declared choice of Settings, in the order of the docs.
const std::vector<ChoiceSpec>& choice_specs();

/// The declaration of the choice `name`; std::out_of_range if there is none.
const ChoiceSpec& choice_spec(std::string_view name);

/// A choice of the settling stage (its `type`: SettleStage::dynamic).
using SettleChoiceSpec = laws::ChoiceSpec<SettleStage>;

/// Every declared choice of the settling stage.
const std::vector<SettleChoiceSpec>& settle_choice_specs();

/// The declaration of the settling stage's choice `name`; std::out_of_range if there is none.
const SettleChoiceSpec& settle_choice_spec(std::string_view name);

/// The word of each time integration (the scene's `time_integration`), in the docs' order.
std::span<const laws::ChoiceWord<TimeIntegration>> time_integrations();

/// A vector setting of Settings (gravity): its scene word, unit, meaning and member; its
/// default is Settings{}'s.
struct VectorSettingSpec {
  std::string key;      ///< the member's scene word
  std::string unit;     ///< its dimension
  std::string meaning;  ///< one table cell of the docs
  Vec2 Settings::*field = nullptr;

  const std::string& name() const { return key; }
  Vec2 default_value() const { return Settings{}.*field; }
};

/// The declaration of Settings::gravity.
const VectorSettingSpec& gravity_spec();

/// A number as the docs write it: "0.3", "30", "1e-4", "1e-10".
using laws::setting_number_text;

/// The Markdown table of the declared settings (`| setting | unit | range | default | meaning |`),
/// as docs/reference/engine.md holds it between `<!-- settings:begin/end -->`.
std::string settings_table_markdown();

/// Throws ModelError("settings.NAME", ...) for the first declared setting of `s` that its
/// declaration does not admit (model_checks.cpp; the checks that tie settings together stay there).
void check_setting_ranges(const Settings& s);

}  // namespace rheodda::core
