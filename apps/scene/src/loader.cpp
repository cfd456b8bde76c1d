// The scene loader: YAML -> SceneDescription, checking as it goes.
//
// Each YAML map is read through a MapReader that knows the map's valid keys, so
// an unknown (mistyped) key is reported before anything else, with a "did you
// mean" hint (laws::nearest_name). Duplicated keys are refused too: yaml-cpp
// would silently keep one of them.
#include "rheodda/scene/loader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/geometry.hpp"
#include "rheodda/scene/memory.hpp"
#include "yaml_document.hpp"

namespace rheodda::scene {

std::string_view analysis_type_name(AnalysisType t) {
  return t == AnalysisType::static_analysis ? "static" : "dynamic";
}
std::string_view plane_name(PlaneKind p) { return p == PlaneKind::strain ? "strain" : "stress"; }
std::string_view time_integration_name(TimeIntegration t) {
  return t == TimeIntegration::trapezoidal ? "trapezoidal" : "shi";
}
std::string_view solver_name(SolverKind s) {
  switch (s) {
    case SolverKind::automatic: return "automatic";
    case SolverKind::cholmod: return "cholmod";
    case SolverKind::pcg: return "pcg";
    case SolverKind::amg: return "amg";
  }
  return "?";
}

SceneError::SceneError(std::string file, SourceLocation where, std::string key, std::string message)
    : std::runtime_error(where.line > 0 ? fmt::format("{}:{}:{}: {}{}", file, where.line, where.column,
                                                      key.empty() ? "" : key + ": ", message)
                                        : fmt::format("{}: {}{}", file, key.empty() ? "" : key + ": ", message)),
      file_(std::move(file)),
      where_(where),
      key_(std::move(key)),
      message_(std::move(message)) {}

namespace {

// The valid keys of every map of a scene file, each list defined once: the
// MapReader of that map reads it through the list, and scene_schema() publishes
// the same lists, so what the loader accepts and what the schema (and the test of
// docs/scene-format.md against it) says cannot diverge. Order: that of the docs.
namespace keys {
const std::vector<std::string> top{"title", "units", "analysis", "materials", "joint_sets",
                                   "blocks", "rock_mass", "fixed_points", "loads", "measurement_points"};
const std::vector<std::string> units{"length", "force", "time"};
const std::vector<std::string> analysis{
    "type", "duration", "dt", "dt_growth", "dt_cut", "max_cuts", "max_displacement_ratio", "settle",
    "dynamic_ratio", "time_integration", "scheme", "creep_tolerance", "step_tolerance",
    "step_extrapolation", "dt_max", "creep_restart_on_contact_change", "penalty",
    "shear_normal_ratio", "search_factor", "angle_tolerance", "penetration_ratio",
    "stick_keeps_force", "friction_tolerance", "force_resolution", "max_flips", "max_refinements",
    "penalty_raise", "penalty_max_factor", "open_close_limit", "fixed_point_stiffness", "solver", "solver_tolerance",
    "solver_max_iterations", "solver_iterate_tolerance", "contact_solver", "contact_residual_tolerance", "output_interval", "max_travel_ratio", "max_output_size", "gravity"};
const std::vector<std::string> settle{"until", "dt", "max_displacement_ratio", "type", "collapse_dt", "gravity_ramp",
                                      "rest_tolerance", "open_close_limit"};
const std::vector<std::string> material{"density", "young_modulus", "poisson_ratio", "plane", "damping_ratio"};
const std::vector<std::string> joint_set{"friction_angle", "cohesion", "tensile_strength",
                                         "residual_friction_angle", "residual_cohesion", "normal_stiffness", "shear_stiffness", "restitution", "law", "record"};
/// And the parameters of the law named, which only the registry knows.
const std::vector<std::string> law{"name"};
const std::vector<std::string> block{"name", "material", "polygon", "rectangle", "grid",
                                     "joint_set", "edge_joint_sets", "fixed", "initial_stress",
                                     "initial_velocity"};
const std::vector<std::string> rectangle{"x", "y", "width", "height", "angle"};
const std::vector<std::string> grid{"x", "y", "width", "height", "columns", "rows", "angle"};
const std::vector<std::string> rock_mass{"name", "material", "region", "holes", "boundary_joint_set",
                                         "seed", "sliver_area", "joint_sets", "traces"};
const std::vector<std::string> rock_mass_joint_set{"joint_set", "dip", "dip_direction", "spacing",
                                                   "spacing_distribution", "spacing_deviation",
                                                   "trace_length", "gap", "dip_spread", "origin"};
const std::vector<std::string> rock_mass_trace{"joint_set", "from", "to"};
const std::vector<std::string> fixed_point{"point", "block"};
const std::vector<std::string> load{"point", "block", "force", "history"};
const std::vector<std::string> measurement_point{"name", "point", "block"};
}  // namespace keys

// Guards against absurd sizes (a typo such as `columns: 1e9`): generous for real scenes.
constexpr std::size_t kMaxBlocks = 200000;
constexpr std::size_t kMaxVertices = 10000;
constexpr std::size_t kMaxSamples = 1000000;

SourceLocation location(const YAML::Node& n) {
  if (!n.IsDefined()) return {};
  const YAML::Mark m = n.Mark();
  return {m.line + 1, m.column + 1};
}

struct Ctx {
  std::string file;
  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& msg) const {
    throw SceneError(file, location(n), key, msg);
  }
  [[noreturn]] void fail(SourceLocation where, const std::string& key,
                         const std::string& msg) const {
    throw SceneError(file, where, key, msg);
  }
};

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

/// One YAML map with a fixed set of valid keys.
class MapReader {
 public:
  MapReader(const Ctx& ctx, const YAML::Node& node, std::string path,
            std::vector<std::string> allowed)
      : ctx_(ctx), node_(node), path_(std::move(path)), allowed_(std::move(allowed)) {
    if (!node.IsMap())
      ctx.fail(node, path_, fmt::format("expected a map of keys ({}), got {}", join(allowed_),
                                        type_word(node)));
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node k = it->first;
      if (!k.IsScalar()) ctx.fail(k, path_, "a key must be a plain word");
      const std::string key = k.Scalar();
      if (std::find(allowed_.begin(), allowed_.end(), key) == allowed_.end()) {
        const std::string hint = laws::nearest_name(key, allowed_);
        ctx.fail(k, child(key),
                 fmt::format("unknown key '{}'{}; valid keys here: {}", key,
                             hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                             join(allowed_)));
      }
      for (const auto& e : entries_)
        if (e.key == key)
          ctx.fail(k, child(key), fmt::format("key '{}' is given twice (first at line {})", key,
                                              location(e.key_node).line));
      entries_.push_back({key, k, it->second});
    }
  }

  std::string child(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const YAML::Node& node() const { return node_; }
  SourceLocation where() const { return location(node_); }

  /// The value of `key`, or an undefined node.
  YAML::Node find(const std::string& key) const {
    for (const auto& e : entries_)
      if (e.key == key) return e.value;
    return YAML::Node(YAML::NodeType::Undefined);
  }
  bool has(const std::string& key) const { return find(key).IsDefined(); }
  YAML::Node required(const std::string& key, const std::string& what) const {
    YAML::Node v = find(key);
    if (!v.IsDefined())
      ctx_.fail(node_, child(key), fmt::format("missing required key '{}' ({})", key, what));
    return v;
  }
  /// Key nodes in file order (for maps of named items).
  const auto& entries() const { return entries_; }

 private:
  struct Entry {
    std::string key;
    YAML::Node key_node;
    YAML::Node value;
  };
  const Ctx& ctx_;
  YAML::Node node_;
  std::string path_;
  std::vector<std::string> allowed_;
  std::vector<Entry> entries_;
};

/// Valid range of a number; `unit` goes into messages.
struct Range {
  double min = std::numeric_limits<double>::lowest();
  bool min_exclusive = false;
  double max = std::numeric_limits<double>::max();
  bool max_exclusive = false;
  const char* unit = "";
};
Range positive(const char* unit) { return {0.0, true, std::numeric_limits<double>::max(), false, unit}; }
Range non_negative(const char* unit) { return {0.0, false, std::numeric_limits<double>::max(), false, unit}; }
Range any(const char* unit) { return {std::numeric_limits<double>::lowest(), false, std::numeric_limits<double>::max(), false, unit}; }

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
      ctx.fail(n, key, fmt::format("'{}' is not a number", n.Scalar()));
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
    out.push_back(in_range ? *fast : number(ctx, item, fmt::format("{}[{}]", key, i), r));
  }
  return out;
}

Point point(const Ctx& ctx, const YAML::Node& n, const std::string& key) {
  const auto v = numbers(ctx, n, key, 2, any("length"));
  return {v[0], v[1]};
}

