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
      if (wedge_score(vb, v, n) < -sin_tol) continue;
      const double len = contact_length(vb, v, eb, e, d0, cos_tol);
      out.push_back({{iv, v, ie, e}, len > 0.0 ? ContactKind::edge_edge : ContactKind::vertex_edge,
                     len});
    }
  }
}

}  // namespace

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
      const std::array<ContactKey, 4> cand{ContactKey{ia, k, ib, wrap(m - 1, nb)},
                                           ContactKey{ia, k, ib, m},
                                           ContactKey{ib, m, ia, wrap(k - 1, na)},
                                           ContactKey{ib, m, ia, k}};
      std::array<double, 4> score{};
      double best = -2.0;
      for (int c = 0; c < 4; ++c) {
        const BlockView& eb = blocks[cand[c].eblock];
        const int ne = static_cast<int>(eb.vertices.size());
        const Vec2 n =
            outward_normal(eb.vertices[cand[c].edge], eb.vertices[wrap(cand[c].edge + 1, ne)]);
        score[c] = wedge_score(blocks[cand[c].vblock], cand[c].vertex, n);
        best = std::max(best, score[c]);
      }
      // Among the candidates tied with the best score, prefer one whose vertex
      // projects inside its edge, then the contact of the last step, then the order above.
      std::array<bool, 4> in_range{}, was{};
      for (int c = 0; c < 4; ++c) {
        const BlockView& eb = blocks[cand[c].eblock];
        const int ne = static_cast<int>(eb.vertices.size());
        const Vec2& a = eb.vertices[cand[c].edge];
        const Vec2& b = eb.vertices[wrap(cand[c].edge + 1, ne)];
        const double l2 = (b - a).squaredNorm();
        const double r = (b - a).dot(blocks[cand[c].vblock].vertices[cand[c].vertex] - a) / l2;
        in_range[c] = r >= -1e-9 && r <= 1.0 + 1e-9;
        was[c] = std::binary_search(previous.begin(), previous.end(), cand[c]);
      }
      int chosen = -1;
      for (int pass = 0; pass < 4 && chosen < 0; ++pass)
        for (int c = 0; c < 4 && chosen < 0; ++c) {
          if (score[c] < best - sin_tol) continue;
          const bool ok = pass == 0 ? (in_range[c] && was[c])
                        : pass == 1 ? in_range[c]
                        : pass == 2 ? was[c]
                                    : true;
          if (ok) chosen = c;
        }
      const ContactKey& key = cand[chosen];
      const double len = contact_length(blocks[key.vblock], key.vertex, blocks[key.eblock], key.edge,
                                        d0, cos_tol);
      out.push_back({key, len > 0.0 ? ContactKind::edge_edge : ContactKind::vertex_vertex, len});
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
  return out;
}

}  // namespace rheodda::contact
