// The seed's two-block shear creep test (Section 4, Figure 6): block A on
// block B, B fixed, normal force F1 and shear force F2 on A below the friction
// limit. Units MPa, mm, h, unit thickness [mm]: forces per unit thickness are
// N/mm = MPa mm. Static analysis (dynamic ratio 0), no gravity.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/laws/registry.hpp"
#include "rheodda/laws/seed_table1.hpp"
#include "sim.hpp"

namespace rheodda::testing {

/// The seed's Table 1 (laws/seed_table1.hpp).
using Table1Row = laws::SeedTable1Row;
inline constexpr const auto& kTable1 = laws::kSeedTable1;

inline std::shared_ptr<const laws::ContactRheology> make_law(const std::string& name,
                                                             const laws::ParameterValues& p) {
  return laws::LawRegistry::builtin().create(name, p);
}

inline std::shared_ptr<const laws::ContactRheology> table1_burgers(const Table1Row& r) {
  return make_law("burgers", {{"E1", r.E1}, {"E2", r.E2}, {"eta1", r.eta1}, {"eta2", r.eta2}});
}

/// Two-block creep scene: A = [0, w] x [0, w] on B = [-w, 2w] x [-w, 0], w = 100 mm.
/// Blocks are 1e6 times stiffer than the joint, so block strain does not
/// pollute the joint displacement (which is read from the contacts anyway).
/// With a tilt [rad], A is rotated counter-clockwise by it about the origin:
/// it stands on its corner (0, 0), one vertex-edge contact, and both forces
/// act at that corner.
struct CreepScene {
  static constexpr double w = 100.0;  ///< width of A = joint length [mm]
  core::Model model;
  contact::JointSet joint;

  CreepScene(std::shared_ptr<const laws::ContactRheology> law, double sigma, double tau, double dt,
             double tilt = 0.0) {
    core::Model& m = model;
    m.materials[0].young_modulus = 1e7;  // [MPa]
    m.materials[0].density = 1e-12;      // [MPa h^2/mm^2]: no inertia at creep time scales
    m.settings.dt = dt;                  // [h]
    m.settings.dynamic_ratio = 0.0;      // static analysis
    m.settings.gravity = {0.0, 0.0};
    add_fixed(m, rect(-w, -w, 2 * w, 0.0));
    m.blocks.push_back(block(rect(0.0, 0.0, w, w, tilt)));
    // F1 (normal, down) and F2 (shear, +x) at the joint line (at the corner
    // when tilted), so A takes no moment.
    const Vec2 at = tilt == 0.0 ? Vec2(0.5 * w, 0.0) : Vec2(0.0, 0.0);
    core::PointLoad normal{1, at, {{0.0, {0.0, -sigma * w}}}};
    core::PointLoad shear{1, at, {{0.0, {tau * w, 0.0}}}};
    m.point_loads = {normal, shear};
    joint.name = "joint";
    joint.friction_angle = 60.0;       // tan = 1.73 > tau/sigma of every Table 1 row
    joint.normal_stiffness = 1e4;      // [MPa/mm]
    joint.law = std::move(law);
  }
};

/// A law on the creep scene's joint: its name, parameters, and the joint's elastic
/// shear_stiffness where the law has no instantaneous spring (Kelvin: tau/k_s) [MPa/mm].
struct LawCase {
  std::string name, law;
  laws::ParameterValues p;
  std::optional<double> shear_stiffness;
};

/// The laws besides Burgers with Table 1's first row's constants: Maxwell, Kelvin, and
/// Nishihara below its threshold (no viscoplastic creep) and above it.
inline std::vector<LawCase> other_law_cases() {
  const Table1Row& r = kTable1[0];
  return {
      {"maxwell", "maxwell", {{"E1", r.E1}, {"eta1", r.eta1}}, std::nullopt},
      {"kelvin", "kelvin", {{"E2", r.E2}, {"eta2", r.eta2}}, 30.0},
      {"nishihara below Fs", "nishihara",
       {{"E1", r.E1}, {"E2", r.E2}, {"eta2", r.eta2}, {"eta3", 5000.0}, {"Fs", 0.3}}, std::nullopt},
      {"nishihara above Fs", "nishihara",
       {{"E1", r.E1}, {"E2", r.E2}, {"eta2", r.eta2}, {"eta3", 5000.0}, {"Fs", 0.15}}, std::nullopt},
  };
}

/// Joint's relative shear displacement [mm], in the direction of F2 (+x): mean
/// over the contacts of A's base (B's top edge runs in -x).
inline double joint_shear(const contact::ContactSystem& cs) {
  double sum = 0.0;
  int n = 0;
  for (const contact::Contact& c : cs.contacts())
    if (c.key.vblock == 1 && c.state != contact::ContactState::open) {
      sum -= c.shear_displacement;
      ++n;
    }
  return n ? sum / n : 0.0;
}

}  // namespace rheodda::testing
