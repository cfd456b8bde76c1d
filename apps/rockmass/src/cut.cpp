// The exact cutter (cut.hpp): CGAL 2D arrangement of the region boundary and
// the joint traces over an exact kernel. The only translation unit with CGAL.
#include "rheodda/rockmass/cut.hpp"

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

namespace rheodda::rockmass {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
/// Each edge keeps the list of input curves (by index) it lies on: its tags and
/// whether it lies on the region's boundary follow from that list.
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, int>;
/// Face data: -1 not yet classified, 0 outside the region, 1 inside, 2 inside and
/// already merged in the current sliver pass.
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;
using Face = Arrangement::Face_handle;
using Halfedge = Arrangement::Halfedge_handle;
using Vertex = Arrangement::Vertex_handle;
using Ccb = Arrangement::Ccb_halfedge_circulator;

constexpr int kOutside = 0, kInside = 1, kMerged = 2;

Point approx(const Kernel::Point_2& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

class Cutter {
 public:
  Cutter(const Region& region, const std::vector<Trace>& traces) {
    std::vector<Traits::Curve_2> curves;
    auto add = [&](const Point& a, const Point& b, int tag) {
      for (double v : {a[0], a[1], b[0], b[1]})
        if (!std::isfinite(v)) throw CutError("a coordinate is not a finite number", a);
      if (a == b) return;  // a zero-length trace cuts nothing
      curves.emplace_back(SegmentTraits::Curve_2(Kernel::Point_2(a[0], a[1]), Kernel::Point_2(b[0], b[1])),
                          static_cast<int>(tag_of_.size()));
      tag_of_.push_back(tag);
    };
    auto ring = [&](const std::vector<Point>& p) {
      for (std::size_t i = 0; i < p.size(); ++i) add(p[i], p[(i + 1) % p.size()], kBoundaryTag);
    };
    ring(region.outer);
    for (const auto& h : region.holes) ring(h);
    for (const Trace& t : traces) {
      if (t.tag < 0) throw CutError(fmt::format("trace with tag {} (joint set tags are >= 0)", t.tag), t.a);
      add(t.a, t.b, t.tag);
    }
    // Aggregated insertion: one plane sweep over all curves (Bentley-Ottmann).
    CGAL::insert(arr_, curves.begin(), curves.end());
  }

  /// Tag of the edge of h: kBoundaryTag if any of its curves is the boundary,
  /// else the smallest joint-set tag of the (possibly coincident) traces on it.
  int tag(Halfedge h) const {
    int t = std::numeric_limits<int>::max();
    for (int c : h->curve().data()) {
      if (tag_of_[c] == kBoundaryTag) return kBoundaryTag;
      t = std::min(t, tag_of_[c]);
    }
    return t;
  }
  /// True if an odd number of boundary curves run along h: crossing it enters or leaves the region.
  bool toggles(Halfedge h) const {
    int n = 0;
    for (int c : h->curve().data()) n += tag_of_[c] == kBoundaryTag;
    return n % 2 == 1;
  }

  /// Labels every face inside/outside: a walk from the unbounded face across
  /// edges, switching side at each boundary edge.
  void classify() {
    for (auto f = arr_.faces_begin(); f != arr_.faces_end(); ++f) f->set_data(-1);
    std::deque<Face> queue;
    Face u = arr_.unbounded_face();
    u->set_data(kOutside);
    queue.push_back(u);
    auto visit = [&](Face f, Ccb start) {
      Ccb c = start;
      do {
        Face g = c->twin()->face();
        if (g->data() < 0) {
          g->set_data(toggles(c) ? 1 - f->data() : f->data());
          queue.push_back(g);
        }
      } while (++c != start);
    };
    while (!queue.empty()) {
      Face f = queue.front();
      queue.pop_front();
      if (!f->is_unbounded()) visit(f, f->outer_ccb());
      for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h) visit(f, *h);
    }
  }

  /// Removes every edge with the same inside face on both sides: dead-end traces
  /// (and traces that only bridge to a hole) do not separate blocks (Shi's DC).
  int remove_dangling() {
    std::vector<Halfedge> dead;
    for (auto e = arr_.edges_begin(); e != arr_.edges_end(); ++e)
      if (e->face() == e->twin()->face() && e->face()->data() != kOutside) dead.push_back(e);
    for (Halfedge h : dead) arr_.remove_edge(h);
    return static_cast<int>(dead.size());
  }

  static double approx_area(Face f) {
    double a = 0.0;
    Ccb c = f->outer_ccb(), start = c;
    do {
      const Point p = approx(c->source()->point()), q = approx(c->target()->point());
      a += p[0] * q[1] - q[0] * p[1];
    } while (++c != start);
    return 0.5 * a;
  }

  /// Merges faces below `sliver_area` into the inside neighbour they share the
  /// longest joint (non-boundary edges) with; passes until none is left that can merge.
  std::pair<int, int> merge_slivers(double sliver_area) {
    int merged = 0;
    for (int pass = 0; pass < 1000; ++pass) {
      std::vector<std::pair<double, Face>> slivers;
      for (auto f = arr_.faces_begin(); f != arr_.faces_end(); ++f) {
        if (f->data() == kMerged) f->set_data(kInside);
        if (f->data() == kInside && !f->is_unbounded()) {
          const double a = approx_area(f);
          if (a < sliver_area) slivers.emplace_back(a, f);
        }
      }
      std::stable_sort(slivers.begin(), slivers.end(),
                       [](const auto& x, const auto& y) { return x.first < y.first; });
      std::vector<Halfedge> remove;
      int deferred = 0, stuck = 0;
      for (const auto& [area, f] : slivers) {
        if (f->data() != kInside) {
          ++deferred;
          continue;
        }
        std::vector<std::pair<Face, double>> shared;  // neighbour, shared joint length (first-seen order)
        Ccb c = f->outer_ccb(), start = c;
        do {
          Face g = c->twin()->face();
          if (g == f || g->data() == kOutside || tag(c) == kBoundaryTag) continue;
          const Point p = approx(c->source()->point()), q = approx(c->target()->point());
          const double len = std::hypot(q[0] - p[0], q[1] - p[1]);
          auto it = std::find_if(shared.begin(), shared.end(), [&](const auto& s) { return s.first == g; });
          if (it == shared.end())
            shared.emplace_back(g, len);
          else
            it->second += len;
        } while (++c != start);
        if (shared.empty()) {
          ++stuck;  // bounded by the region's boundary only: kept
          continue;
        }
        const auto best = std::max_element(shared.begin(), shared.end(),
                                           [](const auto& x, const auto& y) { return x.second < y.second; });
        if (best->first->data() != kInside) {
          ++deferred;  // its neighbour merges with another sliver in this pass: next pass
          continue;
        }
        Face g = best->first;
        f->set_data(kMerged);
        g->set_data(kMerged);
        c = start;
        do
          if (c->twin()->face() == g) remove.push_back(c);
        while (++c != start);
        ++merged;
      }
      for (Halfedge h : remove) arr_.remove_edge(h);
      // Done when nothing merged or nothing waits for the next pass.
      if (remove.empty() || deferred == 0) return {merged, stuck};
    }
    return {merged, 0};
  }

  CutResult extract() {
    CutResult out;
    std::unordered_map<const void*, Point> rounded;
    auto point = [&](Vertex v) {
      auto [it, fresh] = rounded.try_emplace(&*v);
      if (fresh) it->second = {CGAL::to_double(v->point().x().exact()), CGAL::to_double(v->point().y().exact())};
      return it->second;
    };
    // A vertex between two collinear edges of the same tag, and no other edge, is dropped
    // (both blocks at it drop it): what is left of a removed dead-end trace.
    auto kept = [&](Ccb in) {
      Ccb out_edge = std::next(in);
      Vertex v = in->target();
      if (v->degree() != 2) return true;
      if (tag(in) != tag(out_edge)) return true;
      return !CGAL::collinear(in->source()->point(), v->point(), out_edge->target()->point());
    };
    struct Keyed {
      Point low;
      Block block;
    };
    std::vector<Keyed> blocks;
    for (auto f = arr_.faces_begin(); f != arr_.faces_end(); ++f) {
      if (f->data() == kOutside || f->is_unbounded()) continue;
      Ccb start = f->outer_ccb();
      if (f->number_of_inner_ccbs() > 0) {
        Ccb inner = *f->inner_ccbs_begin();
        const Point at = point(inner->source());
        throw CutError(fmt::format("a block would enclose the hole or the block at ({:g}, {:g}), which no "
                                   "joint reaches: DDA blocks are simple polygons; add a trace (e.g. in "
                                   "`traces:`) that cuts through it",
                                   at[0], at[1]),
                       at);
      }
      // Start at a kept vertex (the target of `in`).
      Ccb in = start;
      while (!kept(in))
        if (++in == start) break;
      Block b;
      Ccb c = in, first = in;
      do {
        if (kept(c)) {
          b.polygon.push_back(point(c->target()));
          b.edge_tag.push_back(tag(std::next(c)));
        }
      } while (++c != first);
      b.area = polygon_area(b.polygon);
      if (!(b.area > 0.0))
        throw CutError(fmt::format("the block at ({:g}, {:g}) has area {:g} after rounding to doubles",
                                   b.polygon[0][0], b.polygon[0][1], b.area),
                       b.polygon[0]);
      Point low = b.polygon[0];
      for (const Point& p : b.polygon)
        if (p[1] < low[1] || (p[1] == low[1] && p[0] < low[0])) low = p;
      blocks.push_back({low, std::move(b)});
    }
    std::stable_sort(blocks.begin(), blocks.end(), [](const Keyed& x, const Keyed& y) {
      return x.low[1] != y.low[1] ? x.low[1] < y.low[1] : x.low[0] < y.low[0];
    });
    for (auto& k : blocks) out.blocks.push_back(std::move(k.block));
    for (auto e = arr_.edges_begin(); e != arr_.edges_end(); ++e) {
      if (e->face()->data() == kOutside && e->twin()->face()->data() == kOutside) continue;
      const Point p = point(e->source()), q = point(e->target());
      out.joint_length[tag(e)] += std::hypot(q[0] - p[0], q[1] - p[1]);
    }
    return out;
  }

 private:
  Arrangement arr_;
  std::vector<int> tag_of_;  ///< per input curve
};

}  // namespace

