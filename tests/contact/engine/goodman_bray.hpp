// Goodman & Bray (1976) block toppling: the textbook 16-block slope on a
// stepped base (Hoek & Bray, Rock Slope Engineering, 3rd ed., worked example:
// dx = 10 m, a1 = 5 m, a2 = 5.2 m, b = 1 m, base steps dipping 30 deg, crest
// over block 10; limiting equilibrium at phi = 38.15 deg), and its
// limit-equilibrium analysis, written here independently of the DDA code.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
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

/// How a block fails in the limit-equilibrium analysis.
enum class Mode { stable, topples, slides };

/// One block of the analysis: its height, lever arms, the two candidate forces on
/// its lower side and the one taken [m^2: per unit weight density and thickness].
struct BlockForces {
  int n;                       ///< block (1 = toe)
  double y, M, L;              ///< height y_n, lever arms M_n (of P_n), L_n (of P_{n-1}) [m]
  double p_topple, p_slide;    ///< P_{n-1,t} (-inf where L_n <= 0), P_{n-1,s}
  Mode mode;
  double p;                    ///< P_{n-1} taken: P_{n-1,t} or P_{n-1,s}
};

/// Goodman & Bray's step-by-step analysis from the crest down at friction angle phi
/// (the same on base and sides), block 16 first (Goodman & Bray 1976; Hoek & Bray, Rock
/// Slope Engineering, 3rd ed., ch. 10; Wyllie & Mah, Rock Slope Engineering, 4th ed.,
/// section 9.4.3):
///   toppling: P_{n-1,t} = [P_n (M_n - dx tan phi) + W_n/2 (y_n sin a - dx cos a)] / L_n
///   sliding:  P_{n-1,s} = P_n - W_n (cos a tan phi - sin a) / (1 - tan^2 phi)
/// with W_n = y_n dx, M_n and L_n the lever arms of P_n and P_{n-1}
/// (n below the crest: y_n, y_n - a1; at it: y_n - a2, y_n - a1; above it:
/// y_n - a2, y_n). The blocks fall in three zones, as the method takes them: from
/// the top, the stable blocks (P_{n-1} = 0) down to the first block slender enough
/// to topple on its own (y_n / dx > cot a); from it down, the toppling blocks
/// (P_{n-1} = P_{n-1,t}), whatever their slenderness, since the thrust P_n from
/// above tips them too, down to the first block for which P_{n-1,s} > P_{n-1,t}:
/// it and every block below it slide. (A block of the top zone with P_{n-1,s} > 0,
/// phi < a, slides, and so do all below it.) A negative P_{n-1} is passed down as 0,
/// except the toe's P_0.
inline std::vector<BlockForces> analysis(const Slope& s, double phi_deg) {
  const double a = s.alpha_deg * std::numbers::pi / 180.0, t = std::tan(phi_deg * std::numbers::pi / 180.0);
  std::vector<BlockForces> rows;
  double P = 0.0;  // P_n, the force on block n's upper side
  Mode zone = Mode::stable;
  for (int n = s.blocks; n >= 1; --n) {
    const double y = s.height(n), W = y * s.dx;
    double M, L;
    if (n < s.crest) { M = y; L = y - s.a1; }
    else if (n == s.crest) { M = y - s.a2; L = y - s.a1; }
    else { M = y - s.a2; L = y; }
    const double p_slide = P - W * (std::cos(a) * t - std::sin(a)) / (1.0 - t * t);
    // L_n <= 0 (the toe block, whose face rises above the next step): it cannot tip about its toe.
    const double p_topple = L > 0.0 ? (P * (M - s.dx * t) + 0.5 * W * (y * std::sin(a) - s.dx * std::cos(a))) / L
                                    : -std::numeric_limits<double>::infinity();
    if (zone == Mode::stable && p_slide > 0.0) zone = Mode::slides;
    if (zone == Mode::stable && y / s.dx > 1.0 / std::tan(a)) zone = Mode::topples;
    if (zone == Mode::topples && p_slide > p_topple) zone = Mode::slides;
    const double p = zone == Mode::topples ? p_topple : p_slide;
    rows.push_back({n, y, M, L, p_topple, p_slide, zone, p});
    P = std::max(p, 0.0);
  }
  return rows;
}

/// Force P_0 [m^2] needed at the toe for limiting equilibrium at friction angle phi
/// (analysis): the slope is stable iff P_0 <= 0.
inline double toe_force(const Slope& s, double phi_deg) { return analysis(s, phi_deg).back().p; }

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
