// Exact integrals over a simple polygon and orientation normalisation.
//
// DDA needs, per block, the area S, the first moments Sx, Sy and the second
// moments Sxx, Syy, Sxy (Shi 1988, "simplex integration"). For a polygon they
// are exact sums over a fan of triangles (origin, v_k, v_k+1); see
// docs/reference/engine.md. The fan works for concave polygons too, because triangles
// of a clockwise sweep enter with negative signed area.
#pragma once

#include <span>
#include <vector>

#include "rheodda/core/model.hpp"

namespace rheodda::core {

/// Integrals of 1, x, y, x^2, y^2, xy over a polygon.
struct PolygonIntegrals {
  double S = 0.0;    ///< signed area, > 0 for counter-clockwise [length^2]
  double Sx = 0.0;   ///< integral of x [length^3]
  double Sy = 0.0;   ///< integral of y [length^3]
  double Sxx = 0.0;  ///< integral of x^2 [length^4]
  double Syy = 0.0;  ///< integral of y^2 [length^4]
  double Sxy = 0.0;  ///< integral of x y [length^4]
  /// Centroid (Sx/S, Sy/S) [length].
  Vec2 centroid() const { return {Sx / S, Sy / S}; }
};

/// Integrals about the origin of the coordinates (signed, as oriented).
PolygonIntegrals polygon_integrals(std::span<const Vec2> vertices);

/// Integrals with x, y measured from the centroid (so Sx = Sy = 0 up to
/// round-off and Sxx, Syy, Sxy are central second moments); computed on
/// shifted coordinates, which keeps them accurate far from the origin.
PolygonIntegrals central_integrals(std::span<const Vec2> vertices, Vec2* centroid = nullptr);

/// True if no two non-adjacent edges touch and no adjacent edges fold back.
bool is_simple_polygon(std::span<const Vec2> vertices);

/// Makes the polygon counter-clockwise. When it reverses the vertex order it
/// permutes edge_joint_set to match: new edge j (new vertex j -> j+1) is old
/// edge (n-2-j) mod n. Returns true if it reversed.
bool normalise_orientation(std::vector<Vec2>& vertices, std::vector<int>& edge_joint_set);

}  // namespace rheodda::core
