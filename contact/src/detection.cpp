#include "rheodda/contact/detection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace rheodda::contact {

const char* contact_kind_name(ContactKind kind) {
  switch (kind) {
    case ContactKind::vertex_edge: return "vertex_edge";
    case ContactKind::vertex_vertex: return "vertex_vertex";
    case ContactKind::edge_edge: return "edge_edge";
  }
  return "?";
}

namespace {

int wrap(int k, int n) { return (k % n + n) % n; }

/// Outward unit normal of an edge a -> b of a counter-clockwise polygon.
Vec2 outward_normal(const Vec2& a, const Vec2& b) {
  const Vec2 t = (b - a).normalized();
  return {t.y(), -t.x()};
}

/// True when vertex v is a corner that can enter an edge: convex, and not a
/// straight angle (a vertex that only subdivides a straight side) within the
/// angle tolerance. Reflex vertices never enter an edge.
bool is_corner(const BlockView& blk, int v, double sin_tol) {
  const int nv = static_cast<int>(blk.vertices.size());
  const Vec2& p = blk.vertices[v];
  const Vec2 u1 = (p - blk.vertices[wrap(v - 1, nv)]).normalized();
  const Vec2 u2 = (blk.vertices[wrap(v + 1, nv)] - p).normalized();
  return u1.x() * u2.y() - u1.y() * u2.x() > sin_tol;
}

/// True when vertex v is reflex (interior angle above 180 deg + tolerance).
bool is_reflex(const BlockView& blk, int v, double sin_tol) {
  const int nv = static_cast<int>(blk.vertices.size());
  const Vec2& p = blk.vertices[v];
  const Vec2 u1 = (p - blk.vertices[wrap(v - 1, nv)]).normalized();
  const Vec2 u2 = (blk.vertices[wrap(v + 1, nv)] - p).normalized();
  return u1.x() * u2.y() - u1.y() * u2.x() < -sin_tol;
}

/// Angle-rule score of vertex v of `blk` entering the edge with outward normal n.
double wedge_score(const BlockView& blk, int v, const Vec2& n) {
  const int nv = static_cast<int>(blk.vertices.size());
  const Vec2& p = blk.vertices[v];
  const Vec2 u1 = (blk.vertices[wrap(v - 1, nv)] - p).normalized();
  const Vec2 u2 = (blk.vertices[wrap(v + 1, nv)] - p).normalized();
  return std::min(n.dot(u1), n.dot(u2));
}

/// Contact length of vertex v of block vb against edge e of block eb: half the
/// overlap of each edge of v's block at v that lies antiparallel on edge e.
double contact_length(const BlockView& vb, int v, const BlockView& eb, int e, double d0,
                      double cos_tol) {
  const int nv = static_cast<int>(vb.vertices.size());
  const int ne = static_cast<int>(eb.vertices.size());
  const Vec2& a = eb.vertices[e];
  const Vec2& b = eb.vertices[wrap(e + 1, ne)];
  const double l = (b - a).norm();
  const Vec2 t = (b - a) / l;
  const Vec2 n(t.y(), -t.x());
  double length = 0.0;
  for (int f : {wrap(v - 1, nv), v}) {
    const Vec2& fa = vb.vertices[f];
    const Vec2& fb = vb.vertices[wrap(f + 1, nv)];
    const Vec2 tf = (fb - fa).normalized();
    if (tf.dot(t) > -cos_tol) continue;  // not antiparallel
    if (std::abs(n.dot(fa - a)) > d0 || std::abs(n.dot(fb - a)) > d0) continue;
    const double s1 = t.dot(fa - a), s2 = t.dot(fb - a);
    const double lo = std::max(0.0, std::min(s1, s2)), hi = std::min(l, std::max(s1, s2));
    if (hi > lo) length += 0.5 * (hi - lo);
  }
  return length;
}

/// Vertex-edge contacts of vertices of block iv against edges of block ie.
void vertex_edge(std::span<const BlockView> blocks, int iv, int ie, double d0, double sin_tol,
                 double cos_tol, std::vector<DetectedContact>& out) {
  const BlockView& vb = blocks[iv];
  const BlockView& eb = blocks[ie];
  const int nv = static_cast<int>(vb.vertices.size());
  const int ne = static_cast<int>(eb.vertices.size());
  for (int e = 0; e < ne; ++e) {
    const Vec2& a = eb.vertices[e];
    const Vec2& b = eb.vertices[wrap(e + 1, ne)];
    const double l = (b - a).norm();
    const Vec2 t = (b - a) / l;
    const Vec2 n(t.y(), -t.x());
    for (int v = 0; v < nv; ++v) {
      const Vec2& p = vb.vertices[v];
      const double gap = n.dot(p - a);  // > 0 outside block ie
      if (gap > d0 || gap < -d0) continue;
      const double r = t.dot(p - a);
      if (r <= 0.0 || r >= l) continue;
      if ((p - a).norm() < d0 || (p - b).norm() < d0) continue;  // vertex-vertex
      if (!is_corner(vb, v, sin_tol)) continue;
      if (wedge_score(vb, v, n) < -sin_tol) continue;
      const double len = contact_length(vb, v, eb, e, d0, cos_tol);
      out.push_back({{iv, v, ie, e}, len > 0.0 ? ContactKind::edge_edge : ContactKind::vertex_edge,
                     len});
    }
  }
}

}  // namespace

