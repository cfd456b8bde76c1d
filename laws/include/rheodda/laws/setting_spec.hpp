// A setting of a struct of settings declared once: its name (the scene word), unit, range,
// typed default and meaning in the declaration type of the law parameters
// (laws::ParameterSpec), bound to its member. The engine's settings (core::Settings,
// core/settings.hpp) and the contact layer's (contact::ContactSettings,
// contact/contact_settings_specs.hpp) are declared with it.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "rheodda/laws/parameters.hpp"

namespace rheodda::laws {

/// What a setting's value is.
enum class SettingType {
  number,   ///< a finite double within the range
  integer,  ///< an int within the range
  flag,     ///< a bool (true or false; the range is [0, 1])
};

/// A number as the docs write it: "0.3", "30", "1e-4", "1e-10".
std::string setting_number_text(double v);

/// The valid range of `p` as the docs write it: "(0, 1]", "[1, ∞)", "true or false".
std::string setting_range_text(const ParameterSpec& p, SettingType type);

/// A value of a setting of type `type` as the docs write it: "1.5", "30", "true".
std::string setting_value_text(double v, SettingType type);

/// One setting of the struct `S`.
template <class S>
struct SettingSpec {
  /// name: the member of S and the scene's key; unit ("–" for none), meaning (one table
  /// cell), range; default_value: S{}'s.
  ParameterSpec parameter;
  SettingType type = SettingType::number;
  std::variant<double S::*, int S::*, bool S::*> field;
  /// The default of a static analysis (dynamic_ratio 0) where it differs from S{}'s,
  /// which is then the default of a dynamic one.
  std::optional<double> static_default{};
  /// The default value is a mark outside the range that the host replaces by what this
  /// says ("100 × the largest `young_modulus`"): not a value a user gives.
  std::string default_meaning{};
  /// The default where the host decides it by a rule of its own (the analysis's type, its
  /// stages), S{}'s being the engine's when no host sets it: the rule as the docs state it.
  std::string host_default{};
  /// May change between steps (Python's Simulation.set_settings).
  bool between_steps = false;

  const std::string& name() const { return parameter.name; }
  /// The value in `s`, as a double (a flag as 0 or 1).
  double value(const S& s) const {
    return std::visit([&s](auto m) { return static_cast<double>(s.*m); }, field);
  }
  /// Sets the member in `s` to `v` (an integer or a flag given as a double).
  void set(S& s, double v) const {
    std::visit(
        [&s, v](auto m) {
          using T = std::remove_reference_t<decltype(s.*m)>;
          if constexpr (std::is_same_v<T, bool>)
            s.*m = v != 0.0;
          else
            s.*m = static_cast<T>(v);
        },
        field);
  }
  /// The default of a dynamic (`dynamic` true) or static analysis.
  double default_for(bool dynamic) const {
    return !dynamic && static_default ? *static_default : *parameter.default_value;
  }
  /// `v` is valid: within the range, or the default mark of a setting with default_meaning.
  bool admits(double v) const {
    if (!default_meaning.empty() && v == *parameter.default_value) return true;  // infinite too ("never yields")
    if (!std::isfinite(v)) return false;
    if (type != SettingType::number && v != std::floor(v)) return false;  // an integer, a flag 0 or 1
    return parameter.admits(v);
  }
  /// The valid range as text: "(0, 1]", "[1, ∞)", "true or false".
  std::string range_text() const { return setting_range_text(parameter, type); }
  /// The default as the docs state it: "1.5", "1e-10", "1 (dynamic), 0 (static)",
  /// "100 × the largest `young_modulus`", or the host's rule.
  std::string default_text() const {
    if (!default_meaning.empty()) return default_meaning;
    if (!host_default.empty()) return host_default;
    if (static_default)
      return setting_value_text(default_for(true), type) + " (dynamic), " + setting_value_text(default_for(false), type) +
             " (static)";
    return setting_value_text(*parameter.default_value, type);
  }
};

/// The declaration of the member `field` of S, named `name` (the scene's word), its
/// default S{}'s.
template <class S, class T>
SettingSpec<S> declare_setting(const char* name, const char* unit, ParameterRange r, T S::*field,
                               const char* meaning) {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, int> || std::is_same_v<T, bool>);
  SettingSpec<S> s;
  s.type = std::is_same_v<T, double> ? SettingType::number
           : std::is_same_v<T, int>  ? SettingType::integer
                                     : SettingType::flag;
  if (s.type == SettingType::flag) r = {0.0, false, 1.0, false};
  s.parameter = declare_parameter(name, unit, r, meaning);
  s.parameter.default_value = static_cast<double>(S{}.*field);
  s.field = field;
  return s;
}

/// The Markdown table of declared settings (`| setting | unit | range | default | meaning |`).
template <class S>
std::string settings_table_markdown(const std::vector<SettingSpec<S>>& specs) {
  std::string out = "| setting | unit | range | default | meaning |\n|---|---|---|---|---|\n";
  for (const SettingSpec<S>& s : specs)
    out += "| `" + s.name() + "` | " + s.parameter.unit + " | " + s.range_text() + " | " + s.default_text() + " | " +
           s.parameter.meaning + " |\n";
  return out;
}

/// The message of a value `v` a setting's declaration does not admit: "2 is not in (0, 1) (time)".
template <class S>
std::string setting_refusal(const SettingSpec<S>& s, double v) {
  return setting_number_text(v) + " is not in " + s.range_text() +
         (s.parameter.unit == "–" ? "" : " (" + s.parameter.unit + ")");
}

}  // namespace rheodda::laws