double polygon_area(const std::vector<Point>& p) {
  double a = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Point& u = p[i];
    const Point& v = p[(i + 1) % n];
    a += u[0] * v[1] - v[0] * u[1];
  }
  return 0.5 * a;
}

CutResult cut_blocks(const Region& region, const std::vector<Trace>& traces, const CutOptions& options) {
  if (region.outer.size() < 3) throw CutError("the region needs at least 3 vertices", {0.0, 0.0});
  Cutter cutter(region, traces);
  cutter.classify();
  const int dangling = cutter.remove_dangling();
  int merged = 0;
  if (options.sliver_area > 0.0) merged = cutter.merge_slivers(options.sliver_area).first;
  CutResult r = cutter.extract();
  r.dangling_removed = dangling;
  r.merged_slivers = merged;
  r.region_area = std::abs(polygon_area(region.outer));
  for (const auto& h : region.holes) r.region_area -= std::abs(polygon_area(h));
  double sum = 0.0;
  for (const Block& b : r.blocks) {
    sum += b.area;
    for (int t : b.edge_tag)
      if (t < kBoundaryTag || t == std::numeric_limits<int>::max())
        throw CutError("an edge of a block carries no joint set", b.polygon[0]);
  }
  r.area_error = std::abs(sum - r.region_area) / r.region_area;
  // Exactly, the faces tile the region; after rounding the vertices to doubles the
  // areas may differ by rounding only.
  if (!(r.area_error <= 1e-12))
    throw CutError(fmt::format("the blocks' areas sum to {:.17g}, the region's area is {:.17g} (relative "
                               "difference {:g} > 1e-12): the region's boundary crosses itself or a hole "
                               "leaves the region",
                               sum, r.region_area, r.area_error),
                   region.outer[0]);
  return r;
}

}  // namespace rheodda::rockmass