double point_tributary_length(const BlockView& vb, int v, const Vec2& t) {
  const int nv = static_cast<int>(vb.vertices.size());
  const Vec2& p = vb.vertices[v];
  // |(q - p) . t| / 2 = (l_f / 2) |t_f . t| for the edge f from p to its other end q.
  const double before = std::abs((vb.vertices[wrap(v - 1, nv)] - p).dot(t));
  const double after = std::abs((vb.vertices[wrap(v + 1, nv)] - p).dot(t));
  return 0.5 * std::max(before, after);
}

void detect_pair(std::span<const BlockView> blocks, int ia, int ib, const DetectionParams& params,
                 std::span<const ContactKey> previous, std::vector<DetectedContact>& out) {
  const double d0 = params.search_distance;
  const double tol = params.angle_tolerance * std::numbers::pi / 180.0;
  const double sin_tol = std::sin(tol), cos_tol = std::cos(tol);
  const BlockView& A = blocks[ia];
  const BlockView& B = blocks[ib];
  const int na = static_cast<int>(A.vertices.size());
  const int nb = static_cast<int>(B.vertices.size());

  // Vertex-vertex, resolved by the angle rule into one vertex-edge contact.
  for (int k = 0; k < na; ++k)
    for (int m = 0; m < nb; ++m) {
      const Vec2& p = A.vertices[k];
      const Vec2& q = B.vertices[m];
      if ((p - q).norm() >= d0) continue;
      const bool p_corner = is_corner(A, k, sin_tol), q_corner = is_corner(B, m, sin_tol);
      if (!p_corner && !q_corner) continue;
      // A corner in a notch (the other vertex reflex) touches both edges of the notch.
      const bool p_in_notch = p_corner && is_reflex(B, m, sin_tol);
      const bool q_in_notch = q_corner && is_reflex(A, k, sin_tol);
      const std::array<ContactKey, 4> cand{ContactKey{ia, k, ib, wrap(m - 1, nb)},
                                           ContactKey{ia, k, ib, m},
                                           ContactKey{ib, m, ia, wrap(k - 1, na)},
                                           ContactKey{ib, m, ia, k}};
      std::array<double, 4> score{};
      double best = -2.0;
      for (int c = 0; c < 4; ++c) {
        // Only a corner can be the entering vertex.
        if (!(c < 2 ? p_corner : q_corner)) { score[c] = -3.0; continue; }
        const BlockView& eb = blocks[cand[c].eblock];
        const int ne = static_cast<int>(eb.vertices.size());
        const Vec2 n =
            outward_normal(eb.vertices[cand[c].edge], eb.vertices[wrap(cand[c].edge + 1, ne)]);
        score[c] = wedge_score(blocks[cand[c].vblock], cand[c].vertex, n);
        best = std::max(best, score[c]);
      }
      // Candidates tied with the best score are equally valid. Every one of them
      // that was a contact in the last step stays (two blocks sliding past a
      // straight-angle vertex keep both contacts and their identities); if none
      // was, one is taken: preferably one whose vertex projects inside its edge.
      std::array<bool, 4> in_range{}, was{}, in_reach{};
      for (int c = 0; c < 4; ++c) {
        const BlockView& eb = blocks[cand[c].eblock];
        const int ne = static_cast<int>(eb.vertices.size());
        const Vec2& a = eb.vertices[cand[c].edge];
        const Vec2& b = eb.vertices[wrap(cand[c].edge + 1, ne)];
        const double l2 = (b - a).squaredNorm();
        const double r = (b - a).dot(blocks[cand[c].vblock].vertices[cand[c].vertex] - a) / l2;
        in_range[c] = r >= -1e-9 && r <= 1.0 + 1e-9;
        const double reach = params.notch_reach / std::sqrt(l2);
        in_reach[c] = params.notch_reach < 0.0 || (r >= -reach - 1e-9 && r <= 1.0 + reach + 1e-9);
        was[c] = std::binary_search(previous.begin(), previous.end(), cand[c]);
      }
      auto emit = [&](int c) {
        const ContactKey& key = cand[c];
        const double len = contact_length(blocks[key.vblock], key.vertex, blocks[key.eblock],
                                          key.edge, d0, cos_tol);
        out.push_back({key, len > 0.0 ? ContactKind::edge_edge : ContactKind::vertex_vertex, len});
      };
      if (p_in_notch || q_in_notch) {
        // Only the notch edges the corner still lies along: a corner that has
        // moved on past the notch's vertex along one edge (beyond the other's
        // end by more than the allowed penetration) no longer touches the other,
        // whose line would hold it with a spring in tension (docs/reference/contacts.md,
        // "Contact types"; docs/notes/contact-rules.md, "The notch rule").
        bool any = false;
        for (int c = 0; c < 4; ++c)
          if ((c < 2 ? p_in_notch : q_in_notch) && score[c] >= -sin_tol && in_reach[c]) emit(c), any = true;
        if (!any)
          for (int c = 0; c < 4; ++c)
            if ((c < 2 ? p_in_notch : q_in_notch) && score[c] >= -sin_tol) emit(c);
        continue;
      }
      // The angle rule admits no candidate (the best one's wedge crosses its edge's line:
      // a corner paired with a vertex that only subdivides a straight side, its edges
      // along the corner's own): the pair does not touch. Taken all the same, the entrance
      // was an edge the vertex lies beyond, whose line's distance measures no overlap.
      if (best < -sin_tol) continue;
      bool kept = false;
      for (int c = 0; c < 4; ++c)
        if (score[c] >= best - sin_tol && was[c]) emit(c), kept = true;
      if (kept) continue;
      int chosen = -1;
      for (int c = 0; c < 4 && chosen < 0; ++c)
        if (score[c] >= best - sin_tol && in_range[c]) chosen = c;
      // No tied candidate has its vertex within its edge: the vertices are
      // apart (within the search distance, not coincident) and the best
      // scored edge is one the vertex lies beyond. Its line's distance
      // measures nothing there; a valid candidate the vertex does lie along
      // is its entrance (at a T-junction of a generated rock mass, the edge
      // the vertex sits on; docs/reference/contacts.md, "Contact types").
      if (chosen < 0)
        for (int c = 0; c < 4; ++c)
          if (score[c] >= -sin_tol && in_range[c] && (chosen < 0 || score[c] > score[chosen])) chosen = c;
      for (int c = 0; c < 4 && chosen < 0; ++c)
        if (score[c] >= best - sin_tol) chosen = c;
      emit(chosen);
    }

  vertex_edge(blocks, ia, ib, d0, sin_tol, cos_tol, out);
  vertex_edge(blocks, ib, ia, d0, sin_tol, cos_tol, out);
}

