#include "rheodda/scene/geometry.hpp"

#include "rheodda/core/defaults.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "rheodda/rockmass/cut.hpp"

namespace rheodda::scene {
namespace {

double cross(const Point& o, const Point& a, const Point& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

double dist(const Point& a, const Point& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

double point_segment_distance(const Point& p, const Point& a, const Point& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

/// Distance between segments ab and cd (0 if they intersect).
double segment_distance(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 0.0;
  return std::min({point_segment_distance(a, c, d), point_segment_distance(b, c, d),
                   point_segment_distance(c, a, b), point_segment_distance(d, a, b)});
}

/// Segments ab and cd cross at a point inside both, each end clear of the other line by > tol.
bool proper_crossing(const Point& a, const Point& b, const Point& c, const Point& d, double tol) {
  const double lab = dist(a, b), lcd = dist(c, d);
  if (lab <= 0.0 || lcd <= 0.0) return false;
  const double d1 = cross(a, b, c) / lab, d2 = cross(a, b, d) / lab;
  const double d3 = cross(c, d, a) / lcd, d4 = cross(c, d, b) / lcd;
  return ((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) &&
         ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol));
}

bool inside_crossing(const std::vector<Point>& poly, const Point& p) {
  bool in = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point& a = poly[i];
    const Point& b = poly[j];
    if ((a[1] > p[1]) != (b[1] > p[1])) {
      const double x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
      if (p[0] < x) in = !in;
    }
  }
  return in;
}

/// Inside and farther than tol from the boundary.
bool strictly_inside(const std::vector<Point>& poly, const Point& p, double tol) {
  return inside_crossing(poly, p) && boundary_distance(poly, p) > tol;
}

struct Box {
  double x0, y0, x1, y1;
};
Box bounding_box(const std::vector<Point>& poly) {
  Box b{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
        std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for (const auto& p : poly) {
    b.x0 = std::min(b.x0, p[0]);
    b.y0 = std::min(b.y0, p[1]);
    b.x1 = std::max(b.x1, p[0]);
    b.y1 = std::max(b.y1, p[1]);
  }
  return b;
}

/// Calls f(i, j), i < j, once for each pair of blocks whose boxes, enlarged by
/// `margin`, overlap. Boxes are binned in a uniform grid (cell = median box size,
/// at most ~4N cells along the model's larger side), and a pair is reported by the
/// cell holding the lower-left corner of the two boxes' overlap: O(N) for blocks
/// of similar size, never all N^2 pairs.
template <class F>
void for_near_pairs(const std::vector<BlockDescription>& blocks, double margin, F&& f) {
  const std::size_t n = blocks.size();
  if (n < 2) return;
  std::vector<Box> boxes;
  boxes.reserve(n);
  Box all{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
          std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  std::vector<double> sizes;
  for (const auto& b : blocks) {
    Box x = bounding_box(b.polygon);
    x = {x.x0 - margin, x.y0 - margin, x.x1 + margin, x.y1 + margin};
    boxes.push_back(x);
    sizes.push_back(std::max(x.x1 - x.x0, x.y1 - x.y0));
    all = {std::min(all.x0, x.x0), std::min(all.y0, x.y0), std::max(all.x1, x.x1), std::max(all.y1, x.y1)};
  }
  std::nth_element(sizes.begin(), sizes.begin() + n / 2, sizes.end());
  const double extent = std::max(all.x1 - all.x0, all.y1 - all.y0);
  double cell = std::max(sizes[n / 2], extent / (4.0 * double(n)));
  if (!(cell > 0.0)) cell = 1.0;
  // A few large blocks (a base under a wall) must not cover a huge number of cells.
  for (;;) {
    double covered = 0.0;
    for (const Box& b : boxes) covered += (std::floor((b.x1 - b.x0) / cell) + 2) * (std::floor((b.y1 - b.y0) / cell) + 2);
    if (covered <= 16.0 * double(n) + 64.0) break;
    cell *= 2.0;
  }
  auto index = [&](double v, double lo) {
    return static_cast<long long>(std::min(std::floor((v - lo) / cell), 4.0 * double(n) + 1.0));
  };
  std::unordered_map<long long, std::vector<int>> grid;
  const long long stride = static_cast<long long>(4 * n + 4);
  for (std::size_t i = 0; i < n; ++i) {
    const Box& b = boxes[i];
    for (long long cx = index(b.x0, all.x0); cx <= index(b.x1, all.x0); ++cx)
      for (long long cy = index(b.y0, all.y0); cy <= index(b.y1, all.y0); ++cy)
        grid[cx * stride + cy].push_back(static_cast<int>(i));
  }
  for (const auto& [key, items] : grid)
    for (std::size_t a = 0; a < items.size(); ++a)
      for (std::size_t c = a + 1; c < items.size(); ++c) {
        const Box& p = boxes[items[a]];
        const Box& q = boxes[items[c]];
        if (p.x0 > q.x1 || q.x0 > p.x1 || p.y0 > q.y1 || q.y0 > p.y1) continue;
        const long long owner = index(std::max(p.x0, q.x0), all.x0) * stride + index(std::max(p.y0, q.y0), all.y0);
        if (owner != key) continue;
        f(std::min(items[a], items[c]), std::max(items[a], items[c]));
      }
}

}  // namespace

double signed_area(const std::vector<Point>& polygon) {
  return rockmass::polygon_area(polygon);  // about the first vertex: exact enough at map coordinates
}

std::optional<std::string> coordinate_defect(const std::vector<Point>& polygon) {
  // Coordinates whose products (areas, cross products) would overflow a double.
  for (std::size_t i = 0; i < polygon.size(); ++i)
    if (!(std::abs(polygon[i][0]) < 1e150 && std::abs(polygon[i][1]) < 1e150))
      return fmt::format("has vertex {} at ({:g}, {:g}): coordinates beyond 1e150 overflow double-precision "
                         "areas (change the length unit)",
                         i, polygon[i][0], polygon[i][1]);
  return std::nullopt;
}

std::optional<std::string> polygon_defect(const std::vector<Point>& polygon, double tol) {
  const std::size_t n = polygon.size();
  if (n < 3) return fmt::format("has {} vertices; a polygon needs at least 3", n);
  if (auto c = coordinate_defect(polygon)) return c;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (const double d = dist(polygon[i], polygon[j]); d <= tol) {
        if (d == 0.0)
          return j == n - 1 && i == 0
                     ? std::string("repeats its first vertex at the end (list each vertex once)")
                     : fmt::format("has vertices {} and {} at the same place", i, j);
        return fmt::format("has vertices {} and {} only {:g} apart, within the geometric tolerance {:g} "
                           "(1e-9 of the model size): a sliver or a needle that thin cannot be modelled",
                           i, j, d, tol);
      }
  auto crossing = [&]() -> std::optional<std::string> {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 2; j < n; ++j) {
        if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
        if (segment_distance(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n]) <= tol)
          return fmt::format("is not simple: edges {} and {} cross or touch", i, j);
      }
    return std::nullopt;
  };
  const Box box = bounding_box(polygon);
  const double size = std::hypot(box.x1 - box.x0, box.y1 - box.y0);
  if (std::abs(signed_area(polygon)) <= tol * size) {
    // Zero area: all the vertices on one line (within tol of the line through the two
    // farthest apart), or a bow-tie whose two halves cancel: say which.
    std::size_t far_a = 0, far_b = 1;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (dist(polygon[i], polygon[j]) > dist(polygon[far_a], polygon[far_b])) far_a = i, far_b = j;
    bool on_a_line = true;
    for (std::size_t i = 0; i < n && on_a_line; ++i)
      on_a_line = point_segment_distance(polygon[i], polygon[far_a], polygon[far_b]) <= tol;
    if (on_a_line) return std::string("is degenerate: its area is zero (its vertices lie on one line)");
    if (auto c = crossing()) return c;
    return std::string("is degenerate: its area is zero");
  }
  for (std::size_t i = 0; i < n; ++i) {
    // Adjacent edges folding back onto each other (a spike of zero width).
    const Point& a = polygon[(i + n - 1) % n];
    const Point& b = polygon[i];
    const Point& c = polygon[(i + 1) % n];
    const double ab = dist(a, b), bc = dist(b, c);
    const double dot = (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]);
    if (std::abs(cross(a, b, c)) <= tol * std::max(ab, bc) && dot < 0.0)
      return fmt::format("folds back on itself at vertex {}", i);
  }
  return crossing();
}

std::optional<std::pair<int, double>> stray_block(const std::vector<BlockDescription>& blocks, double ratio) {
  const std::size_t n = blocks.size();
  if (n < 2) return std::nullopt;
  std::vector<Box> box(n);
  std::vector<double> size(n);
  for (std::size_t i = 0; i < n; ++i) {
    box[i] = bounding_box(blocks[i].polygon);
    size[i] = std::hypot(box[i].x1 - box[i].x0, box[i].y1 - box[i].y0);
  }
  std::vector<double> sorted = size;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(n / 2), sorted.end());
  const double median = sorted[n / 2];
  // Union of the boxes of all blocks but i, from prefix and suffix unions: O(n).
  auto unite = [](Box a, const Box& b) {
    a.x0 = std::min(a.x0, b.x0), a.y0 = std::min(a.y0, b.y0);
    a.x1 = std::max(a.x1, b.x1), a.y1 = std::max(a.y1, b.y1);
    return a;
  };
  const Box empty{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                  std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  std::vector<Box> pre(n + 1, empty), suf(n + 1, empty);
  for (std::size_t i = 0; i < n; ++i) pre[i + 1] = unite(pre[i], box[i]);
  for (std::size_t i = n; i-- > 0;) suf[i] = unite(suf[i + 1], box[i]);
  for (std::size_t i = 0; i < n; ++i) {
    const Box rest = unite(pre[i], suf[i + 1]);
    const double dx = std::max({0.0, rest.x0 - box[i].x1, box[i].x0 - rest.x1});
    const double dy = std::max({0.0, rest.y0 - box[i].y1, box[i].y0 - rest.y1});
    const double gap = std::hypot(dx, dy);
    if (gap > ratio * median) return std::make_pair(static_cast<int>(i), gap);
  }
  return std::nullopt;
}

double boundary_distance(const std::vector<Point>& polygon, const Point& p) {
  double d = std::numeric_limits<double>::max();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i)
    d = std::min(d, point_segment_distance(p, polygon[i], polygon[(i + 1) % n]));
  return d;
}

