// The velocity of a block that fixed points begin or stop holding (Engine::edit,
// model_edits.cpp; docs/reference/engine.md, "Fixing and freeing a moving block").
//
// Fixed points added to a moving block are a constraint imposed at once: the
// velocity of each held point, S T(x) v in the directions S it holds, must
// vanish. The constraint acts by an impulse along its rows J (the rows S T(x)
// of every held point): M (v+ - v) = J^T lambda with J v+ = 0, which are the
// conditions of
//   v+ = argmin (w - v)^T M (w - v) over the w with J w = 0
// (Lagrange's equations of impulsive motion), solved as
//   v+ = N (N^T M N)^-1 N^T M v,  N a basis of the null space of J.
// Then (v - v+)^T M v+ = -lambda^T J v+ = 0, so the kinetic energy lost is
// (v - v+)^T M (v - v+)/2 >= 0: Carnot's theorem on sudden constraints (e.g.
// Whittaker, A Treatise on the Analytical Dynamics of Particles and Rigid
// Bodies, on impulsive motion). A block held at every vertex has v+ = 0.
//
// A held rotation (FixedPoint::hold_rotation) is the row g of the block's mean rotation
// (block_terms.hpp, RotationHold): g v = 0 is a zero angular momentum about the centroid,
// rho J g v. Since M^-1 g^T = e_r0 / (rho J), the impulse changes the angular velocity
// alone, by -g v: a spinning block (strain rates zero) stops turning and loses I omega^2/2,
// I = rho J, whatever its shape.
//
// Fixed points removed: a block held by penalty springs carries, in the held
// directions, only the springs' numerical vibration (Shi's v' = 2 D/dt - v on a
// step whose D is the spring's deflection change flips the velocity's sign
// every step, amplitude 2 delta/dt), not a motion: it is dropped by the same
// projection with the removed points' rows, and the freed block starts from
// rest in the directions they held.
#pragma once

#include <Eigen/Dense>

#include "rheodda/core/model.hpp"
#include "rheodda/core/polygon.hpp"

namespace rheodda::core {

/// Rows S T(x) of held points, one per held direction [-, length].
using HeldRows = Eigen::Matrix<double, Eigen::Dynamic, 6>;

/// Appends the rows of a point at x (current position) held in the directions
/// `held` (FixedPoint::held()) to J, for a block of centroid c.
void add_held_rows(HeldRows& J, const Vec2& c, const Vec2& x, const Eigen::Matrix2d& held);

/// Appends the rows of fixed point fp whose material point stands at x on a block of
/// centroid c and central integrals g: its held directions (add_held_rows) and, when it
/// holds the rotation, the row of the block's mean rotation, scaled by the radius of
/// gyration sqrt(J/S) so that it has the units of a point's row [-, length].
void add_fixed_point_rows(HeldRows& J, const Vec2& c, const Vec2& x, const PolygonIntegrals& g, const FixedPoint& fp);

/// v+: the velocity nearest v in the metric M (the block's mass matrix) that
/// leaves every row of J at rest; v when J has no row. `size`: a length of the
/// block (sqrt of its area), to scale the rotation and strain columns [length].
Vec6 held_velocity(const Eigen::Matrix<double, 6, 6>& M, const HeldRows& J, const Vec6& v, double size);

}  // namespace rheodda::core
