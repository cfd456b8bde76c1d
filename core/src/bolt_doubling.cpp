// The bolts under step doubling (Settings::step_tolerance; docs/reference/step-controls.md,
// "Step doubling"): their part of the error estimate, and the Richardson
// extrapolation of their states, as the contacts' (ContactModel::extrapolate).
#include <algorithm>
#include <cmath>

#include "bolts.hpp"

namespace rheodda::core {

double BoltSet::creep_difference(const std::vector<BoltState>& fine, const std::vector<BoltState>& coarse) {
  double worst = 0.0;
  for (std::size_t k = 0; k < fine.size() && k < coarse.size(); ++k)
    worst = std::max(worst, std::abs(fine[k].creep_elongation() - coarse[k].creep_elongation()));
  return worst;
}

bool BoltSet::same_modes(const std::vector<BoltState>& fine, const std::vector<BoltState>& coarse) {
  if (fine.size() != coarse.size()) return false;
  for (std::size_t k = 0; k < fine.size(); ++k) {
    if (fine[k].state != coarse[k].state) return false;
    if (fine[k].state == BoltMode::yielding && (fine[k].force >= 0.0) != (coarse[k].force >= 0.0)) return false;
  }
  return true;
}

void BoltSet::extrapolate(const Model& m, const std::vector<BlockState>& blocks, std::vector<BoltState>& fine,
                          const std::vector<BoltState>& coarse) {
  for (std::size_t k = 0; k < fine.size(); ++k) {
    BoltState& s = fine[k];
    const BoltState& c = coarse[k];
    if (s.state == BoltMode::ruptured) continue;  // as it ruptured in the finer run
    const Bolt& bolt = m.bolts[k];
    for (std::size_t i = 0; i < s.rheology.q.size(); ++i) s.rheology.q[i] = 2.0 * s.rheology.q[i] - c.rheology.q[i];
    s.rheology.damage = 2.0 * s.rheology.damage - c.rheology.damage;
    s.plastic_elongation = 2.0 * s.plastic_elongation - c.plastic_elongation;
    const auto [xa, xb] = bolt_ends(bolt, blocks);
    s.length = (xb - xa).norm();
    s.elongation = s.length - bolt_rest_length(bolt);
    // (1) of docs/reference/bolts.md: N = k (e - e_p - e_c), |N| <= N_y; a yielding
    // bolt (or one the extrapolation takes beyond N_y) at N_y, its plastic
    // elongation taking up the rest.
    const double kb = bolt.axial_stiffness;
    double force = kb * (s.elongation - s.plastic_elongation - s.creep_elongation());
    if (s.state == BoltMode::yielding || std::abs(force) > bolt.yield_force) {
      const double sign = s.state == BoltMode::yielding ? (s.force >= 0.0 ? 1.0 : -1.0) : (force >= 0.0 ? 1.0 : -1.0);
      force = sign * bolt.yield_force;
      s.plastic_elongation = s.elongation - s.creep_elongation() - force / kb;
      s.state = BoltMode::yielding;
    }
    s.force = force;
  }
}

}  // namespace rheodda::core