/// Index of `name` among items with a `.name`; error with a hint if absent.
template <class T>
int resolve(const Ctx& ctx, const YAML::Node& n, const std::string& key, const std::vector<T>& items,
            const char* what) {
  const std::string s = text(ctx, n, key);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == s) return static_cast<int>(i);
    names.push_back(items[i].name);
  }
  const std::string hint = laws::nearest_name(s, names);
  ctx.fail(n, key, fmt::format("unknown {} '{}'{}; defined: {}", what, s,
                               hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint),
                               join(names)));
}

Units read_units(const Ctx& ctx, const YAML::Node& n) {
  MapReader m(ctx, n, "units", keys::units);
  Units u;
  u.length = text(ctx, m.required("length", "label of the length unit, e.g. m"), m.child("length"));
  u.force = text(ctx, m.required("force", "label of the force unit, e.g. N"), m.child("force"));
  u.time = text(ctx, m.required("time", "label of the time unit, e.g. s"), m.child("time"));
  return u;
}

Analysis read_analysis(const Ctx& ctx, const YAML::Node& n) {
  MapReader m(ctx, n, "analysis", keys::analysis);
  Analysis a;
  a.where = m.where();
  auto num = [&](const char* key, double& field, const Range& r) {
    if (YAML::Node v = m.find(key); v.IsDefined()) field = number(ctx, v, m.child(key), r);
  };
  if (YAML::Node v = m.find("type"); v.IsDefined())
    a.type = choice(ctx, v, m.child("type"), {"static", "dynamic"}) == "static"
                 ? AnalysisType::static_analysis
                 : AnalysisType::dynamic_analysis;
  a.duration = number(ctx, m.required("duration", "simulated time [time]"), m.child("duration"),
                      positive("time"));
  YAML::Node dt = m.required("dt", "first and largest time step [time]");
  a.dt = number(ctx, dt, m.child("dt"), positive("time"));
  if (a.dt > a.duration)
    ctx.fail(dt, m.child("dt"), fmt::format("dt = {:g} is longer than duration = {:g}", a.dt, a.duration));
  if (YAML::Node v = m.find("max_cuts"); v.IsDefined())
    a.max_cuts = integer(ctx, v, m.child("max_cuts"), 0, 200);
  num("dt_cut", a.dt_cut, {0.0, true, 1.0, true, ""});
  num("max_displacement_ratio", a.max_displacement_ratio, {0.0, true, 1.0, false, ""});
  if (YAML::Node v = m.find("settle"); v.IsDefined()) {
    // The settling stage (docs/engine.md, "Settling stage").
    MapReader sm(ctx, v, m.child("settle"), keys::settle);
    Analysis::Settle st;
    // A stage that ends at rest (docs/engine.md, "Dynamic stages") needs no
    // length: `until` is then its longest, by default the analysis's duration.
    YAML::Node rest = sm.find("rest_tolerance");
    YAML::Node until = rest.IsDefined() ? sm.find("until") : sm.required("until", "end of the settling stage [time]");
    if (until.IsDefined()) {
      st.until = number(ctx, until, sm.child("until"), positive("time"));
      if (st.until > a.duration || (!rest.IsDefined() && st.until >= a.duration))
        ctx.fail(until, sm.child("until"),
                 fmt::format("the settling stage ends at {:g}, not before the analysis does (duration = {:g})",
                             st.until, a.duration));
    } else {
      st.until = a.duration;
    }
    if (YAML::Node ol = sm.find("open_close_limit"); ol.IsDefined())
      st.open_close_limit = integer(ctx, ol, sm.child("open_close_limit"), 1, 1000);
    if (rest.IsDefined()) {
      st.rest_tolerance = number(ctx, rest, sm.child("rest_tolerance"), {0.0, true, 1.0, true, ""});
      if (!sm.find("type").IsDefined() || sm.find("type").as<std::string>() != "dynamic")
        ctx.fail(rest, sm.child("rest_tolerance"),
                 "a stage ends at rest when its kinetic energy has decayed: give `type: dynamic`");
    }
    YAML::Node sdt = sm.required("dt", "largest step of the settling stage [time]");
    st.dt = number(ctx, sdt, sm.child("dt"), positive("time"));
    if (st.dt > st.until)
      ctx.fail(sdt, sm.child("dt"),
               fmt::format("dt = {:g} is longer than the settling stage (until = {:g})", st.dt, st.until));
    st.max_displacement_ratio = a.max_displacement_ratio;
    if (YAML::Node g = sm.find("max_displacement_ratio"); g.IsDefined())
      st.max_displacement_ratio = number(ctx, g, sm.child("max_displacement_ratio"), {0.0, true, 1.0, false, ""});
    if (YAML::Node t = sm.find("type"); t.IsDefined()) {
      // A dynamic settling stage in a static analysis (docs/engine.md, "Settling stage").
      st.dynamic = choice(ctx, t, sm.child("type"), {"static", "dynamic"}) == "dynamic";
      if (!st.dynamic && a.type == AnalysisType::dynamic_analysis)
        ctx.fail(t, sm.child("type"),
                 "the settling stage of a dynamic analysis is dynamic; a static stage before dynamic steps "
                 "is not modelled");
    }
    if (YAML::Node c = sm.find("collapse_dt"); c.IsDefined()) {
      // Collapse stages (docs/engine.md, "Collapse stages").
      st.collapse_dt = number(ctx, c, sm.child("collapse_dt"), positive("time"));
      if (!st.dynamic || a.type != AnalysisType::static_analysis)
        ctx.fail(c, sm.child("collapse_dt"),
                 "collapse stages are dynamic stages within a static analysis: give `type: dynamic` in the "
                 "settling stage of a static analysis");
      if (st.collapse_dt >= a.dt)
        ctx.fail(c, sm.child("collapse_dt"),
                 fmt::format("collapse_dt = {:g} is not below the analysis's dt = {:g}", st.collapse_dt, a.dt));
    }
    if (YAML::Node r = sm.find("gravity_ramp"); r.IsDefined()) {
      // Gravity ramped up over the stage's start (docs/engine.md, "Gravity ramp").
      st.gravity_ramp = number(ctx, r, sm.child("gravity_ramp"), positive("time"));
      if (st.gravity_ramp > st.until)
        ctx.fail(r, sm.child("gravity_ramp"),
                 fmt::format("the gravity ramp ends at {:g}, after the settling stage (until = {:g}): the creep "
                             "would start under part of gravity",
                             st.gravity_ramp, st.until));
    }
    a.settle = st;
  }
  a.dynamic_ratio = a.type == AnalysisType::dynamic_analysis ? 1.0 : 0.0;
  if (YAML::Node v = m.find("dynamic_ratio"); v.IsDefined()) {
    if (a.type == AnalysisType::static_analysis)
      ctx.fail(v, m.child("dynamic_ratio"),
               "a static analysis carries no velocity; dynamic_ratio needs `type: dynamic`");
    a.dynamic_ratio = number(ctx, v, m.child("dynamic_ratio"), {0.0, false, 1.0, false, ""});
  }
  if (YAML::Node v = m.find("time_integration"); v.IsDefined()) {
    a.time_integration = choice(ctx, v, m.child("time_integration"), {"shi", "trapezoidal"}) == "trapezoidal"
                             ? TimeIntegration::trapezoidal
                             : TimeIntegration::shi;
    // The trapezoidal rule carries velocity and acceleration from step to step;
    // a static analysis (or dynamic_ratio 0) carries neither. The engine refuses
    // it too (settings.time_integration), but only at `run` and at the analysis map.
    if (a.time_integration == TimeIntegration::trapezoidal && a.type == AnalysisType::static_analysis)
      ctx.fail(v, m.child("time_integration"),
               "a static analysis carries no velocity; time_integration: trapezoidal needs `type: dynamic`");
    if (a.time_integration == TimeIntegration::trapezoidal && a.dynamic_ratio == 0.0)
      ctx.fail(v, m.child("time_integration"),
               "dynamic_ratio = 0 carries no velocity; time_integration: trapezoidal needs dynamic_ratio > 0");
  }
  if (YAML::Node v = m.find("scheme"); v.IsDefined()) {
    const std::string name =
        choice(ctx, v, m.child("scheme"), {"automatic", "lagged", "implicit", "exponential-linear"});
    if (name != "automatic") a.scheme = laws::parse_scheme(name);
  }
  num("creep_tolerance", a.creep_tolerance, non_negative("length"));
  if (YAML::Node v = m.find("step_tolerance"); v.IsDefined()) {
    a.step_tolerance = number(ctx, v, m.child("step_tolerance"), non_negative("length"));
    if (a.step_tolerance > 0.0 && a.creep_tolerance > 0.0)
      ctx.fail(v, m.child("step_tolerance"),
               "give step_tolerance (step doubling) or creep_tolerance (creep error estimate), "
               "not both: they are two step controls");
    if (a.step_tolerance > 0.0 && a.settle && a.settle->collapse_dt > 0.0)
      ctx.fail(v, m.child("step_tolerance"),
               "step doubling takes no collapse stage: give step_tolerance or settle.collapse_dt, not both");
  }
  if (YAML::Node v = m.find("step_extrapolation"); v.IsDefined()) {
    a.step_extrapolation = flag(ctx, v, m.child("step_extrapolation"));
    if (!(a.step_tolerance > 0.0))
      ctx.fail(v, m.child("step_extrapolation"),
               "step_extrapolation applies under step_tolerance only (give step_tolerance > 0)");
  }
  if (YAML::Node v = m.find("dt_max"); v.IsDefined()) {
    a.dt_max = number(ctx, v, m.child("dt_max"), non_negative("time"));
    if (a.dt_max > 0.0 && !(a.creep_tolerance > 0.0 || a.step_tolerance > 0.0))
      ctx.fail(v, m.child("dt_max"),
               "dt_max applies under creep_tolerance or step_tolerance only (a fixed-step run "
               "takes dt)");
    if (a.dt_max > 0.0 && a.dt_max < a.dt)
      ctx.fail(v, m.child("dt_max"),
               fmt::format("dt_max = {:g} is shorter than dt = {:g} (the first step)", a.dt_max, a.dt));
  }
  if (YAML::Node v = m.find("dt_growth"); v.IsDefined()) {
    a.dt_growth = number(ctx, v, m.child("dt_growth"), {1.0, false, std::numeric_limits<double>::max(), false, ""});
    // Only a fixed-step run grows its step back by dt_growth after a cut; an
    // adaptive control sizes every step itself, so the value would be ignored.
    if (a.creep_tolerance > 0.0 || a.step_tolerance > 0.0)
      ctx.fail(v, m.child("dt_growth"),
               "dt_growth applies to a fixed-step run only (under creep_tolerance or step_tolerance "
               "the control sizes the steps)");
  }
  if (YAML::Node v = m.find("creep_restart_on_contact_change"); v.IsDefined())
    a.creep_restart_on_contact_change = flag(ctx, v, m.child("creep_restart_on_contact_change"));
  num("penalty", a.penalty, positive("stress"));
  num("shear_normal_ratio", a.shear_normal_ratio, positive(""));
  num("search_factor", a.search_factor, positive(""));
  num("angle_tolerance", a.angle_tolerance, {0.0, true, 45.0, false, "deg"});
  num("penetration_ratio", a.penetration_ratio, {0.0, true, 1.0, false, ""});
  // Default by analysis type (docs/notes/contact-solves.md, "Stick and slip"): in a dynamic
  // analysis Shi's stick rule ratchets a slope that stands down its friction
  // limit, the more the smaller dt; in a static creep analysis the kept force
  // makes the creep run depend on dt. With collapse stages (docs/engine.md,
  // "Collapse stages") the static steps keep the stages' rule: with Shi's rule
  // there, the contacts a stage left sliding stuck in the first static step
  // with their friction dropped, and the slope slid again (measured: a stage
  // every 0.007 d, 23 in 4 d of the seed's slope against 4 with the force kept).
  a.stick_keeps_force =
      a.type == AnalysisType::dynamic_analysis || (a.settle && a.settle->collapse_dt > 0.0);
  if (YAML::Node v = m.find("stick_keeps_force"); v.IsDefined()) {
    a.stick_keeps_force = flag(ctx, v, m.child("stick_keeps_force"));
    a.stick_keeps_force_given = true;
  }
  // The open-close iteration's settings (contact::ContactSettings; docs/contacts.md).
  num("friction_tolerance", a.friction_tolerance, positive(""));
  num("force_resolution", a.force_resolution, {0.0, false, 1.0, true, ""});
  if (YAML::Node v = m.find("max_flips"); v.IsDefined())
    a.max_flips = integer(ctx, v, m.child("max_flips"), 1, 1000);
  if (YAML::Node v = m.find("max_refinements"); v.IsDefined())
    a.max_refinements = integer(ctx, v, m.child("max_refinements"), 0, 1000);
  num("penalty_raise", a.penalty_raise, {1.0, false, std::numeric_limits<double>::max(), false, ""});
  num("penalty_max_factor", a.penalty_max_factor, {1.0, false, std::numeric_limits<double>::max(), false, ""});
  // Static: Shi's 8, so that a step whose contacts do not settle is cut and retaken
  // smaller rather than settled into a sliding state at a large dt; dynamic: 30
  // (brick walls). Measured in docs/notes/contact-solves.md, "The iteration limit in static analysis".
  a.open_close_limit = a.type == AnalysisType::dynamic_analysis ? 30 : 8;
  if (YAML::Node v = m.find("open_close_limit"); v.IsDefined())
    a.open_close_limit = integer(ctx, v, m.child("open_close_limit"), 1, 1000);
  num("fixed_point_stiffness", a.fixed_point_stiffness, positive("force/length"));
  if (YAML::Node v = m.find("solver"); v.IsDefined()) {
    const std::string name = choice(ctx, v, m.child("solver"), {"automatic", "cholmod", "pcg", "amg"});
    for (SolverKind k : {SolverKind::automatic, SolverKind::cholmod, SolverKind::pcg, SolverKind::amg})
      if (solver_name(k) == name) a.solver = k;
  }
  num("solver_tolerance", a.solver_tolerance, {0.0, true, 1.0, true, ""});
  if (YAML::Node v = m.find("solver_max_iterations"); v.IsDefined())
    a.solver_max_iterations = integer(ctx, v, m.child("solver_max_iterations"), 1, 1000000000);
  num("solver_iterate_tolerance", a.solver_iterate_tolerance, {0.0, false, 1.0, true, ""});
  if (YAML::Node v = m.find("contact_solver"); v.IsDefined()) {
    // docs/contacts.md, "Contact solves".
    const std::string name = choice(ctx, v, m.child("contact_solver"), {"open-close", "newton"});
    a.contact_solver = name == "newton" ? ContactSolverKind::newton : ContactSolverKind::open_close;
  }
  num("contact_residual_tolerance", a.contact_residual_tolerance, {0.0, true, 1.0, true, ""});
  a.output_interval = a.duration / 100.0;
  if (YAML::Node v = m.find("output_interval"); v.IsDefined()) {
    a.output_interval = number(ctx, v, m.child("output_interval"), positive("time"));
    if (a.output_interval > a.duration)
      ctx.fail(v, m.child("output_interval"),
               fmt::format("output_interval = {:g} is longer than duration = {:g}", a.output_interval, a.duration));
  }
  num("max_travel_ratio", a.max_travel_ratio, non_negative(""));
  num("max_output_size", a.max_output_size, non_negative("MB"));
  const auto g = numbers(ctx, m.required("gravity", "gravity acceleration [gx, gy] [length/time^2]"),
                         m.child("gravity"), 2, any("length/time^2"));
  a.gravity = {g[0], g[1]};
  return a;
}

