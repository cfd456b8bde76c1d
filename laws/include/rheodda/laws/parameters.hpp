// Self-describing law parameters: each law declares its parameters once
// (name, unit, meaning, valid range, default) and every input path - the
// command line, YAML scenes, fits - is validated against that schema.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rheodda::laws {

/// Error in user-given law input: names the offending key.
class LawError : public std::runtime_error {
 public:
  LawError(std::string key, const std::string& message)
      : std::runtime_error(message), key_(std::move(key)) {}
  /// The parameter (or law) name the error is about; empty if none.
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

/// One parameter of a law, or one setting of the engine (core/settings.hpp declares
/// core::Settings with it): the one declaration type of a number the user gives.
struct ParameterSpec {
  std::string name;     ///< key in YAML, on the command line and in fits, e.g. "eta1"
  std::string unit;     ///< dimension per unit joint area, e.g. "stress/length"
  std::string meaning;  ///< one line for `rheodda law list`
  double min = 0.0;     ///< lower bound of the valid range
  bool min_exclusive = true;  ///< true: value > min; false: value >= min
  double max = std::numeric_limits<double>::max();  ///< upper bound
  std::optional<double> default_value{};  ///< used when the key is absent
  bool max_exclusive = false;  ///< true: value < max; false: value <= max
  /// "(0, 1.8e308]"-style text of the valid range.
  std::string range_text() const;
  /// `v` lies in the valid range.
  bool admits(double v) const {
    return (min_exclusive ? v > min : v >= min) && (max_exclusive ? v < max : v <= max);
  }
  /// What the parameter's value decides in the law's creep, by its dimension, for a
  /// value the data do not determine: a threshold [stress] decides whether a contact
  /// near it flows at all; a viscosity, the rate of its element; a stiffness, its size.
  std::string what_its_value_decides() const;
};

/// A valid range as a ParameterSpec states it, written as one value in declarations
/// (core/settings.cpp, contact/joint_set_specs.cpp): [min or (min, max] or max).
struct ParameterRange {
  double min = 0.0;
  bool min_exclusive = false;
  double max = std::numeric_limits<double>::max();
  bool max_exclusive = false;
};
inline constexpr ParameterRange kPositiveRange{0.0, true, std::numeric_limits<double>::max(), false};     ///< > 0
inline constexpr ParameterRange kNonNegativeRange{0.0, false, std::numeric_limits<double>::max(), false};  ///< >= 0

/// The declaration of `name` [`unit`] valid in `range`, meaning `meaning`; no default.
ParameterSpec declare_parameter(std::string name, std::string unit, const ParameterRange& range, std::string meaning);

/// Parameter values by name.
using ParameterValues = std::map<std::string, double, std::less<>>;

/// Checks `given` against `specs`: rejects unknown keys (suggesting the nearest
/// valid name), missing keys without default, NaN/inf and out-of-range values.
/// Returns the complete set with defaults filled in. `law` is used in messages.
ParameterValues validate_parameters(std::string_view law, const std::vector<ParameterSpec>& specs,
                                    const ParameterValues& given);

/// Nearest candidate to `word` by edit distance, for "did you mean" hints; empty if none is close.
std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace rheodda::laws