bool contains(const std::vector<Point>& polygon, const Point& p, double tol) {
  return inside_crossing(polygon, p) || boundary_distance(polygon, p) <= tol;
}

Point interior_point(const std::vector<Point>& polygon) {
  const std::size_t n = polygon.size();
  const double orient = signed_area(polygon) >= 0.0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = polygon[(i + n - 1) % n];
    const Point& b = polygon[i];
    const Point& c = polygon[(i + 1) % n];
    if (orient * cross(a, b, c) <= 0.0) continue;  // reflex or straight vertex
    const std::vector<Point> tri{a, b, c};
    bool ear = true;
    for (std::size_t k = 0; k < n && ear; ++k) {
      if (k == i || k == (i + 1) % n || k == (i + n - 1) % n) continue;
      if (contains(tri, polygon[k], 0.0)) ear = false;
    }
    if (ear) return {(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0};
  }
  return polygon.front();  // unreachable for a simple polygon (two-ears theorem)
}

bool interiors_overlap(const std::vector<Point>& a, const std::vector<Point>& b, double tol) {
  const std::size_t na = a.size(), nb = b.size();
  for (std::size_t i = 0; i < na; ++i)
    for (std::size_t j = 0; j < nb; ++j)
      if (proper_crossing(a[i], a[(i + 1) % na], b[j], b[(j + 1) % nb], tol)) return true;
  auto probes_inside = [tol](const std::vector<Point>& p, const std::vector<Point>& q) {
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point& u = p[i];
      const Point& v = p[(i + 1) % n];
      if (strictly_inside(q, u, tol)) return true;
      if (strictly_inside(q, {0.5 * (u[0] + v[0]), 0.5 * (u[1] + v[1])}, tol)) return true;
    }
    return strictly_inside(q, interior_point(p), tol);
  };
  return probes_inside(a, b) || probes_inside(b, a);
}