std::vector<Material> read_materials(const Ctx& ctx, const YAML::Node& n, bool dynamic_steps) {
  if (!n.IsMap() || n.size() == 0)
    ctx.fail(n, "materials", "expected a map of named materials, e.g. `rock: {density: ..., ...}`");
  std::vector<Material> out;
  std::vector<std::string> names;  // every name is a valid key of this map
  for (auto it = n.begin(); it != n.end(); ++it) names.push_back(it->first.IsScalar() ? it->first.Scalar() : "");
  MapReader all(ctx, n, "materials", names);
  for (const auto& e : all.entries()) {
    Material mat;
    mat.name = name_text(ctx, e.key_node, "materials");
    const std::string path = all.child(e.key);
    MapReader m(ctx, e.value, path, keys::material);
    mat.where = location(e.key_node);
    mat.density = number(ctx, m.required("density", "[mass/length^3]"), m.child("density"),
                         positive("mass/length^3"));
    mat.young_modulus = number(ctx, m.required("young_modulus", "E [stress]"),
                               m.child("young_modulus"), positive("stress"));
    mat.poisson_ratio = number(ctx, m.required("poisson_ratio", "nu [-]"), m.child("poisson_ratio"),
                               {0.0, false, 0.5, true, ""});
    if (YAML::Node v = m.find("plane"); v.IsDefined())
      mat.plane = choice(ctx, v, m.child("plane"), {"strain", "stress"}) == "strain" ? PlaneKind::strain
                                                                                   : PlaneKind::stress;
    if (YAML::Node v = m.find("damping_ratio"); v.IsDefined()) {
      // Block damping damps velocities; a static analysis carries none.
      if (!dynamic_steps)
        ctx.fail(v, m.child("damping_ratio"),
                 "a static analysis carries no velocity; damping_ratio needs `analysis: {type: dynamic}` "
                 "or a dynamic settling stage (`settle: {type: dynamic, ...}`)");
      mat.damping_ratio = number(ctx, v, m.child("damping_ratio"), {0.0, false, 1.0, false, ""});
    }
    out.push_back(std::move(mat));
  }
  return out;
}

