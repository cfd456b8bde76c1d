// The load terms of the water in the joints (water.hpp; docs/reference/water.md).
//
// Along a straight edge x(s) = a + s (b - a), s in [0, 1], of a block whose
// interior lies to the left of a -> b, the outward normal times the edge length
// is nL = (b_y - a_y, -(b_x - a_x)), and the pressure's traction -p n does, per
// unit of s, the work of the force -p(s) nL. Its six DDA load terms (Shi 1988:
// a point load f at x adds T(x)^T f to the block's right-hand side, T the
// first-order displacement matrix of eq. 27 of the seed) summed along the edge:
//   F = int_0^1 T(x(s))^T (-p(s)) nL ds,   p(s) = gamma_w max(0, g(s)),
//   g(s) = h(x(s), t) - y(s)                                      (hydrostatic head)
// g is linear in s between the x of the surfaces' points, so the edge is split
// there and where g changes sign; on each piece p is linear and T linear, the
// integrand quadratic, and Simpson's rule integrates it exactly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/model.hpp"
#include "rheodda/core/property_specs.hpp"
#include "rheodda/core/water.hpp"

namespace rheodda::core {

namespace {

/// Height of one surface at x: linear between its points, held beyond its ends [length].
double surface_height(const WaterSurface& s, double x) {
  const auto& p = s.points;
  if (x <= p.front().x()) return p.front().y();
  if (x >= p.back().x()) return p.back().y();
  const auto it = std::upper_bound(p.begin(), p.end(), x, [](double v, const Vec2& q) { return v < q.x(); });
  const Vec2& r = *it;
  const Vec2& l = *(it - 1);
  return l.y() + (r.y() - l.y()) * (x - l.x()) / (r.x() - l.x());
}

/// The surface at time t: (1 - weight) first + weight second (second null:
/// first alone), piecewise linear in time between the samples around t.
struct SurfaceAt {
  const WaterSurface* first = nullptr;
  const WaterSurface* second = nullptr;
  double weight = 0.0;
  double height(double x) const {
    const double h = surface_height(*first, x);
    return second ? (1.0 - weight) * h + weight * surface_height(*second, x) : h;
  }
};

SurfaceAt surface_at(const Water& w, double t) {
  const auto& h = w.history;
  if (t <= h.front().time) return {&h.front(), nullptr, 0.0};
  if (t >= h.back().time) return {&h.back(), nullptr, 0.0};
  const auto it = std::upper_bound(h.begin(), h.end(), t, [](double v, const WaterSurface& s) { return v < s.time; });
  const WaterSurface& r = *it;
  const WaterSurface& l = *(it - 1);
  return {&l, &r, (t - l.time) / (r.time - l.time)};
}

}  // namespace

double water_level_at(const Water& w, double x, double t) { return surface_at(w, t).height(x); }

double water_pressure(const Water& w, const Vec2& point, double t) {
  // p = gamma_w (h - y) below the surface (hydrostatic), 0 above [stress]; no water: 0.
  if (!w.active()) return 0.0;
  return w.unit_weight * std::max(0.0, water_level_at(w, point.x(), t) - point.y());
}

Vec6 water_edge_load(const Water& w, const Vec2& a, const Vec2& b, const Vec2& centroid, double t) {
  const SurfaceAt surf = surface_at(w, t);
  const Vec2 e = b - a;
  const Vec2 nL(e.y(), -e.x());  // outward normal x edge length [length]
  // Pieces of [0, 1] on which the head g(s) is linear: split at the x of every
  // point of the surfaces in force.
  std::vector<double> all{0.0, 1.0};
  auto add_cuts = [&](const WaterSurface* s) {
    if (!s || e.x() == 0.0) return;
    for (const Vec2& q : s->points)
      if (const double c = (q.x() - a.x()) / e.x(); c > 0.0 && c < 1.0) all.push_back(c);
  };
  add_cuts(surf.first);
  add_cuts(surf.second);
  std::sort(all.begin(), all.end());
  auto head = [&](double s) {
    const Vec2 x = a + s * e;
    return surf.height(x.x()) - x.y();  // [length]
  };
  // Simpson on [s0, s1] where g is linear and >= 0: exact for the quadratic
  // integrand T(x(s))^T (-gamma_w g(s)) nL.
  Vec6 F = Vec6::Zero();
  auto simpson = [&](double s0, double g0, double s1, double g1) {
    if (!(s1 > s0)) return;
    auto f = [&](double s, double g) -> Vec6 {
      return contact::displacement_matrix(centroid, a + s * e).transpose() * (-w.unit_weight * g * nL);
    };
    F += (s1 - s0) / 6.0 * (f(s0, g0) + 4.0 * f(0.5 * (s0 + s1), 0.5 * (g0 + g1)) + f(s1, g1));
  };
  double s0 = all.front(), g0 = head(s0);
  for (std::size_t k = 1; k < all.size(); ++k) {
    const double s1 = all[k];
    if (!(s1 > s0)) continue;
    const double g1 = head(s1);
    if (g0 >= 0.0 && g1 >= 0.0) {
      simpson(s0, g0, s1, g1);
    } else if (g0 > 0.0 || g1 > 0.0) {
      // The edge crosses the surface at g = 0: only the wet part is loaded.
      const double sr = s0 + (s1 - s0) * g0 / (g0 - g1);
      if (g0 > 0.0) simpson(s0, g0, sr, 0.0);
      else simpson(sr, 0.0, s1, g1);
    }
    s0 = s1;
    g0 = g1;
  }
  return F;
}

Vec6 water_block_load(const Water& w, std::span<const Vec2> vertices, const Vec2& centroid, double t) {
  Vec6 F = Vec6::Zero();
  const std::size_t n = vertices.size();
  for (std::size_t k = 0; k < n; ++k) F += water_edge_load(w, vertices[k], vertices[(k + 1) % n], centroid, t);
  return F;
}

double next_water_break(const Water& w, double after) {
  double t = std::numeric_limits<double>::infinity();
  for (const WaterSurface& s : w.history)
    if (s.time > after) t = std::min(t, s.time);
  return t;
}

void validate_water(const Water& w, double x_min, double x_max) {
  check_declared(water_specs(), static_cast<const WaterProperties&>(w), std::string("water"));  // property_specs.hpp
  if (w.history.empty()) throw ModelError("water.history", "needs at least one surface");
  for (std::size_t k = 0; k < w.history.size(); ++k) {
    const WaterSurface& s = w.history[k];
    const ModelEntry key{"water.history", k};
    if (!std::isfinite(s.time)) throw ModelError(key, "time", "must be finite");
    if (k > 0 && !(s.time > w.history[k - 1].time))
      throw ModelError(key, "time", "times must increase strictly");
    if (s.points.size() < 2) throw ModelError(key, "points", "a surface needs at least 2 points");
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      if (!s.points[i].allFinite()) throw ModelError(key, "points", "coordinates must be finite");
      if (i > 0 && !(s.points[i].x() > s.points[i - 1].x()))
        throw ModelError(key, "points", "x must increase strictly along the surface");
    }
    // Spanning is the user's intent checked (a surface is held level beyond its ends);
    // blocks that moved by a billionth of the model past a surface's end still pass.
    const double slack = 1e-9 * std::max(1.0, x_max - x_min);
    if (s.points.front().x() > x_min + slack || s.points.back().x() < x_max - slack)
      throw ModelError(key, "points", "the surface does not span the blocks' x-range [" + std::to_string(x_min) +
                                            ", " + std::to_string(x_max) + "]");
  }
}

}  // namespace rheodda::core
