// The engine's analysis settings (core::Settings, model.hpp) declared once: each by its
// scene word, unit, valid range, typed default and meaning, in the declaration type of
// the law parameters (laws::ParameterSpec), bound to its member of Settings.
//
// Everything that lists these settings reads them from here: the engine's range checks
// (model_checks.cpp), the scene's `analysis:` keys (scene/src/keys.cpp takes each
// key's unit, range, default and meaning from its declaration; the loader's defaults
// by analysis type and the copy into the Model go through it), Python's
// Simulation.set_settings, and the table of docs/reference/engine.md ("Parameters",
// `rheodda keys --markdown settings`, checked by a test).
//
// The default is Settings{}'s (the member's initializer in model.hpp is the one place
// it is written); where a static analysis (dynamic_ratio 0) defaults otherwise, the
// declaration says so (static_default), and the scene applies it.
//
// Not declared here yet: the settling stage's settle_* (the scene's `analysis.settle`
// sub-map, where 0 means no stage), the choices (time_integration, solver,
// contact_solver, integrator: their words are core/methods.hpp's registries), gravity
// (a vector) and threads (a command-line option, not a scene key).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "rheodda/core/model.hpp"
#include "rheodda/core/setting_defaults.hpp"
#include "rheodda/laws/parameters.hpp"

namespace rheodda::core {

/// What a setting's value is.
enum class SettingType {
  number,   ///< a finite double within the range
  integer,  ///< an int within the range
  flag,     ///< a bool (true or false; the range is [0, 1])
};

/// One setting of core::Settings.
struct SettingSpec {
  /// name: the member of Settings and the key of the scene's `analysis:` map; unit ("–"
  /// for none), meaning (one table cell), range; default_value: Settings{}'s.
  laws::ParameterSpec parameter;
  SettingType type = SettingType::number;
  std::variant<double Settings::*, int Settings::*, bool Settings::*> field;
  /// The default of a static analysis (dynamic_ratio 0) where it differs from Settings{}'s,
  /// which is then the default of a dynamic one.
  std::optional<double> static_default{};
  /// The default value is a mark outside the range that the engine replaces by what this
  /// says ("100 × the largest `young_modulus`"): not a value a user gives.
  std::string default_meaning{};
  /// May change between steps (Python's Simulation.set_settings).
  bool between_steps = false;

  const std::string& name() const { return parameter.name; }
  /// The value in `s`, as a double (a flag as 0 or 1).
  double value(const Settings& s) const;
  /// Sets the member in `s` to `v` (an integer or a flag given as a double).
  void set(Settings& s, double v) const;
  /// The default of a dynamic (`dynamic` true) or static analysis.
  double default_for(bool dynamic) const;
  /// `v` is valid: within the range, or the default mark of a setting with default_meaning.
  bool admits(double v) const;
  /// The valid range as text: "(0, 1]", "[1, ∞)", "true or false".
  std::string range_text() const;
  /// The default as the docs state it: "1.5", "1e-10", "1 (dynamic), 0 (static)",
  /// "100 × the largest `young_modulus`".
  std::string default_text() const;
};

/// Every declared setting, in the order of the docs.
const std::vector<SettingSpec>& setting_specs();

/// The declaration of the setting `name`; std::out_of_range if there is none.
const SettingSpec& setting_spec(std::string_view name);

/// A number as the docs write it: "0.3", "30", "1e-4", "1e-10".
std::string setting_number_text(double v);

/// The Markdown table of the declared settings (`| setting | unit | range | default | meaning |`),
/// as docs/reference/engine.md holds it between `<!-- settings:begin/end -->`.
std::string settings_table_markdown();

/// Throws ModelError("settings.NAME", ...) for the first declared setting of `s` that its
/// declaration does not admit (model_checks.cpp; the checks that tie settings together stay there).
void check_setting_ranges(const Settings& s);

}  // namespace rheodda::core
