// Joint traces from joint-set statistics, as rock engineers describe a rock mass
// (ISRM 1978 "Suggested methods for the quantitative description of
// discontinuities": orientation, spacing, persistence; Shi's DC program, UDEC's
// `jset`). A 2D section: a joint set is a family of parallel lines (dip, dip
// direction in the section), spaced normal to themselves by a random spacing;
// along each line traces of a given length alternate with gaps (persistence =
// trace_length / (trace_length + gap)). Plain doubles, no geometry library: the
// cutter (cut.hpp) intersects the traces exactly.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rheodda::rockmass {

using Point = std::array<double, 2>;  ///< (x, y) [length]

/// The edge tag of the region's boundary (a joint set's tag is its index, >= 0).
inline constexpr int kBoundaryTag = -1;

/// A straight joint trace from `a` to `b` carrying the tag of its joint set.
struct Trace {
  Point a{0.0, 0.0};  ///< [length]
  Point b{0.0, 0.0};  ///< [length]
  int tag = 0;        ///< joint set (>= 0)
};

enum class SpacingDistribution { constant, normal, exponential, log_normal };

/// "constant", "normal", "exponential", "log-normal".
const char* spacing_distribution_name(SpacingDistribution d);

/// One joint set's statistics in the section.
struct JointSetGeneration {
  int tag = 0;               ///< carried by every trace and edge of the set (the scene's joint set index)
  double dip = 0.0;          ///< angle of the traces below the horizontal [deg], in [0, 90]
  bool dips_right = true;    ///< dip_direction: the traces descend towards +x (right) or -x (left)
  double spacing = 1.0;      ///< mean spacing, measured normal to the traces [length], > 0
  SpacingDistribution spacing_distribution = SpacingDistribution::constant;
  double spacing_deviation = 0.0;  ///< standard deviation of the spacing (normal, log-normal) [length]
  /// Length of each trace along a line [length]; nullopt: persistent (every line crosses the region).
  std::optional<double> trace_length;
  double gap = 0.0;          ///< rock bridge between two traces of a line [length] (with trace_length)
  double dip_spread = 0.0;   ///< standard deviation of each line's dip about `dip` [deg]
  /// A point one line passes through [length]; nullopt: the first line's offset is random.
  std::optional<Point> origin;
};

/// Axis-aligned box [length].
struct Box {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};

/// Most traces a rock mass may draw (all its sets together): beyond, generate_traces
/// throws before its memory and time run away (a gap of millimetres along a line of
/// kilometres would draw 1e10 traces).
inline constexpr std::size_t kMaxTraces = 2'000'000;

/// The traces of `set` over `box` (clipped to it), drawn from std::mt19937_64
/// seeded with `seed` mixed with the set's position `index` in the scene (so
/// adding a set leaves the others' traces unchanged).
///
/// Lines: positions along the normal n = (sin dip, cos dip) (dipping right) from
/// the box's lowest projection (or through `origin`), successive gaps drawn from
/// the spacing distribution; a normal spacing below 1 % of the mean is drawn
/// again (the spacing is positive). Traces along each line start at a random
/// phase in [0, trace_length + gap). Each line, with all its traces, is turned
/// about its middle by a normal deviate of standard deviation dip_spread (traces
/// of one line stay collinear: turned one by one they would cross each other at
/// grazing angles and leave needles). Throws std::invalid_argument beyond kMaxTraces.
std::vector<Trace> generate_traces(const JointSetGeneration& set, const Box& box, std::uint64_t seed,
                                   int index);

}  // namespace rheodda::rockmass
