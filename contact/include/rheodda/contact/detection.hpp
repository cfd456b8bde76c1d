// Narrow phase: which vertex touches which edge.
//
// Every DDA contact is a vertex of one block against an edge (the entrance
// edge) of another (Shi 1988; the seed's Section 3.1 and Figure 4):
//   vertex-edge    a vertex within the search distance of an edge's interior;
//   vertex-vertex  two vertices within the search distance; the angle rule
//                  picks which of the four edges at the two vertices is the
//                  entrance edge (below);
//   edge-edge      two antiparallel edges overlapping over a length L: found as
//                  the two vertex-edge contacts at the ends of the overlap, each
//                  with contact length L/2 (the seed: "the contact length of each
//                  contact point is half of the total contact length").
//
// Corners only. The entering vertex must be a corner: convex, and not a
// straight angle within the angle tolerance. A vertex that only subdivides a
// straight side (a joint trace ending there) never enters an edge, and a
// reflex vertex cannot poke into anything.
//
// Angle rule. A vertex p can enter an edge only if both edges of p's block at p
// stay on the outer side of that edge's line: with n the edge's outward normal
// and u1, u2 the unit directions of p's two edges, the score min(n.u1, n.u2)
// must be >= -sin(angle tolerance). For a vertex-vertex pair the candidate
// with the highest score wins; candidates within sin(tolerance) of the best are
// tied. A corner sitting in a notch (the other vertex is reflex) touches both
// edges of the notch: every valid candidate is kept. Otherwise every tied candidate that was a contact in the last step is kept (so
// contacts keep their identity, also where two blocks slide past a
// straight-angle vertex and both vertices touch); if none was, one is taken:
// preferably one whose vertex projects inside its edge, then in a fixed order.
#pragma once

#include <compare>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "rheodda/contact/kinematics.hpp"

namespace rheodda::contact {

/// Identity of a contact: vertex `vertex` of block `vblock` against edge `edge`
/// (vertex edge -> edge+1, counter-clockwise) of block `eblock`.
struct ContactKey {
  int vblock = 0;
  int vertex = 0;
  int eblock = 0;
  int edge = 0;
  auto operator<=>(const ContactKey&) const = default;
};

/// How a contact was found.
enum class ContactKind : std::uint8_t {
  vertex_edge,    ///< vertex against the interior of an edge
  vertex_vertex,  ///< two vertices; entrance edge chosen by the angle rule
  edge_edge       ///< one end of two overlapping antiparallel edges (length = half the overlap)
};

/// Name used in outputs: "vertex_edge", "vertex_vertex", "edge_edge".
const char* contact_kind_name(ContactKind kind);

/// A detected contact.
struct DetectedContact {
  ContactKey key;
  ContactKind kind = ContactKind::vertex_edge;
  double length = 0.0;  ///< contact length [length]: half the shared length (edge-edge), else 0
};

/// Tributary length of a point contact [length]: the joint length that vertex
/// v of block `vb` stands for against an entrance edge of unit direction t,
/// the longer projection on t of the two half edges of `vb` at v,
///     l_t = max_f (l_f / 2) |t_f . t|      (f the two edges at v, l_f their lengths).
/// Why: a creep law works per unit joint area (the seed applies it to
/// angle-line contacts too, its section 3.2), so a point contact needs a
/// length. This one equals the edge-edge contact length of the same vertex
/// (half the overlap, the seed's section 3.1) when the edge lies on the
/// entrance edge over its whole length, so a contact whose block tilts off a
/// face onto its corner keeps its joint length through the change of kind; it
/// varies continuously as the block rotates (docs/reference/rheology-in-dda.md,
/// "The tributary length of a point contact").
double point_tributary_length(const BlockView& vb, int v, const Vec2& t);

/// Narrow-phase tolerances.
struct DetectionParams {
  double search_distance = 0.0;  ///< d0 = 2.5 max_displacement_ratio w0 [length]
  double angle_tolerance = 3.0;  ///< [deg]
  /// A corner in a notch touches a notch edge while its projection lies on the
  /// edge or beyond the notch's vertex by at most this much (docs/reference/contacts.md,
  /// "Contact types"); the contact system passes the allowed penetration [length].
  /// Negative: no limit (both notch edges whatever the projection).
  double notch_reach = -1.0;
};

/// Contacts between blocks `ia` and `ib` (both orders), appended to `out`.
/// `previous` holds the keys of the last step's contacts, sorted (angle-rule ties).
void detect_pair(std::span<const BlockView> blocks, int ia, int ib, const DetectionParams& params,
                 std::span<const ContactKey> previous, std::vector<DetectedContact>& out);

/// All contacts among the candidate block pairs, sorted by key, without duplicates.
std::vector<DetectedContact> detect_contacts(std::span<const BlockView> blocks,
                                             std::span<const std::pair<int, int>> pairs,
                                             const DetectionParams& params,
                                             std::span<const ContactKey> previous);

}  // namespace rheodda::contact
