// Cutting a region into blocks with joint traces, exactly.
//
// Why exact: a cutter in floating point decides "do these two traces cross, and
// where" with rounding; near-parallel traces, a trace through a vertex or two
// coincident traces then give inconsistent answers and the cutter loops or loses
// blocks (the failure of older DDA cutters). Here the region boundary and the
// traces go into a CGAL 2D arrangement over an exact kernel
// (Exact_predicates_exact_constructions_kernel): every intersection, overlap and
// incidence is decided exactly, so the faces tile the region. Then, as Shi's DC
// program does, dead-end (dangling) trace segments are removed (edges with the
// same face on both sides: a trace ending inside a block does not cut it), the
// bounded faces inside the region are the blocks (concave ones kept), faces
// below a sliver area are merged into the neighbour they share the longest joint
// with, and the result is checked. Only at the end are coordinates rounded to
// doubles (each exact coordinate to the nearest double below or equal).
//
// CGAL stays inside cut.cpp; this interface is plain doubles.
#pragma once

#include <map>
#include <stdexcept>
#include <vector>

#include "rheodda/rockmass/generate.hpp"

namespace rheodda::rockmass {

/// The region to cut: a simple polygon with optional holes (tunnels, openings), each
/// a simple polygon strictly inside the outer one, not touching one another [length].
struct Region {
  std::vector<Point> outer;
  std::vector<std::vector<Point>> holes;
};

/// A generated block: a simple polygon, counter-clockwise, first vertex not repeated.
struct Block {
  std::vector<Point> polygon;  ///< [length]
  std::vector<int> edge_tag;   ///< edge k (vertex k -> k+1): its joint set's tag, or kBoundaryTag
  double area = 0.0;           ///< shoelace area of `polygon` [length^2]
};

struct CutOptions {
  /// Blocks below this area are merged into a neighbour [length^2]; 0: none.
  double sliver_area = 0.0;
};

struct CutResult {
  std::vector<Block> blocks;       ///< ordered by the lowest, then leftmost, vertex
  double region_area = 0.0;        ///< outer area minus the holes' [length^2]
  double area_error = 0.0;         ///< |sum of block areas - region_area| / region_area [-]
  int merged_slivers = 0;          ///< faces below sliver_area merged into a neighbour
  int dangling_removed = 0;        ///< dead-end trace segments removed (arrangement edges)
  /// Traces extended along their own line to the next joint, so that no block encloses
  /// a hole or another block or touches itself at a vertex.
  int extended_traces = 0;
  /// Of these, the ones that could not continue a trace and run parallel to one of
  /// the block's joints from a vertex of the hole or the enclosed block instead.
  int added_traces = 0;
  /// Blocks dropped because welding their vertices (closer than 1e-9 of the region's
  /// size after rounding to doubles) left no area: slivers of rounding size.
  int collapsed_blocks = 0;
  std::map<int, double> joint_length;  ///< per tag: length of the block edges it carries [length]
};

/// What went wrong in a cut, for people: `where` is a point of the region near the fault.
class CutError : public std::runtime_error {
 public:
  CutError(const std::string& message, Point where) : std::runtime_error(message), where_(where) {}
  const Point& where() const { return where_; }

 private:
  Point where_;
};

/// Cuts `region` with `traces` (tags >= 0). DDA blocks are simple polygons: where a
/// block would enclose a hole or another block, or touch itself at a vertex, the
/// joint edge whose extension reaches the rest of its boundary soonest is extended
/// (CutResult::extended_traces). Throws CutError when no joint edge can be extended
/// (a hole inside an uncut block: add a trace that reaches it) or when a check fails: block areas must sum to the region's
/// within 1e-12 relative, every block must be counter-clockwise with positive area.
CutResult cut_blocks(const Region& region, const std::vector<Trace>& traces, const CutOptions& options = {});

/// Shoelace area, > 0 counter-clockwise [length^2].
double polygon_area(const std::vector<Point>& polygon);

}  // namespace rheodda::rockmass
