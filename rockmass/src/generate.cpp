// Joint trace generation (generate.hpp).
#include "rheodda/rockmass/generate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rheodda/rockmass/random.hpp"

namespace rheodda::rockmass {

const char* spacing_distribution_name(SpacingDistribution d) {
  switch (d) {
    case SpacingDistribution::constant: return "constant";
    case SpacingDistribution::normal: return "normal";
    case SpacingDistribution::exponential: return "exponential";
    case SpacingDistribution::log_normal: return "log-normal";
  }
  return "?";
}

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

double draw_spacing(const JointSetGeneration& s, PortableRandom& rng) {
  switch (s.spacing_distribution) {
    case SpacingDistribution::constant: return s.spacing;
    case SpacingDistribution::normal:
      for (int k = 0; k < 1000; ++k) {
        const double v = s.spacing + s.spacing_deviation * rng.normal();
        if (v >= 0.01 * s.spacing) return v;
      }
      return s.spacing;
    case SpacingDistribution::exponential: return std::max(rng.exponential(s.spacing), 1e-3 * s.spacing);
    case SpacingDistribution::log_normal: return rng.log_normal(s.spacing, s.spacing_deviation);
  }
  return s.spacing;
}

/// Clips segment a-b to the box (Liang & Barsky 1984); false if nothing is left.
bool clip(Point& a, Point& b, const Box& box) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a[0] - box.x0, box.x1 - a[0], a[1] - box.y0, box.y1 - a[1]};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0.0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 >= t1) return false;
  }
  const Point a0 = a;
  a = {a0[0] + t0 * dx, a0[1] + t0 * dy};
  b = {a0[0] + t1 * dx, a0[1] + t1 * dy};
  return !(a[0] == b[0] && a[1] == b[1]);
}

}  // namespace

std::vector<Trace> generate_traces(const JointSetGeneration& set, const Box& box, std::uint64_t seed,
                                   int index) {
  if (!(set.spacing > 0.0)) throw std::invalid_argument("joint set spacing must be > 0");
  if (set.trace_length && !(*set.trace_length > 0.0 && set.gap >= 0.0))
    throw std::invalid_argument("trace_length must be > 0 and gap >= 0");
  // Each set draws from its own stream: seed mixed with the set's index (SplitMix64's constant).
  PortableRandom rng(seed ^ (0x9E3779B97F4A7C15ull * std::uint64_t(index + 1)));
  const double dip = set.dip * kDegree;
  // Direction along the traces d and the normal n: dipping right, the trace goes down as x grows.
  // dip 0 and 90 exactly horizontal and vertical (cos 90 deg is not 0 in doubles).
  const double cd = set.dip == 90.0 ? 0.0 : set.dip == 0.0 ? 1.0 : portable_cos(dip);
  const double sd = set.dip == 90.0 ? 1.0 : set.dip == 0.0 ? 0.0 : portable_sin(dip);
  const Point d = set.dips_right ? Point{cd, -sd} : Point{cd, sd};
  const Point n{-d[1], d[0]};
  // The box, a little enlarged, projected on n and d.
  const double margin = 1e-3 * std::max(box.x1 - box.x0, box.y1 - box.y0);
  const Box big{box.x0 - margin, box.y0 - margin, box.x1 + margin, box.y1 + margin};
  double tmin = 1e300, tmax = -1e300, umin = 1e300, umax = -1e300;
  for (const Point c : {Point{big.x0, big.y0}, Point{big.x1, big.y0}, Point{big.x1, big.y1}, Point{big.x0, big.y1}}) {
    const double t = n[0] * c[0] + n[1] * c[1], u = d[0] * c[0] + d[1] * c[1];
    tmin = std::min(tmin, t), tmax = std::max(tmax, t), umin = std::min(umin, u), umax = std::max(umax, u);
  }
  // Line positions along n.
  std::vector<double> lines;
  const std::size_t kMaxLines = 10'000'000;
  if (set.origin) {
    const double t0 = n[0] * (*set.origin)[0] + n[1] * (*set.origin)[1];
    for (double t = t0; t <= tmax && lines.size() < kMaxLines; t += draw_spacing(set, rng))
      if (t >= tmin) lines.push_back(t);
    for (double t = t0 - draw_spacing(set, rng); t >= tmin && lines.size() < kMaxLines; t -= draw_spacing(set, rng))
      if (t <= tmax) lines.push_back(t);
  } else {
    for (double t = tmin + rng.uniform() * draw_spacing(set, rng); t <= tmax && lines.size() < kMaxLines;
         t += draw_spacing(set, rng))
      lines.push_back(t);
  }
  if (lines.size() >= kMaxLines)
    throw std::invalid_argument("the spacing gives more than 1e7 lines across the region");
  std::vector<Trace> out;
  // One line: its traces from u0 to u1, turned together about the line's middle by
  // `delta` [rad] (so that the traces of a line stay on one straight line and never
  // cross each other at a grazing angle).
  double c = 1.0, sn = 0.0;
  Point m{0.0, 0.0};
  auto add = [&](double t, double u0, double u1) {
    Point a{n[0] * t + d[0] * u0, n[1] * t + d[1] * u0};
    Point b{n[0] * t + d[0] * u1, n[1] * t + d[1] * u1};
    if (sn != 0.0) {
      auto turn = [&](const Point& p) {
        const double x = p[0] - m[0], y = p[1] - m[1];
        return Point{m[0] + c * x - sn * y, m[1] + sn * x + c * y};
      };
      a = turn(a), b = turn(b);
    }
    if (clip(a, b, big)) out.push_back({a, b, set.tag});
    if (out.size() > kMaxTraces)
      throw std::invalid_argument(fmt::format("the set draws more than {:g} traces across the region: a larger "
                                              "spacing, longer traces or a smaller gap",
                                              static_cast<double>(kMaxTraces)));
  };
  const double umid = 0.5 * (umin + umax);
  for (const double t : lines) {
    c = 1.0, sn = 0.0;
    if (set.dip_spread > 0.0) {
      const double delta = set.dip_spread * kDegree * rng.normal();
      c = portable_cos(delta), sn = portable_sin(delta);
      m = {n[0] * t + d[0] * umid, n[1] * t + d[1] * umid};
    }
    // A turned line must still cross the box: make it longer by the box's extent.
    const double extra = set.dip_spread > 0.0 ? (umax - umin) : 0.0;
    if (!set.trace_length) {
      add(t, umin - extra, umax + extra);  // persistent: across the box
      continue;
    }
    const double period = *set.trace_length + set.gap;
    for (double u = umin - extra - rng.uniform() * period; u < umax + extra; u += period)
      add(t, u, u + *set.trace_length);
  }
  return out;
}

}  // namespace rheodda::rockmass
