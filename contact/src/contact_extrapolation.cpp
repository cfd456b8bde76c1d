// Richardson extrapolation of the contact records for step doubling
// (docs/reference/step-controls.md, "Step doubling").
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"

namespace rheodda::contact {

bool ContactSystem::extrapolate(const ContactSystem& coarse) {
  const std::vector<Contact>& cc = coarse.records_.committed.contacts;
  if (cc.size() != records_.committed.contacts.size() || coarse.penalty_ != penalty_) return false;
  for (size_t k = 0; k < records_.committed.contacts.size(); ++k) {
    const Contact& f = records_.committed.contacts[k];
    const Contact& c = cc[k];
    if (!(f.key == c.key) || f.joint_set != c.joint_set || f.state != c.state ||
        f.intact != c.intact || (f.rheology >= 0) != (c.rheology >= 0) ||
        f.creep_failed != c.creep_failed ||
        (f.state == ContactState::sliding && f.slide_direction != c.slide_direction))
      return false;
  }
  // Richardson: y_f - y = C dt^2/2 and y_c - y = C dt^2 to leading order, so
  // 2 y_f - y_c cancels the leading error (docs/reference/step-controls.md).
  auto richardson = [](double& fine, double c) { fine = 2.0 * fine - c; };
  for (size_t k = 0; k < records_.committed.contacts.size(); ++k) {
    Contact& f = records_.committed.contacts[k];
    const Contact& c = cc[k];
    richardson(f.locking_ratio, c.locking_ratio);
    richardson(f.normal_force, c.normal_force);
    richardson(f.shear_force, c.shear_force);
    richardson(f.shear_displacement, c.shear_displacement);
    richardson(f.penetration, c.penetration);
    richardson(f.creep_displacement, c.creep_displacement);
    if (f.rheology < 0) continue;
    laws::RheologyState& qf = records_.committed.rheology[f.rheology];
    const laws::RheologyState& qc = coarse.records_.committed.rheology[c.rheology];
    // Both runs start from the same history, so the fine run's creep over the
    // step is the coarse one's plus qf.creep() - qc.creep(); the extrapolated
    // increment is 2 (that) - coarse's.
    const double creep_fine_minus_coarse = qf.creep() - qc.creep();
    for (size_t i = 0; i < qf.q.size(); ++i) richardson(qf.q[i], qc.q[i]);
    // Damage of a damage law: extrapolated like the displacements, but never
    // to failure or below 0 by extrapolation (the fine value is kept then).
    if (const double d = 2.0 * qf.damage - qc.damage; d >= 0.0 && d < 1.0) qf.damage = d;
    records_.committed.creep[k] = coarse.records_.committed.creep[k] + 2.0 * creep_fine_minus_coarse;
  }
  return true;
}

}  // namespace rheodda::contact
