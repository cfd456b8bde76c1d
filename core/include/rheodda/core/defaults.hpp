// The defaults that depend on the model, in one place: the scene loader fills them
// into a scene (scene/src/loader.cpp), the contact adapter and the engine apply
// them to a Model that leaves them at 0 (a test's hand-written model).
#pragma once

#include <algorithm>
#include <vector>

#include "rheodda/core/model.hpp"
#include "rheodda/core/polygon.hpp"

namespace rheodda::core {

/// k1 of Shi's normal penalty p_n = k1 E (the seed's eq. 17, k1 = 10-100) [-].
inline constexpr double kPenaltyFactor = 40.0;
/// Fixed-point spring / E: Shi's code holds fixed points with 10-100 E (dda.md) [-].
inline constexpr double kFixedPointFactor = 100.0;

/// The largest Young's modulus of `materials`, each read by `young_modulus` [stress]; 0 for none.
template <class Range, class Modulus>
double largest_young_modulus(const Range& materials, Modulus young_modulus) {
  double e = 0.0;
  for (const auto& m : materials) e = std::max(e, young_modulus(m));
  return e;
}
inline double largest_young_modulus(const std::vector<Material>& materials) {
  return largest_young_modulus(materials, [](const Material& m) { return m.young_modulus; });
}

/// The normal contact penalty p_n = k1 E_max [stress].
inline double default_penalty(double largest_young_modulus) { return kPenaltyFactor * largest_young_modulus; }

/// The fixed-point spring 100 E_max [force/length].
inline double default_fixed_point_stiffness(double largest_young_modulus) {
  return kFixedPointFactor * largest_young_modulus;
}

/// Stiffness of the rotational spring of a fixed point held in rotation
/// (FixedPoint::hold_rotation), k_r = p J/S = p rho_g^2 [force x length/rad, per unit
/// thickness]: the fixed-point spring p [force/length] spread evenly over the block's
/// area S [length^2], which resists a rotation theta about the centroid with the moment
/// int (p/S) |x - c|^2 theta dA = p (J/S) theta, J = int |x - c|^2 dA the polar second
/// moment of area [length^4] and rho_g^2 = J/S the polar radius of gyration squared
/// [length^2]. It gives the held rotation the frequency of a point held by p,
/// k_r/(rho J) = p/(rho S) = p/m (the explicit step's stable cycle: no shorter than
/// a fixed point's). `vertices`: the block's polygon, either orientation [length]; or its
/// central integrals (polygon.hpp).
inline double rotation_hold_stiffness(double fixed_point_stiffness, const PolygonIntegrals& central) {
  return fixed_point_stiffness * (central.Sxx + central.Syy) / central.S;  // J/S: a clockwise polygon's signs cancel
}
inline double rotation_hold_stiffness(double fixed_point_stiffness, std::span<const Vec2> vertices) {
  return rotation_hold_stiffness(fixed_point_stiffness, central_integrals(vertices));
}

/// Shi's half model size w0: half the larger side of the model's bounding box [length];
/// the step limit is max_displacement_ratio w0 and the contact search reaches search_factor max_displacement_ratio w0.
inline double half_model_size(double width, double height) { return 0.5 * std::max(width, height); }

}  // namespace rheodda::core
