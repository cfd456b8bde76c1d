// Texts of declared settings (setting_spec.hpp): numbers, ranges and values as the docs write them.
#include "rheodda/laws/setting_spec.hpp"

#include <fmt/format.h>

#include <limits>

namespace rheodda::laws {

namespace {

/// A bound of a range: "∞" for none, an integer's without decimals.
std::string bound_text(double v, SettingType t) {
  if (v == std::numeric_limits<double>::max()) return "∞";
  if (v == std::numeric_limits<double>::lowest()) return "−∞";
  return t == SettingType::integer && v < 1e6 ? fmt::format("{:.0f}", v) : setting_number_text(v);
}

}  // namespace

std::string setting_number_text(double v) {
  if (!std::isfinite(v) || v == 0.0 || (std::abs(v) >= 0.01 && std::abs(v) < 1e6)) return fmt::format("{:g}", v);
  // 1.000000e-04 -> 1e-4, 1.000000e+09 -> 1e9: the mantissa without trailing zeros, the exponent without padding.
  const std::string e = fmt::format("{:e}", v);
  const auto at = e.find('e');
  std::string mantissa = e.substr(0, at);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  return mantissa + "e" + std::to_string(std::stoi(e.substr(at + 1)));
}

std::string setting_range_text(const ParameterSpec& p, SettingType type) {
  if (type == SettingType::flag) return "true or false";
  return fmt::format("{}{}, {}{}", p.min_exclusive || p.min == std::numeric_limits<double>::lowest() ? "(" : "[",
                     bound_text(p.min, type), bound_text(p.max, type),
                     p.max_exclusive || p.max == std::numeric_limits<double>::max() ? ")" : "]");
}

std::string setting_value_text(double v, SettingType type) {
  if (type == SettingType::flag) return v != 0.0 ? "true" : "false";
  return type == SettingType::integer ? fmt::format("{:.0f}", v) : setting_number_text(v);
}

}  // namespace rheodda::laws