LawChoice read_law(const Ctx& ctx, const YAML::Node& n, const std::string& path) {
  const auto& registry = laws::LawRegistry::builtin();
  if (!n.IsMap()) ctx.fail(n, path, fmt::format("expected a map `{{name: LAW, PARAM: value, ...}}`, got {}", type_word(n)));
  YAML::Node name_node = n["name"];
  if (!name_node.IsDefined())
    ctx.fail(n, path + ".name", "missing required key 'name' (the law: see `rheodda law list`)");
  const std::string name = text(ctx, name_node, path + ".name");
  const laws::LawInfo* info = registry.find(name);
  if (!info) {
    std::vector<std::string> names;
    for (const auto& l : registry.laws()) names.push_back(l.name);
    const std::string hint = laws::nearest_name(name, names);
    ctx.fail(name_node, path + ".name",
             fmt::format("unknown law '{}'{}; known laws: {}", name,
                         hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint), join(names)));
  }
  std::vector<std::string> allowed = keys::law;
  for (const auto& p : info->parameters) allowed.push_back(p.name);
  MapReader m(ctx, n, path, allowed);
  LawChoice law;
  law.name = name;
  laws::ParameterValues given;
  for (const auto& e : m.entries())
    if (e.key != "name") given[e.key] = number(ctx, e.value, m.child(e.key), any(""));
  try {
    law.parameters = laws::validate_parameters(name, info->parameters, given);
  } catch (const laws::LawError& err) {
    YAML::Node at = m.find(err.key());
    ctx.fail(at.IsDefined() ? at : n, m.child(err.key()), err.what());
  }
  // The law must also build (a law may check relations between its parameters).
  try {
    (void)registry.create(name, law.parameters);
  } catch (const laws::LawError& err) {
    YAML::Node at = m.find(err.key());
    ctx.fail(at.IsDefined() ? at : n, m.child(err.key()), err.what());
  }
  return law;
}

std::vector<JointSetDescription> read_joint_sets(const Ctx& ctx, const YAML::Node& n, bool dynamic_steps) {
  if (!n.IsMap() || n.size() == 0)
    ctx.fail(n, "joint_sets", "expected a map of named joint sets, e.g. `bedding: {friction_angle: 30}`");
  std::vector<std::string> names;  // every name is a valid key of this map
  for (auto it = n.begin(); it != n.end(); ++it) names.push_back(it->first.IsScalar() ? it->first.Scalar() : "");
  MapReader all(ctx, n, "joint_sets", names);
  std::vector<JointSetDescription> out;
  for (const auto& e : all.entries()) {
    JointSetDescription js;
    js.name = name_text(ctx, e.key_node, "joint_sets");
    js.where = location(e.key_node);
    MapReader m(ctx, e.value, all.child(e.key), keys::joint_set);
    js.friction_angle = number(ctx, m.required("friction_angle", "phi [deg], 0 <= phi < 90"),
                               m.child("friction_angle"), {0.0, false, 90.0, true, "deg"});
    if (YAML::Node v = m.find("cohesion"); v.IsDefined())
      js.cohesion = number(ctx, v, m.child("cohesion"), non_negative("stress"));
    if (YAML::Node v = m.find("tensile_strength"); v.IsDefined())
      js.tensile_strength = number(ctx, v, m.child("tensile_strength"), non_negative("stress"));
    // Residual strength (UDEC/3DEC): once a contact slid, opened or its damage law failed.
    if (YAML::Node v = m.find("residual_friction_angle"); v.IsDefined()) {
      js.residual_friction_angle = number(ctx, v, m.child("residual_friction_angle"), non_negative("deg"));
      if (*js.residual_friction_angle > js.friction_angle)
        ctx.fail(v, m.child("residual_friction_angle"),
                 fmt::format("{:g} deg is above the peak friction_angle {:g} deg: a residual strength is at most the peak",
                             *js.residual_friction_angle, js.friction_angle));
    }
    if (YAML::Node v = m.find("residual_cohesion"); v.IsDefined()) {
      js.residual_cohesion = number(ctx, v, m.child("residual_cohesion"), non_negative("stress"));
      if (js.residual_cohesion > js.cohesion)
        ctx.fail(v, m.child("residual_cohesion"),
                 fmt::format("{:g} is above the peak cohesion {:g}: a residual strength is at most the peak",
                             js.residual_cohesion, js.cohesion));
    }
    if (YAML::Node v = m.find("normal_stiffness"); v.IsDefined())
      js.normal_stiffness = number(ctx, v, m.child("normal_stiffness"), positive("stress/length"));
    if (YAML::Node v = m.find("shear_stiffness"); v.IsDefined())
      js.shear_stiffness = number(ctx, v, m.child("shear_stiffness"), positive("stress/length"));
    if (YAML::Node v = m.find("restitution"); v.IsDefined()) {
      // Contact dashpots damp motion; a static analysis has none to damp.
      if (!dynamic_steps)
        ctx.fail(v, m.child("restitution"),
                 "a static analysis carries no velocity; restitution needs `analysis: {type: dynamic}` "
                 "or a dynamic settling stage (`settle: {type: dynamic, ...}`)");
      js.restitution = number(ctx, v, m.child("restitution"), {0.0, false, 1.0, false, ""});
    }
    if (YAML::Node v = m.find("law"); v.IsDefined()) {
      js.law = read_law(ctx, v, m.child("law"));
      // A law with an instantaneous spring E1 (burgers, maxwell, nishihara) is the
      // joint's elastic shear spring, k_s = E1 l: one value, given once.
      if (js.shear_stiffness && js.law->parameters.count("E1"))
        ctx.fail(m.find("shear_stiffness"), m.child("shear_stiffness"),
                 fmt::format("law '{}' sets the joint's elastic shear stiffness with its E1; "
                             "remove shear_stiffness (or use a law without E1)", js.law->name));
    }
    if (YAML::Node v = m.find("record"); v.IsDefined()) js.record = flag(ctx, v, m.child("record"));
    out.push_back(std::move(js));
  }
  return out;
}

/// A block entry before the geometry checks: one or many blocks (grid).
struct RawBlock {
  BlockDescription block;
  std::string path;
  YAML::Node node;
  YAML::Node geometry_node;
};

std::vector<int> edge_sets(const Ctx& ctx, const MapReader& m, const SceneDescription& s,
                           std::size_t edges, const char* order) {
  YAML::Node all = m.find("joint_set");
  YAML::Node each = m.find("edge_joint_sets");
  if (all.IsDefined() && each.IsDefined())
    ctx.fail(each, m.child("edge_joint_sets"), "give either joint_set (every edge) or edge_joint_sets, not both");
  if (each.IsDefined()) {
    if (!each.IsSequence() || each.size() != edges)
      ctx.fail(each, m.child("edge_joint_sets"),
               fmt::format("expected a list of {} joint set names, one per edge ({})", edges, order));
    std::vector<int> out;
    for (std::size_t k = 0; k < edges; ++k)
      out.push_back(resolve(ctx, each[k], fmt::format("{}[{}]", m.child("edge_joint_sets"), k),
                            s.joint_sets, "joint set"));
    return out;
  }
  int js = 0;
  if (all.IsDefined())
    js = resolve(ctx, all, m.child("joint_set"), s.joint_sets, "joint set");
  else if (s.joint_sets.size() != 1)
    ctx.fail(m.node(), m.child("joint_set"),
             "missing key 'joint_set' (or edge_joint_sets): the scene has several joint sets");
  return std::vector<int>(edges, js);
}

