// The typed readers of a scene file's YAML (yaml_reader.hpp).
#include "yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace rheodda::scene::detail {

SourceLocation location(const YAML::Node& n) {
  if (!n.IsDefined()) return {};
  const YAML::Mark m = n.Mark();
  return {m.line + 1, m.column + 1};
}


std::string join(const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, ", ")); }

const char* type_word(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Null: return "empty";
    case YAML::NodeType::Scalar: return "a single value";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    default: return "undefined";
  }
}



std::string range_text(const Range& r) {
  auto num = [](double v) {
    if (v == std::numeric_limits<double>::max()) return std::string("inf");
    if (v == std::numeric_limits<double>::lowest()) return std::string("-inf");
    return fmt::format("{:g}", v);
  };
  return fmt::format("{}{}, {}{}", r.min_exclusive ? "(" : "[", num(r.min), num(r.max),
                     r.max_exclusive ? ")" : "]");
}

/// A plain decimal number (digits, sign, point, exponent) read by std::from_chars, or
/// nullopt for anything else: yaml-cpp's as<double> (a stringstream per number) took a
/// fifth of `check` on an explicit rock mass of 1e5 blocks; what this does not take
/// (hex, .inf, words, out of range) goes through as<double> as before.
std::optional<double> plain_number(const std::string& s) {
  if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '-' || s[0] == '.')) return std::nullopt;
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

double number(const Ctx& ctx, const YAML::Node& n, const std::string& key, const Range& r) {
  if (!n.IsScalar())
    ctx.fail(n, key, fmt::format("expected a number{}, got {}",
                                 *r.unit ? fmt::format(" [{}]", r.unit) : "", type_word(n)));
  double v = 0.0;
  if (const auto fast = plain_number(n.Scalar())) {
    v = *fast;
  } else {
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      v = quantity(ctx, n, key, n.Scalar(), r.unit);  // "2600 kg/m^3"
    }
  }
  if (!std::isfinite(v))
    ctx.fail(n, key, fmt::format("'{}' is not a finite number (NaN and inf are not allowed)", n.Scalar()));
  const bool low_ok = r.min_exclusive ? v > r.min : v >= r.min;
  const bool high_ok = r.max_exclusive ? v < r.max : v <= r.max;
  if (!low_ok || !high_ok)
    ctx.fail(n, key, fmt::format("{:g} is out of range {}{}", v, range_text(r),
                                 *r.unit ? fmt::format(" [{}]", r.unit) : ""));
  return v;
}

int integer(const Ctx& ctx, const YAML::Node& n, const std::string& key, int min, int max) {
  const double v = number(ctx, n, key, {double(min), false, double(max), false, ""});
  if (v != std::floor(v)) ctx.fail(n, key, fmt::format("{:g} is not a whole number", v));
  return static_cast<int>(v);
}

std::string text(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar() || n.Scalar().empty())
    ctx.fail(n, key, fmt::format("expected a word, got {}", type_word(n)));
  return n.Scalar();
}

/// A name that can head a CSV column: letters, digits, '_', '-', '.'.
std::string name_text(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  std::string s = text(ctx, n, key);
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      ctx.fail(n, key, fmt::format("name '{}' may only hold letters, digits, '_', '-' and '.'", s));
  return s;
}

bool flag(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  bool b = false;
  if (!n.IsScalar()) ctx.fail(n, key, fmt::format("expected true or false, got {}", type_word(n)));
  try {
    b = n.as<bool>();
  } catch (const YAML::Exception&) {
    ctx.fail(n, key, fmt::format("'{}' is not true or false", n.Scalar()));
  }
  return b;
}

std::string choice(const Ctx& ctx, const YAML::Node& n, const std::string& key,
                   const std::vector<std::string>& values) {
  const std::string s = text(ctx, n, key);
  if (std::find(values.begin(), values.end(), s) == values.end()) {
    const std::string hint = laws::nearest_name(s, values);
    ctx.fail(n, key, fmt::format("'{}' is not one of: {}{}", s, join(values),
                                 hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint)));
  }
  return s;
}

namespace {

/// The dimension of item i of a list of `count` numbers whose unit is `unit`: "time, force,
/// force" gives each item its own; one dimension is every item's.
std::string item_dimension(std::string_view unit, std::size_t i, std::size_t count) {
  std::vector<std::string_view> parts;
  for (std::string_view u = unit;;) {
    const std::size_t comma = u.find(", ");
    parts.push_back(u.substr(0, comma));
    if (comma == std::string_view::npos) break;
    u.remove_prefix(comma + 2);
  }
  return std::string(parts.size() == count ? parts[i] : unit);
}

}  // namespace

std::vector<double> numbers(const Ctx& ctx, const YAML::Node& n, const std::string& key,
                            std::size_t count, const Range& r) {
  if (!n.IsSequence() || n.size() != count)
    ctx.fail(n, key, fmt::format("expected a list of {} numbers [{}], got {}", count, r.unit,
                                 n.IsSequence() ? fmt::format("{} items", n.size())
                                                : std::string(type_word(n))));
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    const YAML::Node item = n[i];
    // The common case without building the item's key (only an error needs it).
    const auto fast = item.IsScalar() ? plain_number(item.Scalar()) : std::nullopt;
    const bool in_range = fast && (r.min_exclusive ? *fast > r.min : *fast >= r.min) &&
                          (r.max_exclusive ? *fast < r.max : *fast <= r.max);
    if (in_range) {
      out.push_back(*fast);
      continue;
    }
    const std::string dimension = item_dimension(r.unit, i, count);
    Range ri = r;
    ri.unit = dimension.c_str();
    out.push_back(number(ctx, item, fmt::format("{}[{}]", key, i), ri));
  }
  return out;
}

Point point(const Ctx& ctx, const YAML::Node& n, const std::string& key, const char* dimension) {
  const auto v = numbers(ctx, n, key, 2, any(dimension));
  return {v[0], v[1]};
}

std::vector<Point> polygon_points(const Ctx& ctx, const YAML::Node& v, const std::string& key) {
  if (!v.IsSequence())
    ctx.fail(v, key, fmt::format("expected a list of [x, y] vertices, got {}", type_word(v)));
  if (v.size() > kMaxVertices) ctx.fail(v, key, fmt::format("more than {} vertices", kMaxVertices));
  std::vector<Point> p;
  for (std::size_t k = 0; k < v.size(); ++k) p.push_back(point(ctx, v[k], fmt::format("{}[{}]", key, k)));
  if (p.size() < 3) ctx.fail(v, key, fmt::format("has {} vertices; a polygon needs at least 3", p.size()));
  return p;
}

}  // namespace rheodda::scene::detail
