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
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <optional>
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
    auto add = [&](const Point& a, const Point& b, int tag, int trace) {
      for (double v : {a[0], a[1], b[0], b[1]})
        if (!std::isfinite(v)) throw CutError("a coordinate is not a finite number", a);
      if (a == b) return;  // a zero-length trace cuts nothing
      curves.emplace_back(SegmentTraits::Curve_2(Kernel::Point_2(a[0], a[1]), Kernel::Point_2(b[0], b[1])),
                          static_cast<int>(tag_of_.size()));
      tag_of_.push_back(tag);
      trace_of_.push_back(trace);
    };
    auto ring = [&](const std::vector<Point>& p) {
      for (std::size_t i = 0; i < p.size(); ++i) add(p[i], p[(i + 1) % p.size()], kBoundaryTag, -1);
    };
    ring(region.outer);
    for (const auto& h : region.holes) ring(h);
    for (std::size_t i = 0; i < traces.size(); ++i) {
      const Trace& t = traces[i];
      if (t.tag < 0) throw CutError(fmt::format("trace with tag {} (joint set tags are >= 0)", t.tag), t.a);
      add(t.a, t.b, t.tag, static_cast<int>(i));
    }
    traces_ = traces.size();
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

  /// Per input trace: whether some edge it lies on has the region's inside on a side
  /// (after classify(), before remove_dangling()).
  std::vector<char> traces_in_region() const {
    std::vector<char> in(traces_, 0);
    for (auto e = arr_.edges_begin(); e != arr_.edges_end(); ++e) {
      if (e->face()->data() != kInside && e->twin()->face()->data() != kInside) continue;
      for (int c : e->curve().data())
        if (trace_of_[c] >= 0) in[static_cast<std::size_t>(trace_of_[c])] = 1;
    }
    return in;
  }

  /// Removes every edge with the same inside face on both sides: dead-end traces
  /// (and traces that only bridge to a hole) do not separate blocks (Shi's DC);
  /// and every edge outside the region. Returns the number of inside edges removed.
  int remove_dangling() {
    std::vector<Halfedge> dead;
    int inside = 0;
    for (auto e = arr_.edges_begin(); e != arr_.edges_end(); ++e) {
      const bool out = e->face()->data() == kOutside && e->twin()->face()->data() == kOutside;
      if (e->face() == e->twin()->face() && !out) ++inside;
      // Traces outside the region go too: where they met the boundary no vertex is left.
      if (e->face() == e->twin()->face() || out) dead.push_back(e);
    }
    // The order matters for time, not for the result. An edge between two faces merges
    // them; an edge with one face on both sides at a vertex of degree 1 (a leaf) goes
    // without more; but one in the middle of a dead-end chain splits its face's boundary
    // in two, and CGAL walks it to tell which part is the hole. With thousands of dead
    // ends in one face, a walk per edge took 44 s instead of 2 s on a 30 m x 4.8 km
    // strip. So: the edges between two faces (traces outside the region crossing each
    // other), then the leaves, peeled back along their chains, then what is left
    // (bridges to a hole or between clusters).
    std::unordered_map<const void*, char> is_dead;
    for (Halfedge h : dead) is_dead[&*h] = is_dead[&*h->twin()] = 1;
    for (Halfedge h : dead)
      if (h->face() != h->twin()->face()) {
        is_dead.erase(&*h);
        is_dead.erase(&*h->twin());
        arr_.remove_edge(h);
      }
    std::vector<Halfedge> leaves;
    auto leaf_edges_at = [&](Vertex v) {
      if (v->degree() != 1) return;
      auto e = v->incident_halfedges();  // the one edge at v
      if (is_dead.count(&*e)) leaves.push_back(e);
    };
    for (Halfedge h : dead)
      if (is_dead.count(&*h)) leaf_edges_at(h->source()), leaf_edges_at(h->target());
    while (!leaves.empty()) {
      Halfedge h = leaves.back();
      leaves.pop_back();
      if (!is_dead.count(&*h)) continue;  // removed already (reached from both ends)
      Vertex other = h->source()->degree() == 1 ? h->target() : h->source();
      // A segment alone (both ends leaves) takes both its vertices with it.
      const bool other_stays = other->degree() > 1;
      is_dead.erase(&*h);
      is_dead.erase(&*h->twin());
      arr_.remove_edge(h);
      if (other_stays) leaf_edges_at(other);
    }
    for (Halfedge h : dead)
      if (is_dead.count(&*h)) {
        is_dead.erase(&*h);
        is_dead.erase(&*h->twin());
        arr_.remove_edge(h);
      }
    return inside;
  }

  /// Why face f is not a simple polygon, or an empty string: it encloses a hole or
  /// another block (an inner CCB), or its boundary touches itself at a vertex.
  /// `lobe` receives the halfedges of the enclosed part (the first inner CCB, or the
  /// walk between the two visits of the vertex).
  static bool non_simple(Face f, std::vector<Halfedge>& lobe) {
    lobe.clear();
    if (f->number_of_inner_ccbs() > 0) {
      Ccb c = *f->inner_ccbs_begin(), start = c;
      do lobe.push_back(c);
      while (++c != start);
      return true;
    }
    std::unordered_map<const void*, Ccb> seen;  // vertex -> the halfedge leaving it
    Ccb c = f->outer_ccb(), start = c;
    do {
      auto [it, fresh] = seen.try_emplace(&*c->source(), c);
      if (!fresh) {
        for (Ccb w = it->second; w != c; ++w) lobe.push_back(w);
        return true;
      }
    } while (++c != start);
    return false;
  }

  /// Makes every block a simple polygon: where a face encloses a hole or a block, or
  /// touches itself at a vertex, the joint edge whose extension along its own line
  /// reaches the rest of the face's boundary soonest is extended to it (a trace
  /// continued to the next joint, as a longer trace of the same set would be). Each
  /// round fixes one defect per face; a hole becomes a bridge first, the bridge then
  /// a cut. Returns the number of extensions; throws CutError if a defect has no
  /// joint edge to extend.
  int make_simple() {
    int extensions = 0;
    std::vector<Halfedge> lobe, all;
    for (int round = 0; round < 64; ++round) {
      std::vector<Traits::Curve_2> add;
      for (auto f = arr_.faces_begin(); f != arr_.faces_end(); ++f) {
        if (f->data() == kOutside || f->is_unbounded() || !non_simple(f, lobe)) continue;
        all.clear();
        auto collect = [&](Ccb start) {
          Ccb c = start;
          do all.push_back(c);
          while (++c != start);
        };
        collect(f->outer_ccb());
        for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h) collect(*h);
        std::unordered_map<const void*, bool> in_lobe;
        for (Halfedge h : lobe) in_lobe[&*h] = true;
        bool found = false;
        Kernel::Point_2 best_from, best_to;
        Kernel::FT best_length = 0;
        int best_tag = 0;
        // The ray from the target v of h (a halfedge of f) in direction d, if d points
        // into f at v: its first hit on f's boundary, kept if it joins the lobe to the
        // rest and is the shortest so far.
        auto shoot = [&](Halfedge h, const Kernel::Vector_2& d, int t) {
          const Kernel::Point_2& v = h->target()->point();
          const Kernel::Vector_2 a = h->next()->target()->point() - v;  // out along the boundary
          const Kernel::Vector_2 b = h->source()->point() - v;          // back along the boundary
          // f's sector at v runs counter-clockwise from a to b.
          auto orient = [](const Kernel::Vector_2& x, const Kernel::Vector_2& y) {
            return CGAL::sign(x.x() * y.y() - x.y() * y.x());
          };
          const bool inside = orient(a, b) == CGAL::POSITIVE
                                  ? orient(a, d) == CGAL::POSITIVE && orient(d, b) == CGAL::POSITIVE
                                  : !(orient(b, d) != CGAL::NEGATIVE && orient(d, a) != CGAL::NEGATIVE);
          if (!inside) return;
          const Kernel::Ray_2 ray(v, d);
          const bool from_lobe = in_lobe.count(&*h) > 0 || in_lobe.count(&*h->next()) > 0;
          std::optional<Kernel::FT> nearest;
          Kernel::Point_2 hit;
          bool hits_other = false;
          Halfedge hit_edge;
          for (Halfedge g : all) {
            const auto x = CGAL::intersection(ray, Kernel::Segment_2(g->source()->point(), g->target()->point()));
            if (!x) continue;
            std::vector<Kernel::Point_2> points;
            if (const auto* q = boost::get<Kernel::Point_2>(&*x)) points.push_back(*q);
            if (const auto* sg = boost::get<Kernel::Segment_2>(&*x)) points = {sg->source(), sg->target()};
            for (const auto& q : points) {
              const Kernel::FT dist = CGAL::squared_distance(v, q);
              if (dist == 0 || (nearest && !(dist < *nearest))) continue;
              nearest = dist;
              hit = q;
              hit_edge = g;
              hits_other = (in_lobe.count(&*g) > 0) != from_lobe;
            }
          }
          if (!nearest || !hits_other) return;
          // A ray meeting the edge at a grazing angle (e.g. the next trace of the same
          // line, collinear but for rounding) would leave a needle DDA cannot model.
          const Point e0 = approx(hit_edge->source()->point()), e1 = approx(hit_edge->target()->point());
          const double ex = e1[0] - e0[0], ey = e1[1] - e0[1];
          const double dx = CGAL::to_double(d.x()), dy = CGAL::to_double(d.y());
          if (std::abs(dx * ey - dy * ex) < 1e-6 * std::hypot(dx, dy) * std::hypot(ex, ey)) return;
          if (!found || *nearest < best_length) {
            found = true;
            best_length = *nearest;
            best_from = v;
            best_to = hit;
            best_tag = t;
          }
        };
        // First choice: a joint edge continued straight ahead (a longer trace).
        for (Halfedge h : all)
          if (const int t = tag(h); t != kBoundaryTag)
            shoot(h, h->target()->point() - h->source()->point(), t);
        // Else a joint parallel to one of the block's joint edges (either way) from a
        // vertex of the lobe or of the rest: a hole inside a block its joints miss.
        if (!found) {
          std::vector<std::pair<Kernel::Vector_2, int>> directions;
          for (Halfedge h : all) {
            const int t = tag(h);
            if (t == kBoundaryTag || directions.size() >= 16) continue;
            const Kernel::Vector_2 d = h->target()->point() - h->source()->point();
            const bool known = std::any_of(directions.begin(), directions.end(), [&](const auto& e) {
              return CGAL::Direction_2<Kernel>(e.first) == CGAL::Direction_2<Kernel>(d) ||
                     CGAL::Direction_2<Kernel>(e.first) == CGAL::Direction_2<Kernel>(-d);
            });
            if (!known) directions.emplace_back(d, t);
          }
          for (Halfedge h : all)
            for (const auto& [d, t] : directions) {
              shoot(h, d, t);
              shoot(h, -d, t);
            }
          if (found) ++added_;
        }
        if (!found) {
          const Point at = approx(lobe.front()->source()->point());
          throw CutError(fmt::format("a block would enclose the hole or the block at ({:g}, {:g}), or touch itself "
                                     "there, and no joint ends where it could be extended to separate it: DDA "
                                     "blocks are simple polygons; add a trace (e.g. in `traces:`) that cuts "
                                     "through it",
                                     at[0], at[1]),
                         at);
        }
        add.emplace_back(SegmentTraits::Curve_2(best_from, best_to), static_cast<int>(tag_of_.size()));
        tag_of_.push_back(best_tag);
        trace_of_.push_back(-1);  // an extension, not an input trace
      }
      if (add.empty()) return extensions;
      for (const auto& c : add) CGAL::insert(arr_, c);
      extensions += static_cast<int>(add.size());
      classify();  // the new faces are inside, as the face they split
    }
    throw CutError("the blocks could not be made simple polygons in 64 rounds of trace extensions", {0.0, 0.0});
  }

  static double approx_area(Face f) {
    std::vector<Point> p;
    Ccb c = f->outer_ccb(), start = c;
    do p.push_back(approx(c->source()->point()));
    while (++c != start);
    return polygon_area(p);  // about its first vertex (map coordinates)
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

  /// The blocks in doubles. Vertices closer than `weld` [length] after rounding
  /// (distinct exact points a few ulp apart, e.g. where a trace passes 1e-15 from
  /// a vertex) are welded into one, the same for every block at them, so that no
  /// block has an edge DDA cannot model; zero-length edges and spikes this leaves
  /// are dropped, and a block that collapses (area of rounding size) is dropped.
  CutResult extract(double weld) {
    CutResult out;
    std::unordered_map<const void*, Point> rounded;
    auto exact_point = [&](Vertex v) {
      auto [it, fresh] = rounded.try_emplace(&*v);
      if (fresh) it->second = {CGAL::to_double(v->point().x().exact()), CGAL::to_double(v->point().y().exact())};
      return it->second;
    };
    // Weld: union-find over the edges shorter than `weld` after rounding.
    std::unordered_map<const void*, const void*> parent;
    std::unordered_map<const void*, Point> at;
    std::function<const void*(const void*)> root = [&](const void* v) -> const void* {
      auto it = parent.find(v);
      if (it == parent.end() || it->second == v) return v;
      return it->second = root(it->second);
    };
    for (auto e = arr_.edges_begin(); e != arr_.edges_end(); ++e) {
      if (e->face()->data() == kOutside && e->twin()->face()->data() == kOutside) continue;
      const Point p = exact_point(e->source()), q = exact_point(e->target());
      if (std::hypot(q[0] - p[0], q[1] - p[1]) > weld) continue;
      const void* a = root(&*e->source());
      const void* b = root(&*e->target());
      if (a == b) continue;
      const Point pa = at.count(a) ? at[a] : exact_point(e->source());
      const Point pb = at.count(b) ? at[b] : exact_point(e->target());
      // The cluster's point: the lexicographically smallest of its rounded points.
      const Point keep = std::min(pa, pb);
      parent[a] = a;
      parent[b] = a;
      at[a] = keep;
    }
    auto point = [&](Vertex v) {
      if (parent.empty()) return exact_point(v);
      const void* r = root(&*v);
      auto it = at.find(r);
      return it == at.end() ? exact_point(v) : it->second;
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
      // make_simple() ran: no holes, no vertex visited twice.
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
      if (!parent.empty()) {
        // Drop zero-length edges (vertex k equal to k+1: entry k goes) and spikes
        // (k-1 equal to k+1: entries k-1 and k go, k+1 keeps its outgoing tag).
        for (bool changed = true; changed && b.polygon.size() >= 3;) {
          changed = false;
          const std::size_t n = b.polygon.size();
          for (std::size_t k = 0; k < n && !changed; ++k) {
            if (b.polygon[k] == b.polygon[(k + 1) % n]) {
              b.polygon.erase(b.polygon.begin() + long(k));
              b.edge_tag.erase(b.edge_tag.begin() + long(k));
              changed = true;
            } else if (b.polygon[(k + n - 1) % n] == b.polygon[(k + 1) % n]) {
              const std::size_t first_out = (k + n - 1) % n;
              const std::size_t hi = std::max(first_out, k), lo = std::min(first_out, k);
              b.polygon.erase(b.polygon.begin() + long(hi));
              b.edge_tag.erase(b.edge_tag.begin() + long(hi));
              b.polygon.erase(b.polygon.begin() + long(lo));
              b.edge_tag.erase(b.edge_tag.begin() + long(lo));
              changed = true;
            }
          }
        }
        if (b.polygon.size() < 3) {
          ++out.collapsed_blocks;
          continue;
        }
      }
      b.area = polygon_area(b.polygon);
      if (!(b.area > 0.0) && !parent.empty()) {
        ++out.collapsed_blocks;
        continue;
      }
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
  std::vector<int> tag_of_;    ///< per input curve
  std::vector<int> trace_of_;  ///< per input curve: its index in the traces, -1 for the boundary and extensions
  std::size_t traces_ = 0;     ///< input traces

 public:
  int added_ = 0;  ///< of make_simple()'s extensions, those parallel to a joint rather than along one
};

}  // namespace

CutResult cut_blocks(const Region& region, const std::vector<Trace>& traces, const CutOptions& options) {
  if (region.outer.size() < 3) throw CutError("the region needs at least 3 vertices", {0.0, 0.0});
  Cutter cutter(region, traces);
  cutter.classify();
  std::vector<char> in_region = cutter.traces_in_region();
  const int dangling = cutter.remove_dangling();
  int merged = 0;
  int extended = cutter.make_simple();
  if (options.sliver_area > 0.0) {
    merged += cutter.merge_slivers(options.sliver_area).first;
    extended += cutter.make_simple();  // a merge may have closed a face around another
  }
  double size = 0.0;  // larger side of the region's box [length]
  {
    double x0 = region.outer[0][0], x1 = x0, y0 = region.outer[0][1], y1 = y0;
    for (const Point& p : region.outer)
      x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
    size = std::max(x1 - x0, y1 - y0);
  }
  CutResult r = cutter.extract(1e-9 * size);
  r.added_traces = cutter.added_;
  r.trace_in_region = std::move(in_region);
  r.extended_traces = extended;
  r.dangling_removed = dangling;
  r.merged_slivers = merged;
  for (const Block& b : r.blocks)
    for (int t : b.edge_tag)
      if (t < kBoundaryTag || t == std::numeric_limits<int>::max())
        throw CutError("an edge of a block carries no joint set", b.polygon[0]);
  // Exactly, the faces tile the region; after rounding the vertices to doubles the
  // areas may differ by what rounding explains (block_area_check), whatever the count.
  const AreaCheck check = block_area_check(r.blocks, region);
  r.region_area = check.region_area;
  r.area_error = std::abs(check.block_sum - r.region_area) / r.region_area;
  if (!check.ok())
    throw CutError(fmt::format("the blocks' areas sum to {:.17g}, the region's area is {:.17g}: they differ by "
                               "{:.3g}, more than the {:.3g} rounding explains: the region's boundary crosses "
                               "itself or a hole leaves the region (the scene loader refuses both before cutting)",
                               check.block_sum, r.region_area, std::abs(check.block_sum - r.region_area),
                               check.bound),
                   region.outer[0]);
  return r;
}

}  // namespace rheodda::rockmass
