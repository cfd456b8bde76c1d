// Polygon checks the scene loader needs before a model is built: signed area,
// simplicity, point location, overlap between blocks and an estimate of the
// contacts DDA will find. Plain functions on point lists; lengths in [length].
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// Signed area (shoelace formula): > 0 counter-clockwise [length^2].
double signed_area(const std::vector<Point>& polygon);

/// Why the polygon's coordinates cannot be computed with (beyond 1e150: areas
/// overflow), or nullopt.
std::optional<std::string> coordinate_defect(const std::vector<Point>& polygon);

/// Why the polygon is not a simple polygon with positive area, or nullopt if it is.
/// `tol` is a length below which points count as coincident.
std::optional<std::string> polygon_defect(const std::vector<Point>& polygon, double tol);

/// A block lying more than `ratio` times the median block size (bounding-box
/// diagonal) away from all the others, with that gap [length], or nullopt: a typo
/// in its coordinates, which would also inflate the model size and with it the
/// geometric tolerance applied to every other block.
std::optional<std::pair<int, double>> stray_block(const std::vector<BlockDescription>& blocks, double ratio);

/// Distance from p to the polygon's boundary [length].
double boundary_distance(const std::vector<Point>& polygon, const Point& p);

/// True if p is inside or within `tol` of the boundary.
bool contains(const std::vector<Point>& polygon, const Point& p, double tol);

/// A point strictly inside a simple polygon (centroid of an ear).
Point interior_point(const std::vector<Point>& polygon);

/// True if the interiors of two simple polygons overlap by more than `tol`
/// (touching along edges or at vertices is not overlap).
bool interiors_overlap(const std::vector<Point>& a, const std::vector<Point>& b, double tol);

/// Pairs (i, j), i < j, of blocks whose interiors overlap; bounding boxes sorted in x
/// so that only nearby pairs are tested.
std::vector<std::pair<int, int>> overlapping_blocks(const std::vector<BlockDescription>& blocks,
                                                    double tol);

/// What `rheodda check` reports about contacts at the start.
struct ContactEstimate {
  int block_pairs = 0;   ///< pairs of blocks closer than the search distance
  int vertex_edge = 0;   ///< vertex-edge pairs closer than the search distance (edge-edge counts 2)
};
/// Counts the vertex-edge pairs within `distance` [length] of each other, block against block.
ContactEstimate estimate_contacts(const std::vector<BlockDescription>& blocks, double distance);

/// Half the larger side of the bounding box of all blocks: Shi's w0 [length].
double half_model_size(const std::vector<BlockDescription>& blocks);

}  // namespace rheodda::scene