std::vector<std::pair<int, int>> overlapping_blocks(const std::vector<BlockDescription>& blocks,
                                                    double tol) {
  std::vector<std::pair<int, int>> out;
  for_near_pairs(blocks, 0.0, [&](int i, int j) {
    if (interiors_overlap(blocks[i].polygon, blocks[j].polygon, tol)) out.emplace_back(i, j);
  });
  std::sort(out.begin(), out.end());
  return out;
}

ContactEstimate estimate_contacts(const std::vector<BlockDescription>& blocks, double distance) {
  ContactEstimate est;
  for_near_pairs(blocks, distance, [&](int i, int j) {
    // Contact points: vertices of one block near the other's boundary; a vertex
    // meeting a vertex is one contact (Shi's vertex-vertex), hence the merge.
    std::vector<Point> points;
    auto collect = [&](const std::vector<Point>& p, const std::vector<Point>& q) {
      for (const auto& v : p) {
        if (boundary_distance(q, v) > distance) continue;
        bool seen = false;
        for (const auto& w : points) seen = seen || dist(v, w) <= distance;
        if (!seen) points.push_back(v);
      }
    };
    collect(blocks[i].polygon, blocks[j].polygon);
    collect(blocks[j].polygon, blocks[i].polygon);
    if (!points.empty()) {
      ++est.block_pairs;
      est.vertex_edge += static_cast<int>(points.size());
    }
  });
  return est;
}

double half_model_size(const std::vector<BlockDescription>& blocks) {
  if (blocks.empty()) return 0.0;
  Box all = bounding_box(blocks.front().polygon);
  for (const auto& b : blocks) {
    const Box x = bounding_box(b.polygon);
    all = {std::min(all.x0, x.x0), std::min(all.y0, x.y0), std::max(all.x1, x.x1),
           std::max(all.y1, x.y1)};
  }
  return core::half_model_size(all.x1 - all.x0, all.y1 - all.y0);
}

}  // namespace rheodda::scene
