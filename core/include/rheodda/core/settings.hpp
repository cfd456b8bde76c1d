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
// Not declared here: the choices (time_integration, solver, contact_solver, integrator,
// and the stage's `type`, SettleStage::dynamic: their words are core/methods.hpp's
// registries or the scene's), gravity (a vector) and threads (a command-line option, not a
// scene key).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "rheodda/core/model.hpp"
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

/// A number as the docs write it: "0.3", "30", "1e-4", "1e-10".
using laws::setting_number_text;

/// The Markdown table of the declared settings (`| setting | unit | range | default | meaning |`),
/// as docs/reference/engine.md holds it between `<!-- settings:begin/end -->`.
std::string settings_table_markdown();

/// Throws ModelError("settings.NAME", ...) for the first declared setting of `s` that its
/// declaration does not admit (model_checks.cpp; the checks that tie settings together stay there).
void check_setting_ranges(const Settings& s);

}  // namespace rheodda::core