void read_blocks(const Ctx& ctx, const YAML::Node& n, SceneDescription& s, std::vector<RawBlock>& raw) {
  if (!n.IsSequence() || n.size() == 0)
    ctx.fail(n, "blocks", "expected a list of blocks, e.g. `- {rectangle: {x: 0, y: 0, width: 1, height: 1}}`");
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string path = fmt::format("blocks[{}]", i);
    MapReader m(ctx, n[i], path, keys::block);
    BlockDescription b;
    b.where = m.where();
    if (YAML::Node v = m.find("material"); v.IsDefined())
      b.material = resolve(ctx, v, m.child("material"), s.materials, "material");
    else if (s.materials.size() != 1)
      ctx.fail(m.node(), m.child("material"), "missing key 'material': the scene has several materials");
    if (YAML::Node v = m.find("fixed"); v.IsDefined()) b.fixed = flag(ctx, v, m.child("fixed"));
    if (YAML::Node v = m.find("initial_stress"); v.IsDefined()) {
      const auto x = numbers(ctx, v, m.child("initial_stress"), 3, any("stress"));
      b.initial_stress = {x[0], x[1], x[2]};
    }
    if (YAML::Node v = m.find("initial_velocity"); v.IsDefined()) {
      const auto x = numbers(ctx, v, m.child("initial_velocity"), 3, any("length/time, 1/time"));
      if (s.analysis.type == AnalysisType::static_analysis && (x[0] != 0 || x[1] != 0 || x[2] != 0))
        ctx.fail(v, m.child("initial_velocity"),
                 "a static analysis carries no velocity; initial_velocity needs `analysis: {type: dynamic}`");
      b.initial_velocity = {x[0], x[1], x[2]};
    }
    std::string name;
    if (YAML::Node v = m.find("name"); v.IsDefined()) name = name_text(ctx, v, m.child("name"));

    const int shapes = int(m.has("polygon")) + int(m.has("rectangle")) + int(m.has("grid"));
    if (shapes != 1)
      ctx.fail(m.node(), path, shapes == 0 ? "missing the shape: give one of polygon, rectangle, grid"
                                           : "give only one of polygon, rectangle, grid");
    if (YAML::Node v = m.find("polygon"); v.IsDefined()) {
      if (!v.IsSequence())
        ctx.fail(v, m.child("polygon"), fmt::format("expected a list of [x, y] vertices, got {}", type_word(v)));
      if (v.size() > kMaxVertices)
        ctx.fail(v, m.child("polygon"), fmt::format("more than {} vertices", kMaxVertices));
      for (std::size_t k = 0; k < v.size(); ++k)
        b.polygon.push_back(point(ctx, v[k], fmt::format("{}[{}]", m.child("polygon"), k)));
      if (b.polygon.size() < 3)
        ctx.fail(v, m.child("polygon"), fmt::format("has {} vertices; a polygon needs at least 3", b.polygon.size()));
      b.edge_joint_set = edge_sets(ctx, m, s, b.polygon.size(), "edge k runs from vertex k to k+1");
      b.name = name;
      raw.push_back({b, path, n[i], v});
      continue;
    }
    const bool grid = m.has("grid");
    const std::string key = grid ? "grid" : "rectangle";
    YAML::Node g = m.find(key);
    MapReader r(ctx, g, m.child(key), grid ? keys::grid : keys::rectangle);
    const double x = number(ctx, r.required("x", "x of the lower-left corner [length]"), r.child("x"), any("length"));
    const double y = number(ctx, r.required("y", "y of the lower-left corner [length]"), r.child("y"), any("length"));
    const double w = number(ctx, r.required("width", "[length]"), r.child("width"), positive("length"));
    const double h = number(ctx, r.required("height", "[length]"), r.child("height"), positive("length"));
    double angle = 0.0;  // counter-clockwise rotation about (x, y) [deg]
    if (YAML::Node v = r.find("angle"); v.IsDefined())
      angle = number(ctx, v, r.child("angle"), {-360.0, false, 360.0, false, "deg"});
    const double ca = std::cos(angle * std::numbers::pi / 180.0), sa = std::sin(angle * std::numbers::pi / 180.0);
    auto place = [&](double ls, double lt) -> Point { return {x + ca * ls - sa * lt, y + sa * ls + ca * lt}; };
    int cols = 1, rows = 1;
    if (grid) {
      cols = integer(ctx, r.required("columns", "number of blocks along x"), r.child("columns"), 1, int(kMaxBlocks));
      rows = integer(ctx, r.required("rows", "number of blocks along y"), r.child("rows"), 1, int(kMaxBlocks));
      if (std::size_t(cols) * std::size_t(rows) + raw.size() > kMaxBlocks)
        ctx.fail(g, m.child(key), fmt::format("more than {} blocks in the scene", kMaxBlocks));
    }
    b.edge_joint_set = edge_sets(ctx, m, s, 4, "bottom, right, top, left");
    for (int row = 0; row < rows; ++row)
      for (int col = 0; col < cols; ++col) {
        BlockDescription c = b;
        const double s0 = col * w, t0 = row * h;
        c.polygon = {place(s0, t0), place(s0 + w, t0), place(s0 + w, t0 + h), place(s0, t0 + h)};
        c.name = grid ? fmt::format("{}.r{}.c{}", name.empty() ? fmt::format("grid{}", i + 1) : name,
                                    row + 1, col + 1)
                      : name;
        raw.push_back({c, path, n[i], g});
      }
  }
}

/// A polygon `[[x, y], ...]` of 3 to kMaxVertices vertices [length].
std::vector<Point> polygon_points(const Ctx& ctx, const YAML::Node& v, const std::string& key) {
  if (!v.IsSequence())
    ctx.fail(v, key, fmt::format("expected a list of [x, y] vertices, got {}", type_word(v)));
  if (v.size() > kMaxVertices) ctx.fail(v, key, fmt::format("more than {} vertices", kMaxVertices));
  std::vector<Point> p;
  for (std::size_t k = 0; k < v.size(); ++k) p.push_back(point(ctx, v[k], fmt::format("{}[{}]", key, k)));
  if (p.size() < 3) ctx.fail(v, key, fmt::format("has {} vertices; a polygon needs at least 3", p.size()));
  return p;
}

