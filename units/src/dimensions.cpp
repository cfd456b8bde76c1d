// The text side of units.hpp: a quantity split into its number and its unit, and a
// declared dimension ("stress*time/length") spelled with a scene's unit labels. No
// conversion here (units.cpp).
#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>

#include "rheodda/units/units.hpp"

namespace rheodda::units {

namespace {

bool space(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<Quantity> split_quantity(std::string_view text) {
  text = trim(text);
  if (text.empty()) return std::nullopt;
  std::size_t start = text.front() == '+' ? 1 : 0;  // from_chars takes '-' but not '+'
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data() + start, text.data() + text.size(), v);
  if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
  const std::size_t used = static_cast<std::size_t>(end - text.data());
  if (used < text.size() && !space(text[used])) return std::nullopt;  // "1e5x", "2.5.3"
  return Quantity{v, std::string(trim(text.substr(used)))};
}

std::string unit_of(std::string_view dimension, const Base& base) {
  // A label that is one word ("mm") as it is, another ("kN*m") in parentheses.
  const auto label = [](const std::string& l) {
    for (char c : l)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return fmt::format("({})", l);
    return l;
  };
  const std::string length = label(base.length), time = label(base.time);
  // Products and quotients of labels, read left to right ("N/m^2*d/m" is (N/m^2)*d/m): in
  // parentheses only after a '/' or before a power, where reading on would change them.
  const std::string force = base.stress.empty() ? label(base.force) : fmt::format("{}*{}^2", label(base.stress), length);
  const std::string stress = base.stress.empty() ? fmt::format("{}/{}^2", force, length) : label(base.stress);
  const std::string mass = fmt::format("{}*{}^2/{}", force, time, length);
  std::string out;
  const auto compound = [&out, &dimension](const std::string& u, std::size_t end) {
    const bool after_slash = !out.empty() && out.back() == '/';
    const bool before_power = end < dimension.size() && dimension[end] == '^';
    const bool before_superscript = dimension.compare(end, 2, "²") == 0 || dimension.compare(end, 2, "³") == 0;
    const bool simple = u.find_first_of("*/^") == std::string::npos;
    out += simple || !(after_slash || before_power || before_superscript) ? u : fmt::format("({})", u);
  };
  for (std::size_t i = 0; i < dimension.size();) {
    const unsigned char c = static_cast<unsigned char>(dimension[i]);
    if (std::isalpha(c)) {
      std::size_t j = i;
      while (j < dimension.size() && std::isalpha(static_cast<unsigned char>(dimension[j]))) ++j;
      const std::string_view w = dimension.substr(i, j - i);
      if (w == "length") out += length;
      else if (w == "force") compound(force, j);
      else if (w == "time") out += time;
      else if (w == "stress") compound(stress, j);
      else if (w == "mass") compound(mass, j);
      else out += w;  // deg, rad, MB: units of their own
      i = j;
    } else if (dimension.compare(i, 2, "²") == 0) {
      out += "^2", i += 2;
    } else if (dimension.compare(i, 2, "³") == 0) {
      out += "^3", i += 2;
    } else if (dimension.compare(i, 2, "·") == 0) {
      out += "*", i += 2;
    } else if (dimension.compare(i, 3, "–") == 0) {  // the declarations' "none"
      out += "1", i += 3;
    } else if (c == '-' && dimension.size() == 1) {
      out += "1", ++i;
    } else {
      out += dimension[i], ++i;
    }
  }
  return out.empty() ? "1" : out;
}

}  // namespace rheodda::units
