// A declared key's value read from its node (read_keys.hpp).
#include "read_keys.hpp"

#include <climits>
#include <cmath>

namespace rheodda::scene::detail {

namespace {

/// The unit as messages write it: "mass/length^3" for the docs' "mass/length³", "" for none.
std::string message_unit(const std::string& unit) {
  if (unit == "–") return "";
  std::string out;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    if (unit.compare(i, 2, "²") == 0) out += "^2", ++i;
    else if (unit.compare(i, 2, "³") == 0) out += "^3", ++i;
    else out += unit[i];
  }
  return out;
}

}  // namespace

KeyValue read_value(const Ctx& ctx, const YAML::Node& v, const std::string& path, const KeyInfo& k) {
  const std::string unit = message_unit(k.unit);
  const Range range{k.range.min, k.range.min_exclusive, k.range.max, k.range.max_exclusive, unit.c_str()};
  switch (k.type) {
    case KeyType::number: return number(ctx, v, path, range);
    case KeyType::integer: {
      if (k.range.max <= INT_MAX && k.range.min >= INT_MIN)
        return integer(ctx, v, path, static_cast<int>(k.range.min), static_cast<int>(k.range.max));
      // Beyond an int (a seed up to 2^53): the same checks, kept whole.
      const double x = number(ctx, v, path, {k.range.min, false, k.range.max, false, ""});
      if (x != std::floor(x)) ctx.fail(v, path, fmt::format("{:g} is not a whole number", x));
      return static_cast<std::int64_t>(x);
    }
    case KeyType::flag: return flag(ctx, v, path);
    case KeyType::choice: return choice(ctx, v, path, k.choices);
    case KeyType::point: return point(ctx, v, path, unit.c_str());
    case KeyType::numbers: return numbers(ctx, v, path, k.count, any(unit.c_str()));
    case KeyType::name: return name_text(ctx, v, path);
    case KeyType::text: return text(ctx, v, path);
    case KeyType::reference:
    case KeyType::list:
    case KeyType::named:
    case KeyType::map: break;  // read by the section's reader
  }
  return std::monostate{};
}

}  // namespace rheodda::scene::detail
