// Small geometric helpers shared by the files of ContactSystem (internal).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "rheodda/contact/kinematics.hpp"

namespace rheodda::contact {

inline int wrap(int k, int n) { return (k % n + n) % n; }

/// perp(w) = (-w_y, w_x): perp(w).u = w x u.
inline Vec2 perp(const Vec2& w) { return {-w.y(), w.x()}; }

inline Vec2 edge_start(const BlockView& b, int e) { return b.vertices[e]; }
inline Vec2 edge_end(const BlockView& b, int e) {
  return b.vertices[wrap(e + 1, static_cast<int>(b.vertices.size()))];
}
/// Length of edge e of block b [length]: what a locking ratio along it is a fraction of.
inline double edge_length(const BlockView& b, int e) { return (edge_end(b, e) - edge_start(b, e)).norm(); }

/// Fraction along a -> b of the projection of p, clamped to [0, 1].
inline double projection_ratio(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  return std::clamp(ab.dot(p - a) / ab.squaredNorm(), 0.0, 1.0);
}

/// Fraction along a -> b of the projection of p on the line through a and b,
/// not clamped to [0, 1]: the locking point of a shear spring. A vertex that
/// overhangs its edge's end by a little (a corner contact near the edge end,
/// within the search reach) locks where it is; locking it at the clamped end
/// attaches the spring already stretched by the overhang, energy from nowhere
/// (docs/notes/contact-solves.md, "Locking points on the edge's line": the stepped
/// slope of bench/scenes/stepped-toppling.yaml).
inline double line_ratio(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  return ab.dot(p - a) / ab.squaredNorm();
}


/// Reduced mass m_i m_j / (m_i + m_j) of two blocks [mass/length]; a block of
/// infinite (held) or unknown (0) mass leaves the other's; 0 when neither is known.
inline double reduced_mass(double mi, double mj) {
  const bool ki = mi > 0.0 && std::isfinite(mi), kj = mj > 0.0 && std::isfinite(mj);
  if (ki && kj) return mi * mj / (mi + mj);
  return ki ? mi : kj ? mj : 0.0;
}

}  // namespace rheodda::contact
