// The defaults of the engine's declared settings (settings.hpp) by name, without
// the declarations' types: what a mirror of the settings (the scene's Analysis)
// initializes its fields with, so that each default is written once, in core::Settings.
#pragma once

#include <string_view>
#include <type_traits>

namespace rheodda::core {

/// The default of the declared setting `name` (settings.hpp) in a dynamic (`dynamic`
/// true) or static analysis, a flag as 0 or 1; std::out_of_range for an undeclared name.
double setting_default(std::string_view name, bool dynamic);

/// setting_default as the member's type (double, int or bool).
template <class T>
T setting_default_as(std::string_view name, bool dynamic) {
  const double v = setting_default(name, dynamic);
  if constexpr (std::is_same_v<T, bool>)
    return v != 0.0;
  else
    return static_cast<T>(v);
}

}  // namespace rheodda::core