/// `rock_mass:` (docs/rockmass.md): reads the region, the joint sets' statistics and the
/// explicit traces, generates and cuts (rockmass::generate_traces, cut_blocks) and
/// appends the blocks to `raw`; they are checked with the hand-written ones.
void read_rock_mass(const Ctx& ctx, const YAML::Node& n, SceneDescription& s, std::vector<RawBlock>& raw) {
  MapReader m(ctx, n, "rock_mass", keys::rock_mass);
  RockMassDescription rm;
  rm.where = m.where();
  if (YAML::Node v = m.find("name"); v.IsDefined()) rm.name = name_text(ctx, v, m.child("name"));
  if (YAML::Node v = m.find("material"); v.IsDefined())
    rm.material = resolve(ctx, v, m.child("material"), s.materials, "material");
  else if (s.materials.size() != 1)
    ctx.fail(m.node(), m.child("material"), "missing key 'material': the scene has several materials");
  const YAML::Node region = m.required("region", "the polygon to cut, [[x, y], ...] [length]");
  rm.region.outer = polygon_points(ctx, region, m.child("region"));
  if (auto defect = coordinate_defect(rm.region.outer)) ctx.fail(region, m.child("region"), "the region " + *defect);
  rockmass::Box box{rm.region.outer[0][0], rm.region.outer[0][1], rm.region.outer[0][0], rm.region.outer[0][1]};
  for (const Point& p : rm.region.outer)
    box = {std::min(box.x0, p[0]), std::min(box.y0, p[1]), std::max(box.x1, p[0]), std::max(box.y1, p[1])};
  const double tol = std::max(1e-9 * std::hypot(box.x1 - box.x0, box.y1 - box.y0), std::numeric_limits<double>::min());
  if (auto defect = polygon_defect(rm.region.outer, tol)) ctx.fail(region, m.child("region"), "the region " + *defect);
  if (YAML::Node h = m.find("holes"); h.IsDefined()) {
    if (!h.IsSequence()) ctx.fail(h, m.child("holes"), fmt::format("expected a list of polygons, got {}", type_word(h)));
    for (std::size_t k = 0; k < h.size(); ++k) {
      const std::string key = fmt::format("{}[{}]", m.child("holes"), k);
      auto hole = polygon_points(ctx, h[k], key);
      if (auto defect = polygon_defect(hole, tol)) ctx.fail(h[k], key, "the hole " + *defect);
      for (const Point& p : hole)
        if (!contains(rm.region.outer, p, tol) || boundary_distance(rm.region.outer, p) <= tol)
          ctx.fail(h[k], key, fmt::format("vertex ({:g}, {:g}) of the hole is not strictly inside the region", p[0], p[1]));
      for (const Point& p : rm.region.outer)
        if (contains(hole, p, tol))
          ctx.fail(h[k], key, fmt::format("the hole covers the region's vertex ({:g}, {:g})", p[0], p[1]));
      for (std::size_t j = 0; j < rm.region.holes.size(); ++j) {
        bool touch = interiors_overlap(hole, rm.region.holes[j], tol);
        for (const Point& p : hole) touch = touch || contains(rm.region.holes[j], p, tol);
        for (const Point& p : rm.region.holes[j]) touch = touch || contains(hole, p, tol);
        if (touch) ctx.fail(h[k], key, fmt::format("holes {} and {} overlap or touch", j, k));
      }
      rm.region.holes.push_back(std::move(hole));
    }
  }
  if (YAML::Node v = m.find("boundary_joint_set"); v.IsDefined())
    rm.boundary_joint_set = resolve(ctx, v, m.child("boundary_joint_set"), s.joint_sets, "joint set");
  else if (s.joint_sets.size() != 1)
    ctx.fail(m.node(), m.child("boundary_joint_set"),
             "missing key 'boundary_joint_set' (the joint set of the edges on the region's boundary): the scene "
             "has several joint sets");
  if (YAML::Node v = m.find("seed"); v.IsDefined()) {
    const double seed = number(ctx, v, m.child("seed"), {0.0, false, 9007199254740992.0, false, ""});
    if (seed != std::floor(seed)) ctx.fail(v, m.child("seed"), fmt::format("{:g} is not a whole number", seed));
    rm.seed = static_cast<std::uint64_t>(seed);
  }
  if (YAML::Node v = m.find("sliver_area"); v.IsDefined())
    rm.sliver_area = number(ctx, v, m.child("sliver_area"), non_negative("length^2"));
  auto list = [&](const char* key) {
    YAML::Node v = m.find(key);
    if (v.IsDefined() && !v.IsSequence())
      ctx.fail(v, m.child(key), fmt::format("expected a list of maps, got {}", type_word(v)));
    return v;
  };
  std::vector<rockmass::Trace> traces;
  std::vector<std::pair<std::size_t, std::size_t>> set_traces;  // per joint set: its range in `traces`
  if (YAML::Node sets = list("joint_sets"); sets.IsDefined())
    for (std::size_t i = 0; i < sets.size(); ++i) {
      MapReader j(ctx, sets[i], fmt::format("{}[{}]", m.child("joint_sets"), i), keys::rock_mass_joint_set);
      rockmass::JointSetGeneration g;
      g.tag = resolve(ctx, j.required("joint_set", "a name of the scene's joint_sets"), j.child("joint_set"),
                      s.joint_sets, "joint set");
      g.dip = number(ctx, j.required("dip", "angle below the horizontal [deg], 0 to 90"), j.child("dip"),
                     {0.0, false, 90.0, false, "deg"});
      if (YAML::Node v = j.find("dip_direction"); v.IsDefined())
        g.dips_right = choice(ctx, v, j.child("dip_direction"), {"right", "left"}) == "right";
      g.spacing = number(ctx, j.required("spacing", "mean spacing normal to the joints [length]"),
                         j.child("spacing"), positive("length"));
      if (YAML::Node v = j.find("spacing_distribution"); v.IsDefined()) {
        const std::string d = choice(ctx, v, j.child("spacing_distribution"),
                                     {"constant", "normal", "exponential", "log-normal"});
        for (auto k : {rockmass::SpacingDistribution::constant, rockmass::SpacingDistribution::normal,
                       rockmass::SpacingDistribution::exponential, rockmass::SpacingDistribution::log_normal})
          if (d == rockmass::spacing_distribution_name(k)) g.spacing_distribution = k;
      }
      const bool deviation = g.spacing_distribution == rockmass::SpacingDistribution::normal ||
                             g.spacing_distribution == rockmass::SpacingDistribution::log_normal;
      if (YAML::Node v = j.find("spacing_deviation"); v.IsDefined()) {
        if (!deviation)
          ctx.fail(v, j.child("spacing_deviation"),
                   fmt::format("a {} spacing has no deviation; spacing_deviation applies to spacing_distribution "
                               "normal or log-normal",
                               rockmass::spacing_distribution_name(g.spacing_distribution)));
        g.spacing_deviation = number(ctx, v, j.child("spacing_deviation"), positive("length"));
      } else if (deviation) {
        ctx.fail(j.node(), j.child("spacing_deviation"),
                 fmt::format("missing key 'spacing_deviation' (standard deviation of a {} spacing [length])",
                             rockmass::spacing_distribution_name(g.spacing_distribution)));
      }
      YAML::Node length = j.find("trace_length"), gap = j.find("gap");
      if (length.IsDefined() != gap.IsDefined())
        ctx.fail(length.IsDefined() ? length : gap, j.child(length.IsDefined() ? "gap" : "trace_length"),
                 "give trace_length and gap together (non-persistent joints), or neither (persistent joints)");
      if (length.IsDefined()) {
        g.trace_length = number(ctx, length, j.child("trace_length"), positive("length"));
        g.gap = number(ctx, gap, j.child("gap"), non_negative("length"));
      }
      if (YAML::Node v = j.find("dip_spread"); v.IsDefined())
        g.dip_spread = number(ctx, v, j.child("dip_spread"), {0.0, false, 45.0, false, "deg"});
      if (YAML::Node v = j.find("origin"); v.IsDefined()) g.origin = point(ctx, v, j.child("origin"));
      // Lines across the region: its box's diagonal over the smallest likely spacing.
      const double lines = std::hypot(box.x1 - box.x0, box.y1 - box.y0) / g.spacing;
      if (lines > 1e6)
        ctx.fail(j.find("spacing"), j.child("spacing"),
                 fmt::format("spacing {:g} gives about {:.3g} joints across the region (more than 1e6)", g.spacing, lines));
      std::vector<rockmass::Trace> t;
      try {
        t = rockmass::generate_traces(g, {box.x0, box.y0, box.x1, box.y1}, rm.seed, static_cast<int>(i));
      } catch (const std::invalid_argument& e) {
        ctx.fail(j.node(), j.child("spacing"), e.what());
      }
      if (traces.size() + t.size() > rockmass::kMaxTraces)
        ctx.fail(j.node(), j.child("spacing"), "the joint sets give more than 2e6 traces: larger spacing or fewer sets");
      set_traces.push_back({traces.size(), traces.size() + t.size()});
      traces.insert(traces.end(), t.begin(), t.end());
      rm.joint_sets.push_back(g);
    }
  if (YAML::Node list_t = list("traces"); list_t.IsDefined())
    for (std::size_t i = 0; i < list_t.size(); ++i) {
      MapReader j(ctx, list_t[i], fmt::format("{}[{}]", m.child("traces"), i), keys::rock_mass_trace);
      rockmass::Trace t;
      t.tag = resolve(ctx, j.required("joint_set", "a name of the scene's joint_sets"), j.child("joint_set"),
                      s.joint_sets, "joint set");
      t.a = point(ctx, j.required("from", "[x, y] [length]"), j.child("from"));
      YAML::Node to = j.required("to", "[x, y] [length]");
      t.b = point(ctx, to, j.child("to"));
      if (t.a == t.b) ctx.fail(to, j.child("to"), "the trace ends where it starts");
      rm.traces.push_back(t);
      traces.push_back(t);
    }
  // What the cut will cost, before cutting: a spacing of millimetres over a slope
  // would ask for 1e9 blocks and more memory than the machine has.
  {
    const rockmass::CutEstimate e = rm.estimate = rockmass::estimate_cut(rm.region, traces);
    // Located at the joint set that draws the most traces (or the explicit traces).
    YAML::Node at = m.find("traces");
    std::string key = m.child("traces");
    std::size_t most = 0;
    for (std::size_t i = 0; i < set_traces.size(); ++i)
      if (const std::size_t k = set_traces[i].second - set_traces[i].first; k >= most) {
        most = k;
        at = list("joint_sets")[i]["spacing"];
        key = fmt::format("{}[{}].spacing", m.child("joint_sets"), i);
      }
    if (!at.IsDefined()) at = n, key = "rock_mass";
    const std::string what =
        fmt::format("the traces ({} of them) cross about {:.3g} times and would cut the region into up to {:.3g} "
                    "blocks",
                    traces.size(), e.crossings, e.pieces);
    if (e.pieces > 10.0 * static_cast<double>(kMaxBlocks))
      ctx.fail(at, key, fmt::format("{}; a scene holds at most {} blocks: a larger spacing, shorter traces or a "
                                    "smaller region",
                                    what, kMaxBlocks));
    if (const auto available = available_memory(); available && e.bytes > *available)
      ctx.fail(at, key, fmt::format("{}; the cut would need about {} of memory, {} is available: a larger spacing, "
                                    "shorter traces or a smaller region",
                                    what, format_bytes(e.bytes), format_bytes(*available)));
  }
  rockmass::CutResult cut;
  try {
    cut = rockmass::cut_blocks(rm.region, traces, {rm.sliver_area});
  } catch (const rockmass::CutError& e) {
    ctx.fail(region, m.child("region"), e.what());
  }
  for (const auto& [first, last] : set_traces)
    rm.traces_generated.push_back(static_cast<std::size_t>(
        std::count(cut.trace_in_region.begin() + static_cast<long>(first),
                   cut.trace_in_region.begin() + static_cast<long>(last), 1)));
  if (cut.blocks.size() + raw.size() > kMaxBlocks)
    ctx.fail(n, "rock_mass", fmt::format("the cut gives {} blocks; more than {} blocks in the scene",
                                         cut.blocks.size(), kMaxBlocks));
  rm.first_block = raw.size();
  rm.block_count = cut.blocks.size();
  rm.joint_length = cut.joint_length;
  rm.merged_slivers = cut.merged_slivers;
  rm.dangling_removed = cut.dangling_removed;
  rm.extended_traces = cut.extended_traces;
  rm.added_traces = cut.added_traces;
  rm.collapsed_blocks = cut.collapsed_blocks;
  rm.area_error = cut.area_error;
  for (std::size_t k = 0; k < cut.blocks.size(); ++k) {
    rockmass::Block& c = cut.blocks[k];
    BlockDescription b;
    b.name = fmt::format("{}.{}", rm.name, k + 1);
    b.material = rm.material;
    b.where = rm.where;
    std::vector<bool> on_boundary;
    for (std::size_t e = 0; e < c.polygon.size(); ++e) {
      b.polygon.push_back({c.polygon[e][0], c.polygon[e][1]});
      on_boundary.push_back(c.edge_tag[e] == rockmass::kBoundaryTag);
      b.edge_joint_set.push_back(on_boundary.back() ? rm.boundary_joint_set : c.edge_tag[e]);
    }
    rm.edge_on_boundary.push_back(std::move(on_boundary));
    raw.push_back({std::move(b), "rock_mass", n, region});
  }
  s.rock_mass = std::move(rm);
}

