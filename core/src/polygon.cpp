// Polygon integrals by the triangle fan: for the triangle (0, p, q) with
// c = p.x q.y - q.x p.y (twice its signed area),
//   S   = c/2,                         Sx  = c (p.x + q.x)/6,
//   Sy  = c (p.y + q.y)/6,             Sxx = c (p.x^2 + p.x q.x + q.x^2)/12,
//   Syy = c (p.y^2 + p.y q.y + q.y^2)/12,
//   Sxy = c (2 p.x p.y + p.x q.y + q.x p.y + 2 q.x q.y)/24
// (Shi 1988, simplex integration; the polygon is the signed sum of its fan).
#include "rheodda/core/polygon.hpp"

#include <algorithm>
#include <cmath>

namespace rheodda::core {

namespace {

// Fan sums with coordinates measured from o (no copy of the vertices).
PolygonIntegrals integrals_about(std::span<const Vec2> v, const Vec2& o) {
  PolygonIntegrals r;
  const std::size_t n = v.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 p = v[k] - o;
    const Vec2 q = v[(k + 1) % n] - o;
    const double c = p.x() * q.y() - q.x() * p.y();
    r.S += c;
    r.Sx += c * (p.x() + q.x());
    r.Sy += c * (p.y() + q.y());
    r.Sxx += c * (p.x() * p.x() + p.x() * q.x() + q.x() * q.x());
    r.Syy += c * (p.y() * p.y() + p.y() * q.y() + q.y() * q.y());
    r.Sxy += c * (2.0 * p.x() * p.y() + p.x() * q.y() + q.x() * p.y() + 2.0 * q.x() * q.y());
  }
  r.S /= 2.0;
  r.Sx /= 6.0;
  r.Sy /= 6.0;
  r.Sxx /= 12.0;
  r.Syy /= 12.0;
  r.Sxy /= 24.0;
  return r;
}

}  // namespace

PolygonIntegrals polygon_integrals(std::span<const Vec2> v) { return integrals_about(v, Vec2::Zero()); }

PolygonIntegrals central_integrals(std::span<const Vec2> v, Vec2* centroid) {
  // Two passes: a rough centre (first vertex) removes the far-origin
  // cancellation, then the exact centroid of the shifted polygon.
  const Vec2 o = v.empty() ? Vec2::Zero() : v[0];
  const Vec2 c = o + integrals_about(v, o).centroid();
  if (centroid) *centroid = c;
  return integrals_about(v, c);
}

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

// Closed segments ab and cd share a point (exact orientation signs).
bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  if (d1 == 0 && on_segment(a, b, c)) return true;
  if (d2 == 0 && on_segment(a, b, d)) return true;
  if (d3 == 0 && on_segment(c, d, a)) return true;
  if (d4 == 0 && on_segment(c, d, b)) return true;
  return false;
}

}  // namespace

bool is_simple_polygon(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  if (n < 3) return false;
  for (std::size_t k = 0; k < n; ++k)
    if (v[k] == v[(k + 1) % n]) return false;  // zero-length edge
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % n];
    // Adjacent edge folding back onto this one (collinear, opposite direction).
    const Vec2& c = v[(i + 2) % n];
    if (cross(b - a, c - b) == 0.0 && (b - a).dot(c - b) < 0.0) return false;
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing vertex
      if (segments_touch(a, b, v[j], v[(j + 1) % n])) return false;
    }
  }
  return true;
}

bool normalise_orientation(std::vector<Vec2>& vertices, std::vector<int>& edge_joint_set) {
  if (polygon_integrals(vertices).S >= 0.0) return false;
  const std::size_t n = vertices.size();
  std::reverse(vertices.begin(), vertices.end());
  if (edge_joint_set.size() == n) {
    // New vertex j = old vertex n-1-j, so new edge j runs old n-1-j -> n-2-j,
    // i.e. old edge (n-2-j) mod n traversed backwards.
    std::vector<int> old = edge_joint_set;
    for (std::size_t j = 0; j < n; ++j) edge_joint_set[j] = old[(2 * n - 2 - j) % n];
  }
  return true;
}

}  // namespace rheodda::core
