// Water in the joints (docs/reference/water.md): a phreatic surface, constant or
// piecewise linear in time, whose hydrostatic pressure loads every block edge
// below it.
//
// The pressure at a point (x, y) at time t is (Terzaghi's pore pressure of a
// hydrostatic water table; Hoek & Bray, Rock Slope Engineering, ch. 6)
//   p = gamma_w (h(x, t) - y)   where positive, 0 above the surface,
// h the surface's height at x. It acts on every block edge below the surface as
// the traction -p n (n the edge's outward normal), integrated exactly along the
// straight edge into the block's six DDA load terms (Shi 1988, the point-load
// term T^T f summed along the edge; water_loads.cpp). Both faces of a joint are
// loaded, so the contact springs between them carry the effective normal force
// N' = N - U (Terzaghi), which friction, cohesion and the creep laws see; a
// block wholly below the surface gets the buoyancy gamma_w A (Archimedes).
//
// A model without water (Water::history empty) computes nothing of this.
#pragma once

#include <Eigen/Dense>
#include <span>
#include <vector>

namespace rheodda::core {

using Vec2 = Eigen::Vector2d;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// The phreatic surface at one time.
struct WaterSurface {
  double time = 0.0;          ///< [time]
  /// Polyline (x, h): >= 2 points, x strictly increasing [length]; between the
  /// points h is linear in x, beyond the first and the last point it is held
  /// level at their heights. A level is two points at the same height.
  std::vector<Vec2> points;
};

/// The water's properties, declared in core/property_specs.hpp (the scene's keys of the
/// same names, whose WaterDescription is one).
struct WaterProperties {
  double unit_weight = 0.0;  ///< gamma_w [force/length^3]; > 0 when there is water
};

/// Water in the joints of a model (Model::water).
struct Water : WaterProperties {
  /// The surface's time samples, times strictly increasing: h(x, t) is linear in
  /// t between two samples (at every x) and held before the first and after the
  /// last; one sample: a surface constant in time. Empty: no water (nothing
  /// computed). At the start every surface spans the blocks' x-range.
  std::vector<WaterSurface> history;
  bool active() const { return !history.empty(); }
};

/// Height h(x, t) of the phreatic surface [length] (linear in x along each
/// surface, linear in t between the samples around t).
double water_level_at(const Water& w, double x, double t);

/// Hydrostatic pressure p = gamma_w max(0, h(x, t) - y) at the point (x, y) [stress]; 0 without water.
double water_pressure(const Water& w, const Vec2& point, double t);

/// The six DDA load terms of the pressure on the straight edge a -> b of a
/// block whose unknowns refer to `centroid` and whose interior lies to the
/// left of a -> b (a counter-clockwise polygon) [force, force, force x length,
/// force x length x3]: int_edge T(x)^T (-p(x) n) ds, n the outward unit normal,
/// T the first-order displacement matrix (contact::displacement_matrix). Exact:
/// the edge is split where it crosses the surface and at the x of the
/// surfaces' points, and the integrand, quadratic on each piece, is integrated
/// by Simpson's rule.
Vec6 water_edge_load(const Water& w, const Vec2& a, const Vec2& b, const Vec2& centroid, double t);

/// The sum of water_edge_load over the edges of a counter-clockwise polygon.
Vec6 water_block_load(const Water& w, std::span<const Vec2> vertices, const Vec2& centroid, double t);

/// First sample time of the water history later than `after` (inf if none):
/// adaptive stepping ends steps there, as on point-load sample times [time].
double next_water_break(const Water& w, double after);

/// Checks the water of a model whose blocks span [x_min, x_max] at the start:
/// unit_weight > 0 and finite, at least one sample, finite values, times
/// strictly increasing, every surface with >= 2 points, x strictly increasing
/// and spanning [x_min, x_max]. Throws ModelError (model.hpp) naming
/// "water.unit_weight" or "water.history[k]...".
void validate_water(const Water& w, double x_min, double x_max);

}  // namespace rheodda::core
