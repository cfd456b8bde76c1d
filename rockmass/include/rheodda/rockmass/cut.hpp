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
  /// Per input trace (in the order given): 1 when some part of it lies in the region
  /// (not outside it, not only in a hole), 0 otherwise (e.g. a trace of the region's box
  /// that misses a concave region).
  std::vector<char> trace_in_region;
};

/// The check that the blocks tile the region: |sum of block areas - region area|
/// against what rounding alone can explain (block_area_check).
struct AreaCheck {
  double block_sum = 0.0;    ///< sum of the blocks' areas, compensated (Neumaier) [length^2]
  double region_area = 0.0;  ///< outer area minus the holes' [length^2]
  /// Largest |block_sum - region_area| rounding explains [length^2]: each block's
  /// shoelace sum (about its first vertex, 2 k eps times the sum of its terms' magnitudes
  /// for k vertices; Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed.,
  /// eq. 3.5), the compensated sum (2 eps |sum|), the region's own area, and the
  /// rounding of the vertices the traces make on the region's boundary (half an ulp of
  /// the coordinates across each boundary edge's length). It grows with the blocks'
  /// total area, not with their number.
  double bound = 0.0;
  bool ok() const;
};

/// The area check of cut_blocks, on any blocks (doubles, counter-clockwise).
AreaCheck block_area_check(const std::vector<Block>& blocks, const Region& region);

/// What a cut will cost, estimated from the traces before cutting (estimate_cut).
struct CutEstimate {
  double crossings = 0.0;  ///< trace crossings in the arrangement (vertices) [-]
  double pieces = 0.0;     ///< faces of the arrangement inside the region: at most that many blocks [-]
  double bytes = 0.0;      ///< peak memory of the cut [bytes]
};

/// Estimates a cut: the expected crossings of the traces from their lengths and
/// directions (Santalo's formula for segments in a domain of area A: two families
/// of total lengths L1, L2 at an angle theta cross L1 L2 |sin theta| / A times;
/// L. A. Santalo, "Integral Geometry and Geometric Probability", 1976, ch. 8),
/// exact in expectation for persistent sets and an upper bound of the blocks for
/// non-persistent ones (their dead ends make no block), and the memory of the exact
/// arrangement per vertex measured on the benchmark cuts (docs/guide/rockmass.md, "Performance").
CutEstimate estimate_cut(const Region& region, const std::vector<Trace>& traces);

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
/// within what rounding explains (block_area_check), every block must be counter-clockwise with positive area.
CutResult cut_blocks(const Region& region, const std::vector<Trace>& traces, const CutOptions& options = {});

/// Shoelace area, > 0 counter-clockwise [length^2], taken about the first vertex: at map
/// coordinates (x ~ 5e5, y ~ 4e6 m) the products x y about the origin are ~2e12 m^2, and
/// their rounding (~2e-4 m^2) would swamp the area of a small block.
double polygon_area(const std::vector<Point>& polygon);

}  // namespace rheodda::rockmass
