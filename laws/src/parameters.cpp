#include "rheodda/laws/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace rheodda::laws {

ParameterSpec declare_parameter(std::string name, std::string unit, const ParameterRange& range, std::string meaning) {
  ParameterSpec p;
  p.name = std::move(name);
  p.unit = std::move(unit);
  p.meaning = std::move(meaning);
  p.min = range.min;
  p.min_exclusive = range.min_exclusive;
  p.max = range.max;
  p.max_exclusive = range.max_exclusive;
  return p;
}

std::string ParameterSpec::what_its_value_decides() const {
  // The laws' elements (laws.md): a Bingham threshold [stress], dashpots [stress*time/length],
  // springs [stress/length].
  if (unit == "stress")
    return fmt::format("{} is a threshold: its element flows only where the shear stress exceeds it, so whether a "
                       "contact near it creeps at all is decided by the value of {}, not by the data",
                       name, name);
  if (unit.find("time") != std::string::npos)
    return fmt::format("{} is a viscosity: the rate of its element, and so the creep computed, scales with 1/{}", name,
                       name);
  return fmt::format("{} is a stiffness: the size of its element's creep scales with 1/{}", name, name);
}

std::string ParameterSpec::range_text() const {
  auto num = [](double v) {
    if (v == std::numeric_limits<double>::max()) return std::string("1.8e308");
    return fmt::format("{:g}", v);
  };
  return fmt::format("{}{}, {}{}", min_exclusive ? "(" : "[", num(min), num(max), max_exclusive ? ")" : "]");
}

std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates) {
  // Levenshtein distance, case-insensitive; a hint only when it is close.
  auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const auto& cand : candidates) {
    std::vector<std::size_t> prev(cand.size() + 1), cur(cand.size() + 1);
    for (std::size_t j = 0; j <= cand.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= word.size(); ++i) {
      cur[0] = i;
      for (std::size_t j = 1; j <= cand.size(); ++j) {
        std::size_t sub = prev[j - 1] + (lower(word[i - 1]) == lower(cand[j - 1]) ? 0 : 1);
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
      }
      std::swap(prev, cur);
    }
    if (prev[cand.size()] < best_d) {
      best_d = prev[cand.size()];
      best = cand;
    }
  }
  const std::size_t allowed = std::max<std::size_t>(2, word.size() / 3);
  return best_d <= allowed ? best : std::string{};
}

ParameterValues validate_parameters(std::string_view law, const std::vector<ParameterSpec>& specs,
                                    const ParameterValues& given) {
  std::vector<std::string> names;
  for (const auto& s : specs) names.push_back(s.name);

  for (const auto& [key, value] : given) {
    if (std::find(names.begin(), names.end(), key) == names.end()) {
      std::string hint = nearest_name(key, names);
      throw LawError(key, fmt::format("law '{}' has no parameter '{}'{}; its parameters are: {}",
                                      law, key,
                                      hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                                      fmt::join(names, ", ")));
    }
  }

  ParameterValues out;
  for (const auto& s : specs) {
    auto it = given.find(s.name);
    double v;
    if (it == given.end()) {
      if (!s.default_value)
        throw LawError(s.name, fmt::format("law '{}' needs parameter '{}' ({}, {}) in {}", law,
                                           s.name, s.meaning, s.unit, s.range_text()));
      v = *s.default_value;
    } else {
      v = it->second;
    }
    if (!std::isfinite(v))
      throw LawError(s.name, fmt::format("law '{}': parameter '{}' is {}; it must be a finite "
                                         "number in {} ({})",
                                         law, s.name, v, s.range_text(), s.unit));
    if (!s.admits(v))
      throw LawError(s.name, fmt::format("law '{}': parameter '{}' = {:g} is out of range {} ({}: {})",
                                         law, s.name, v, s.range_text(), s.unit, s.meaning));
    out.emplace(s.name, v);
  }
  return out;
}

}  // namespace rheodda::laws
