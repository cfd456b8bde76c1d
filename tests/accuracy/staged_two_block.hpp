// The seed's two-block shear creep test (Section 4; Burgers joint of Table 1
// row 1; MPa, mm, h) under a staged shear load with unloading: tau from 0 h,
// ramp to 2 tau over 80-85.5 h, ramp to 0 over 140-143.3 h, 0-200 h; shared by
// the adaptive stepping and step doubling tests. Reference: the Boltzmann
// superposition of the closed form (eqs. 20-21), exact() below.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "rheodda/core/model.hpp"
#include "rheodda/laws/registry.hpp"
#include "two_block.hpp"  // tests/models

namespace rheodda::test::staged {

constexpr double kSigma = 1.408, kTau = 0.232;  // [MPa]
constexpr double kE1 = 26.87, kE2 = 192.43, kEta1 = 34807.72, kEta2 = 2141.23;  // Table 1 row 1
constexpr double kStage2 = 80.0, kStage3 = 140.0, kEnd = 200.0;  // ramp starts, end [h]
constexpr double kRamp2 = 85.5, kRamp3 = 143.3;                  // ramp ends [h]

/// Joint displacement under the staged load [mm]: tau J(t) plus, per ramp of
/// slope s from a to b, s (I(t - a) - I(t - b)), with the Burgers creep
/// compliance (the seed's eqs. 20-21) J(u) = 1/E1 + (1 - exp(-E2 u/eta2))/E2 +
/// u/eta1 and I(u) = int_0^max(u,0) J.
inline double exact(double t) {
  auto J = [](double u) { return 1 / kE1 + (1 - std::exp(-kE2 * u / kEta2)) / kE2 + u / kEta1; };
  auto I = [](double u) {
    u = std::max(u, 0.0);
    return u / kE1 + u / kE2 - kEta2 / (kE2 * kE2) * (1 - std::exp(-kE2 * u / kEta2)) +
           u * u / (2 * kEta1);
  };
  const double s2 = kTau / (kRamp2 - kStage2), s3 = -2 * kTau / (kRamp3 - kStage3);
  return kTau * J(t) + s2 * (I(t - kStage2) - I(t - kRamp2)) + s3 * (I(t - kStage3) - I(t - kRamp3));
}

using models::rect;

/// Block A (w x w) on block B (3w x w, fixed by three fixed points), static
/// analysis without gravity, first step dt [h]; no loads yet (tests/models/two_block.hpp).
inline core::Model two_blocks(double w, double dt) { return models::two_block_model(w, dt); }

/// The normal load sigma w and the staged shear load on A at the joint line [N].
inline void add_staged_loads(core::Model& m, double w) {
  m.point_loads.push_back({1, {0.5 * w, 0.0}, {{0.0, {0.0, -kSigma * w}}}});
  m.point_loads.push_back({1,
                           {0.5 * w, 0.0},
                           {{0.0, {kTau * w, 0.0}},
                            {kStage2, {kTau * w, 0.0}},
                            {kRamp2, {2 * kTau * w, 0.0}},
                            {kStage3, {2 * kTau * w, 0.0}},
                            {kRamp3, {0.0, 0.0}}}});
}

/// The Burgers law of Table 1 row 1 [MPa/mm, MPa h/mm].
inline std::shared_ptr<const laws::ContactRheology> burgers_row1() {
  return laws::LawRegistry::builtin().create(
      "burgers", {{"E1", kE1}, {"E2", kE2}, {"eta1", kEta1}, {"eta2", kEta2}});
}

}  // namespace rheodda::test::staged