std::vector<DetectedContact> detect_contacts(std::span<const BlockView> blocks,
                                             std::span<const std::pair<int, int>> pairs,
                                             const DetectionParams& params,
                                             std::span<const ContactKey> previous) {
  std::vector<DetectedContact> out;
  out.reserve(pairs.size() * 2);
  for (const auto& [i, j] : pairs) detect_pair(blocks, i, j, params, previous, out);
  std::sort(out.begin(), out.end(),
            [](const DetectedContact& x, const DetectedContact& y) { return x.key < y.key; });
  out.erase(std::unique(out.begin(), out.end(),
                        [](const DetectedContact& x, const DetectedContact& y) {
                          return x.key == y.key;
                        }),
            out.end());

  // One vertex on two adjacent edges of the same block: a true double contact
  // only in a notch (reflex shared vertex). Otherwise - the edges meet at a
  // corner or continue straight, and the vertex is within the search distance
  // of both - keep one: the last step's contact, else the one the vertex
  // projects into.
  const double sin_tol = std::sin(params.angle_tolerance * std::numbers::pi / 180.0);
  auto was = [&](const ContactKey& k) {
    return std::binary_search(previous.begin(), previous.end(), k);
  };
  auto inside = [&](const ContactKey& k) {
    const BlockView& eb = blocks[k.eblock];
    const int ne = static_cast<int>(eb.vertices.size());
    const Vec2& a = eb.vertices[k.edge];
    const Vec2& b = eb.vertices[wrap(k.edge + 1, ne)];
    const double r = (b - a).dot(blocks[k.vblock].vertices[k.vertex] - a) / (b - a).squaredNorm();
    return r >= 0.0 && r <= 1.0;
  };
  std::vector<char> drop(out.size(), 0);
  for (size_t g = 0; g < out.size();) {
    size_t end = g + 1;
    const ContactKey& k0 = out[g].key;
    while (end < out.size() && out[end].key.vblock == k0.vblock &&
           out[end].key.vertex == k0.vertex && out[end].key.eblock == k0.eblock)
      ++end;
    const BlockView& eb = blocks[k0.eblock];
    const int ne = static_cast<int>(eb.vertices.size());
    for (size_t x = g; x < end; ++x)
      for (size_t y = x + 1; y < end; ++y) {
        if (drop[x] || drop[y]) continue;
        const int ex = out[x].key.edge, ey = out[y].key.edge;
        int shared;
        if (wrap(ex + 1, ne) == ey) shared = ey;
        else if (wrap(ey + 1, ne) == ex) shared = ex;
        else continue;
        // Reflex shared vertex (a notch): both contacts are real.
        const Vec2 u1 = (eb.vertices[shared] - eb.vertices[wrap(shared - 1, ne)]).normalized();
        const Vec2 u2 = (eb.vertices[wrap(shared + 1, ne)] - eb.vertices[shared]).normalized();
        if (u1.x() * u2.y() - u1.y() * u2.x() < -sin_tol) continue;
        const bool wx = was(out[x].key), wy = was(out[y].key);
        bool keep_x;
        if (wx != wy) keep_x = wx;
        else keep_x = inside(out[x].key) || !inside(out[y].key);
        drop[keep_x ? y : x] = 1;
      }
    g = end;
  }
  size_t w = 0;
  for (size_t k = 0; k < out.size(); ++k)
    if (!drop[k]) out[w++] = out[k];
  out.resize(w);
  return out;
}

}  // namespace rheodda::contact
