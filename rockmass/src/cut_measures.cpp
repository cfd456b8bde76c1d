// What the cutter measures without CGAL (cut.hpp): block and region areas with the
// bound rounding puts on their difference (block_area_check), and the estimate of a
// cut's size and memory from the traces alone, before cutting (estimate_cut).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "rheodda/rockmass/cut.hpp"

namespace rheodda::rockmass {

namespace {
/// Shoelace area about the first vertex and the sum of its terms' magnitudes [length^2].
std::pair<double, double> shoelace(const std::vector<Point>& p) {
  double a = 0.0, magnitude = 0.0;
  if (p.size() < 3) return {0.0, 0.0};
  const Point& o = p[0];
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double ux = p[i][0] - o[0], uy = p[i][1] - o[1];
    const double vx = p[i + 1][0] - o[0], vy = p[i + 1][1] - o[1];
    a += ux * vy - vx * uy;
    magnitude += std::abs(ux * vy) + std::abs(vx * uy);
  }
  return {0.5 * a, 0.5 * magnitude};
}

/// Neumaier's compensated sum (Higham, "Accuracy and Stability of Numerical
/// Algorithms", 2nd ed., sec. 4.3): error <= 2 eps |sum| + O(n eps^2) sum |x_i|.
struct CompensatedSum {
  double sum = 0.0, compensation = 0.0;
  void add(double x) {
    const double t = sum + x;
    compensation += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double value() const { return sum + compensation; }
};
}  // namespace

double polygon_area(const std::vector<Point>& p) { return shoelace(p).first; }

bool AreaCheck::ok() const { return std::abs(block_sum - region_area) <= bound; }

AreaCheck block_area_check(const std::vector<Block>& blocks, const Region& region) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  AreaCheck c;
  CompensatedSum sum;
  double bound = 0.0;
  for (const Block& b : blocks) {
    const auto [area, magnitude] = shoelace(b.polygon);
    sum.add(area);
    bound += 2.0 * static_cast<double>(b.polygon.size()) * eps * magnitude;
  }
  c.block_sum = sum.value();
  // The region's area, and the vertices traces make on its boundary: each rounded to the
  // nearest double moves by at most half an ulp of its coordinates, across the edge.
  auto ring = [&](const std::vector<Point>& p) {
    const auto [area, magnitude] = shoelace(p);
    bound += 2.0 * static_cast<double>(p.size()) * eps * magnitude;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Point& u = p[i];
      const Point& v = p[(i + 1) % p.size()];
      const double coordinate = std::max({std::abs(u[0]), std::abs(u[1]), std::abs(v[0]), std::abs(v[1])});
      bound += eps * coordinate * std::hypot(v[0] - u[0], v[1] - u[1]);
    }
    return std::abs(area);
  };
  c.region_area = ring(region.outer);
  for (const auto& h : region.holes) c.region_area -= ring(h);
  c.bound = bound + 2.0 * eps * std::abs(c.block_sum) + 4.0 * eps * c.region_area;
  return c;
}

CutEstimate estimate_cut(const Region& region, const std::vector<Trace>& traces) {
  // Peak resident memory of `rheodda check` per arrangement vertex (a crossing or a
  // trace end) above the program's own 20 MB: 1.6 to 2.0 kB measured on two persistent
  // sets cut into 1e4 to 1.6e5 blocks (scripts/rockmass-scaling.sh), rounded up.
  constexpr double kBytesPerVertex = 2.1e3, kBaseBytes = 20e6;
  constexpr double kPi = 3.14159265358979323846;
  // The traces' lengths by direction, in 1-degree bins of [0, 180).
  constexpr int kBins = 180;
  std::array<double, kBins> length{};
  double x0 = region.outer[0][0], x1 = x0, y0 = region.outer[0][1], y1 = y0;
  auto grow = [&](const Point& p) {
    x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  };
  for (const Point& p : region.outer) grow(p);
  const double region_box = (x1 - x0) * (y1 - y0);
  for (const Trace& t : traces) {
    const double dx = t.b[0] - t.a[0], dy = t.b[1] - t.a[1];
    const double l = std::hypot(dx, dy);
    if (!(l > 0.0) || !std::isfinite(l)) continue;
    double angle = std::atan2(dy, dx);
    if (angle < 0.0) angle += kPi;
    length[static_cast<std::size_t>(std::min(kBins - 1, static_cast<int>(angle / kPi * kBins)))] += l;
    grow(t.a), grow(t.b);
  }
  const double box = (x1 - x0) * (y1 - y0);
  CutEstimate e;
  if (!(box > 0.0)) return e;
  for (int i = 0; i < kBins; ++i)
    for (int j = i + 1; j < kBins; ++j)
      if (length[i] > 0.0 && length[j] > 0.0)
        e.crossings += length[i] * length[j] * std::abs(std::sin((j - i) * kPi / kBins)) / box;
  const double vertices = e.crossings + 2.0 * static_cast<double>(traces.size());
  double area = std::abs(polygon_area(region.outer));
  for (const auto& h : region.holes) area -= std::abs(polygon_area(h));
  // Faces of the arrangement (Euler: about one per crossing, plus one per trace), in
  // the share of the box the region covers.
  e.pieces = (e.crossings + static_cast<double>(traces.size()) + 1.0) * std::min(1.0, area / std::max(region_box, box));
  e.bytes = kBaseBytes + kBytesPerVertex * vertices;
  return e;
}

}  // namespace rheodda::rockmass
