// Goodman & Bray (1976) block toppling: the textbook 16-block slope on a
// stepped base (Hoek & Bray, Rock Slope Engineering, 3rd ed., worked example:
// dx = 10 m, a1 = 5 m, a2 = 5.2 m, b = 1 m, base steps dipping 30 deg, crest
// over block 10; limiting equilibrium at phi = 38.15 deg), and its
// limit-equilibrium analysis, written here independently of the DDA code.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rheodda::testing::goodman_bray {

/// Geometry in the frame of the base steps (x' up the steps, y' normal to them) [m].
struct Slope {
  double alpha_deg = 30.0;  ///< dip of the base steps (and of the frame) [deg]
  double dx = 10.0;         ///< block width [m]
  double a1 = 5.0;          ///< rise of the face per block [m]
  double a2 = 5.2;          ///< fall of the upper slope per block [m]
  double b = 1.0;           ///< step height of the base [m]
  int blocks = 16;
  int crest = 10;           ///< last block below the crest
  /// Height y_n of block n (1-based): n (a1 - b) below the crest, then y_{n-1} - a2 - b.
  double height(int n) const {
    if (n <= crest) return n * (a1 - b);
    return height(n - 1) - a2 - b;
  }
};

/// Force P_0 [per unit weight density and thickness: m^2] needed at the
/// toe for limiting equilibrium at friction angle phi (the same on base and
/// sides), Goodman & Bray's step-by-step analysis from the crest down:
///   toppling: P_{n-1} = [P_n (M_n - dx tan phi) + W_n/2 (y_n sin a - dx cos a)] / L_n
///   sliding:  P_{n-1} = P_n - W_n (cos a tan phi - sin a) / (1 - tan^2 phi)
/// with W_n = y_n dx, M_n and L_n the lever arms of P_n and P_{n-1}; a block
/// topples when y_n / dx > cot a, and once a block slides all below slide.
/// The slope is stable iff P_0 <= 0.
inline double toe_force(const Slope& s, double phi_deg) {
  const double a = s.alpha_deg * std::numbers::pi / 180.0, t = std::tan(phi_deg * std::numbers::pi / 180.0);
  double P = 0.0;
  bool sliding = false;
  for (int n = s.blocks; n >= 1; --n) {
    const double y = s.height(n), W = y * s.dx;
    double M, L;
    if (n < s.crest) { M = y; L = y - s.a1; }
    else if (n == s.crest) { M = y - s.a2; L = y - s.a1; }
    else { M = y - s.a2; L = y; }
    const double p_slide = P - W * (std::cos(a) * t - std::sin(a)) / (1.0 - t * t);
    double p_topple = -1e300;
    if (y / s.dx > 1.0 / std::tan(a) && L > 0.0)
      p_topple = (P * (M - s.dx * t) + 0.5 * W * (y * std::sin(a) - s.dx * std::cos(a))) / L;
    double next;
    if (sliding || p_slide > p_topple) { next = p_slide; sliding = sliding || (p_slide > p_topple && p_slide > 0.0); }
    else next = p_topple;
    P = std::max(next, 0.0);
    if (n == 1) return next;
  }
  return P;
}

/// Friction angle [deg] at which P_0 = 0 (bisection).
inline double critical_friction_angle(const Slope& s) {
  double lo = 5.0, hi = 80.0;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (toe_force(s, mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace rheodda::testing::goodman_bray