/// Tolerance for "same place": a billionth of the model size [length].
double geometry_tolerance(const std::vector<BlockDescription>& blocks) {
  return std::max(1e-9 * 2.0 * half_model_size(blocks), std::numeric_limits<double>::min());
}

BlockPoint read_block_point(const Ctx& ctx, const MapReader& m, const SceneDescription& s, double tol) {
  BlockPoint bp;
  bp.where = m.where();
  YAML::Node p = m.required("point", "[x, y] [length]");
  bp.point = point(ctx, p, m.child("point"));
  if (YAML::Node v = m.find("block"); v.IsDefined()) {
    bp.block = resolve(ctx, v, m.child("block"), s.blocks, "block");
    if (!contains(s.blocks[bp.block].polygon, bp.point, tol))
      ctx.fail(p, m.child("point"),
               fmt::format("({:g}, {:g}) is not on block '{}'", bp.point[0], bp.point[1], s.blocks[bp.block].name));
    return bp;
  }
  std::vector<int> hits;
  for (std::size_t i = 0; i < s.blocks.size(); ++i)
    if (contains(s.blocks[i].polygon, bp.point, tol)) hits.push_back(static_cast<int>(i));
  if (hits.empty())
    ctx.fail(p, m.child("point"), fmt::format("({:g}, {:g}) lies on no block", bp.point[0], bp.point[1]));
  if (hits.size() > 1) {
    std::vector<std::string> names;
    for (int h : hits) names.push_back(s.blocks[h].name);
    ctx.fail(p, m.child("point"),
             fmt::format("({:g}, {:g}) lies on the boundary of several blocks ({}); say which with `block:`",
                         bp.point[0], bp.point[1], join(names)));
  }
  bp.block = hits.front();
  return bp;
}

void read_points(const Ctx& ctx, const MapReader& top, SceneDescription& s) {
  const double tol = geometry_tolerance(s.blocks);
  auto list = [&](const char* key) {
    YAML::Node n = top.find(key);
    if (n.IsDefined() && !n.IsSequence() && !n.IsNull())
      ctx.fail(n, key, fmt::format("expected a list, got {}", type_word(n)));
    return n;
  };
  if (YAML::Node n = list("fixed_points"); n.IsSequence())
    for (std::size_t i = 0; i < n.size(); ++i) {
      MapReader m(ctx, n[i], fmt::format("fixed_points[{}]", i), keys::fixed_point);
      s.fixed_points.push_back(read_block_point(ctx, m, s, tol));
    }
  if (YAML::Node n = list("loads"); n.IsSequence())
    for (std::size_t i = 0; i < n.size(); ++i) {
      MapReader m(ctx, n[i], fmt::format("loads[{}]", i), keys::load);
      LoadDescription load;
      load.at = read_block_point(ctx, m, s, tol);
      YAML::Node f = m.find("force"), h = m.find("history");
      if (f.IsDefined() == h.IsDefined())
        ctx.fail(m.node(), m.child("force"),
                 "give exactly one of force: [fx, fy] or history: [[t, fx, fy], ...]");
      if (f.IsDefined()) {
        const auto v = numbers(ctx, f, m.child("force"), 2, any("force"));
        load.history.push_back({0.0, v[0], v[1]});
      } else {
        if (!h.IsSequence() || h.size() == 0 || h.size() > kMaxSamples)
          ctx.fail(h, m.child("history"), "expected a list of [t, fx, fy] samples");
        for (std::size_t k = 0; k < h.size(); ++k) {
          const std::string key = fmt::format("{}[{}]", m.child("history"), k);
          const auto v = numbers(ctx, h[k], key, 3, any("time, force, force"));
          if (v[0] < 0.0) ctx.fail(h[k], key, fmt::format("time {:g} is negative", v[0]));
          if (!load.history.empty() && v[0] <= load.history.back()[0])
            ctx.fail(h[k], key, fmt::format("times must increase strictly: {:g} after {:g}", v[0],
                                            load.history.back()[0]));
          load.history.push_back({v[0], v[1], v[2]});
        }
      }
      s.loads.push_back(std::move(load));
    }
  if (YAML::Node n = list("measurement_points"); n.IsSequence())
    for (std::size_t i = 0; i < n.size(); ++i) {
      MapReader m(ctx, n[i], fmt::format("measurement_points[{}]", i), keys::measurement_point);
      MeasurementPoint mp;
      YAML::Node name = m.required("name", "column prefix in history.csv");
      mp.name = name_text(ctx, name, m.child("name"));
      for (const auto& other : s.measurement_points)
        if (other.name == mp.name)
          ctx.fail(name, m.child("name"), fmt::format("measurement point '{}' is defined twice", mp.name));
      mp.at = read_block_point(ctx, m, s, tol);
      s.measurement_points.push_back(std::move(mp));
    }
}

void check_geometry(const Ctx& ctx, std::vector<RawBlock>& raw, SceneDescription& s) {
  std::vector<BlockDescription> blocks;
  for (const auto& r : raw) blocks.push_back(r.block);
  // A block with coordinates that overflow, or far from all others (a typo), is
  // named before its size sets the tolerance every other block is checked with.
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (auto defect = coordinate_defect(raw[i].block.polygon))
      ctx.fail(raw[i].geometry_node, raw[i].path + ".polygon",
               fmt::format("block '{}' {}", raw[i].block.name.empty() ? fmt::format("block{}", i + 1) : raw[i].block.name,
                           *defect));
  if (const auto stray = stray_block(blocks, 1e6)) {
    auto name = [&](std::size_t i) {
      return raw[i].block.name.empty() ? fmt::format("block{}", i + 1) : raw[i].block.name;
    };
    const auto& r = raw[stray->first];
    ctx.fail(r.geometry_node, r.path + ".polygon",
             raw.size() == 2
                 ? fmt::format("blocks '{}' and '{}' lie {:g} {} apart, more than 1e6 times the median block size: "
                               "are their coordinates right?",
                               name(0), name(1), stray->second, s.units.length)
                 : fmt::format("block '{}' lies {:g} {} from all the other blocks, more than 1e6 times the median "
                               "block size: are its coordinates right?",
                               name(stray->first), stray->second, s.units.length));
  }
  const double tol = geometry_tolerance(blocks);
  std::unordered_set<std::string> names;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    BlockDescription& b = raw[i].block;
    if (b.name.empty()) b.name = fmt::format("block{}", i + 1);
    if (!names.insert(b.name).second)
      ctx.fail(raw[i].node, raw[i].path + ".name", fmt::format("block name '{}' is used twice", b.name));
    if (auto defect = polygon_defect(b.polygon, tol)) {
      if (raw[i].path == "rock_mass") {
        // A generated block has no place in the file: say where it lies and why.
        double x = 0.0, y = 0.0;
        for (const Point& p : b.polygon) x += p[0], y += p[1];
        x /= static_cast<double>(b.polygon.size()), y /= static_cast<double>(b.polygon.size());
        ctx.fail(raw[i].geometry_node, "rock_mass.region",
                 fmt::format("the cut leaves a needle DDA cannot model at ({:g}, {:g}): the block there {}; two "
                             "traces cross at a grazing angle (below about 1e-7 rad) there: change the seed or the "
                             "joint sets (docs/rockmass.md, \"Limits\")",
                             x, y, *defect));
      }
      ctx.fail(raw[i].geometry_node, raw[i].path + ".polygon", fmt::format("block '{}' {}", b.name, *defect));
    }
    if (signed_area(b.polygon) < 0.0) {
      // Clockwise input: reverse to counter-clockwise. New edge k (v'_k -> v'_k+1) is
      // old edge n-2-k (mod n), so the edge joint sets follow their edges.
      const std::size_t n = b.polygon.size();
      std::vector<Point> p(n);
      std::vector<int> e(n);
      for (std::size_t k = 0; k < n; ++k) {
        p[k] = b.polygon[n - 1 - k];
        e[k] = b.edge_joint_set[(2 * n - 2 - k) % n];
      }
      b.polygon = std::move(p);
      b.edge_joint_set = std::move(e);
    }
    blocks[i] = b;
  }
  const auto overlaps = overlapping_blocks(blocks, tol);
  if (!overlaps.empty()) {
    const auto [i, j] = overlaps.front();
    ctx.fail(raw[j].node, raw[j].path,
             fmt::format("blocks '{}' and '{}' overlap at the start (blocks may touch, not overlap)",
                         blocks[i].name, blocks[j].name));
  }
  s.blocks = std::move(blocks);
}

}  // namespace

SceneDescription parse_scene(const std::string& text_in, const std::string& file) {
  Ctx ctx{file};
  YAML::Node root;
  try {
    root = load_yaml_document(text_in);  // libyaml: yaml-cpp's scanner is 8x slower on large files
  } catch (const YamlSyntaxError& e) {
    throw SceneError(file, {e.line() + 1, e.column() + 1}, "", std::string("YAML syntax: ") + e.what());
  }
  try {
    SceneDescription s;
    s.file = file;
    MapReader top(ctx, root, "", keys::top);
    s.title = file.substr(file.find_last_of('/') == std::string::npos ? 0 : file.find_last_of('/') + 1);
    if (YAML::Node v = top.find("title"); v.IsDefined()) s.title = text(ctx, v, "title");
    s.units = read_units(ctx, top.required("units", "labels {length, force, time}"));
    s.analysis = read_analysis(ctx, top.required("analysis", "time stepping: duration, dt, gravity, ..."));
    s.materials = read_materials(ctx, top.required("materials", "named block materials"),
                                 s.analysis.has_dynamic_steps());
    s.joint_sets = read_joint_sets(ctx, top.required("joint_sets", "named joint sets"),
                                   s.analysis.has_dynamic_steps());
    std::vector<RawBlock> raw;
    // With `rock_mass:`, `blocks:` is optional (blocks besides the generated ones).
    const YAML::Node rock_mass = top.find("rock_mass");
    if (!rock_mass.IsDefined() || top.has("blocks")) read_blocks(ctx, top.required("blocks", "the list of blocks"), s, raw);
    if (rock_mass.IsDefined()) read_rock_mass(ctx, rock_mass, s, raw);
    check_geometry(ctx, raw, s);
    read_points(ctx, top, s);
    if (s.analysis.penalty == 0.0) {
      // Shi's penalty p_n = k1 E with k1 = 10-100 (the seed's eq. 17): k1 = 40.
      for (const auto& m : s.materials) s.analysis.penalty = std::max(s.analysis.penalty, 40.0 * m.young_modulus);
    }
    if (s.analysis.fixed_point_stiffness == 0.0) {
      // The engine's default: 100 x the largest Young's modulus (core/model.hpp).
      for (const auto& m : s.materials)
        s.analysis.fixed_point_stiffness = std::max(s.analysis.fixed_point_stiffness, 100.0 * m.young_modulus);
    }
    return s;
  } catch (const YAML::Exception& e) {
    // Anything yaml-cpp raises past parsing is still a fault of the file.
    throw SceneError(file, {e.mark.line + 1, e.mark.column + 1}, "", e.msg);
  }
}

std::string read_scene_text(const std::string& path) {
  namespace fs = std::filesystem;
  // What is not a regular file of a sensible size is refused before it is read
  // (a folder, /dev/zero, a FIFO would hang or exhaust memory).
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw SceneError(path, {}, "", fmt::format("cannot open the scene file: {}",
                                               ec ? ec.message() : std::string("No such file or directory")));
  if (fs::is_directory(status)) throw SceneError(path, {}, "", "is a folder, not a scene file");
  if (!fs::is_regular_file(status))
    throw SceneError(path, {}, "", "is not a regular file (a device or a pipe?): give a YAML scene file");
  constexpr std::uintmax_t kMaxBytes = 64u << 20;
  const auto size = fs::file_size(path, ec);
  if (!ec && size > kMaxBytes)
    throw SceneError(path, {}, "",
                     fmt::format("is {} MB; scene files above {} MB are refused (describe large models with "
                                 "`grid` blocks)",
                                 size >> 20, kMaxBytes >> 20));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, {}, "", fmt::format("cannot open the scene file: {}", std::strerror(errno)));
  std::ostringstream buf;
  buf << in.rdbuf();
  std::string text = buf.str();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw SceneError(path, {}, "", "the scene file is empty");
  // Encoding: UTF-8 (a UTF-8 byte-order mark is dropped); UTF-16/32 and Latin-1
  // are refused at the first byte that is not UTF-8, with its line and column.
  const auto b0 = text.empty() ? 0 : static_cast<unsigned char>(text[0]);
  const auto b1 = text.size() < 2 ? 0 : static_cast<unsigned char>(text[1]);
  if ((b0 == 0xFF && b1 == 0xFE) || (b0 == 0xFE && b1 == 0xFF))
    throw SceneError(path, {1, 1}, "", "the file is UTF-16 encoded: save the scene as UTF-8");
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  int line = 1, column = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    // Well-formed UTF-8 (Unicode 15, table 3-7): no overlong forms, no surrogates, <= U+10FFFF.
    std::size_t len = c < 0x80 ? 1 : (c >= 0xC2 && c <= 0xDF) ? 2 : (c >= 0xE0 && c <= 0xEF) ? 3
                                                                  : (c >= 0xF0 && c <= 0xF4) ? 4 : 0;
    bool ok = len > 0 && i + len <= text.size();
    for (std::size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (ok && len > 2) {
      const auto c1 = static_cast<unsigned char>(text[i + 1]);
      ok = !((c == 0xE0 && c1 < 0xA0) || (c == 0xED && c1 >= 0xA0) || (c == 0xF0 && c1 < 0x90) ||
             (c == 0xF4 && c1 >= 0x90));
    }
    if (!ok || c == 0)
      throw SceneError(path, {line, column}, "",
                       c == 0 ? std::string("a NUL byte: this is not a text file (UTF-16? save the scene as UTF-8)")
                              : fmt::format("byte 0x{:02X} is not UTF-8 (a Latin-1 file?): save the scene as UTF-8", c));
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
    i += len;
  }
  // YAML indents with spaces only; yaml-cpp's message for a tab is "illegal map value".
  line = 1;
  for (std::size_t at = 0; at < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::size_t first = text.find_first_not_of(" \t", at);
    if (first != std::string::npos && first <= end) {
      // Within the line's indentation only: a search to the end of the file from every
      // line made this quadratic (100 s on a 93 000-line explicit rock mass).
      const auto indent_end = text.begin() + static_cast<std::ptrdiff_t>(first);
      const std::size_t tab = static_cast<std::size_t>(std::find(text.begin() + static_cast<std::ptrdiff_t>(at), indent_end, '\t') - text.begin());
      if (tab < first)
        throw SceneError(path, {line, static_cast<int>(tab - at) + 1}, "",
                         "a tab in the indentation: YAML indents with spaces only");
    }
    at = end + 1;
  }
  return text;
}

SceneDescription load_scene(const std::string& path) { return parse_scene(read_scene_text(path), path); }

const std::vector<SceneMapKeys>& scene_schema() {
  static const std::vector<SceneMapKeys> schema{
      {"", keys::top},
      {"units", keys::units},
      {"analysis", keys::analysis},
      {"analysis.settle", keys::settle},
      {"materials.*", keys::material},
      {"joint_sets.*", keys::joint_set},
      {"joint_sets.*.law", keys::law},
      {"blocks[*]", keys::block},
      {"blocks[*].rectangle", keys::rectangle},
      {"blocks[*].grid", keys::grid},
      {"rock_mass", keys::rock_mass},
      {"rock_mass.joint_sets[*]", keys::rock_mass_joint_set},
      {"rock_mass.traces[*]", keys::rock_mass_trace},
      {"fixed_points[*]", keys::fixed_point},
      {"loads[*]", keys::load},
      {"measurement_points[*]", keys::measurement_point},
  };
  return schema;
}

}  // namespace rheodda::scene
