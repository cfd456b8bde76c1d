// The springs of a contact (the seed's eqs. 17-18, 23-29; docs/reference/contacts.md,
// "Springs"): its linearized geometry on the step-start configuration, normal
// and shear springs, dashpots, and their terms in the global system.
#include "rheodda/contact/contact_system.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact_geometry.hpp"
#include "rheodda/contact/strength.hpp"

namespace rheodda::contact {

void ContactSystem::prepare(std::span<const BlockView> blocks, const Contact& c, Hot& h) const {
  const BlockView& bi = blocks[c.key.vblock];
  const BlockView& bj = blocks[c.key.eblock];
  const Vec2& p = bi.vertices[c.key.vertex];
  const Vec2 a = edge_start(bj, c.key.edge), b = edge_end(bj, c.key.edge);
  const double l = (b - a).norm();
  const Vec2 t = (b - a) / l;

  // Normal: d_n = S / l with S = (a - p) x (b - p) > 0 when p is inside block j
  // (Shi 1988, the determinant form of the distance of P1 to P2P3); linearized
  // in the displacements u = T D of p, a and b.
  const double S = (a - p).x() * (b - p).y() - (a - p).y() * (b - p).x();
  h.dn0 = S / l;
  h.ni = displacement_matrix(bi.centroid, p).transpose() * perp(b - a) / l;
  h.nj = -(displacement_matrix(bj.centroid, a).transpose() * perp(b - p) +
           displacement_matrix(bj.centroid, b).transpose() * perp(p - a)) / l;

  // Shear: d_t = (P0P1 . P2P3)/l + H^T D_i + G^T D_j (the seed's eqs. 23-24, 27),
  // P0 the locking point on the entrance edge.
  const Vec2 p0 = a + c.locking_ratio * (b - a);
  h.dt0 = t.dot(p - p0);
  h.ti = displacement_matrix(bi.centroid, p).transpose() * t;
  h.tj = -displacement_matrix(bj.centroid, p0).transpose() * t;

  // Springs: penalty (eq. 17, one value for every contact point), or the joint
  // stiffness per unit area times the contact's tributary length l_t (its
  // length for an edge-edge contact, point_tributary_length for a point
  // contact), so that the joint's per-area response holds on every contact
  // and a contact's springs do not jump when it changes kind. With the contact
  // length instead, a column that rises off one base corner turns its other
  // base contact from edge-edge into a point contact whose shear spring jumps
  // from the joint's to the penalty's with the stretch it had, and slides
  // (docs/notes/contact-solves.md, "Springs of a joint on point contacts").
  const JointSet& js = joint_sets_[c.joint_set];
  const double lt = c.tributary_length > 0.0 ? c.tributary_length : c.length;  // [length]
  h.pn = (js.normal_stiffness && lt > 0.0) ? *js.normal_stiffness * lt : penalty_;
  h.ps = (js.shear_stiffness && lt > 0.0) ? *js.shear_stiffness * lt
                                          : penalty_ / settings_.shear_normal_ratio;
  // A creep law's instantaneous spring E1 [stress/length] is the joint's elastic
  // shear stiffness, so a run reproduces the law's instantaneous response.
  if (js.law && lt > 0.0)
    if (const auto e1 = js.law->instantaneous_stiffness()) h.ps = *e1 * lt;
  // Dashpots c = 2 zeta sqrt(k m) beside the springs (JointSet::restitution),
  // m the reduced mass m_i m_j / (m_i + m_j) of the two blocks: the mass that
  // oscillates on the contact spring (the moving block's own mass against a
  // held one, infinite; one block's mass where the other's is unknown, 0).
  h.cn = h.cs = 0.0;
  h.reduced_mass = reduced_mass(bi.mass, bj.mass);
  if (js.restitution) {
    const double zeta = restitution_damping_ratio(*js.restitution);
    h.cn = 2.0 * zeta * std::sqrt(h.pn * h.reduced_mass);
    h.cs = 2.0 * zeta * std::sqrt(h.ps * h.reduced_mass);
  }
  h.tan_phi = tan_deg(js.friction_angle_of(c.intact));
  h.cohesion = js.cohesion_of(c.intact);
  h.tensile_strength = c.intact ? js.tensile_strength : 0.0;
}

double ContactSystem::normal_dashpot(size_t c) const {
  return step_.dt > 0.0 && step_.dynamic ? step_.hot[c].cn / step_.dt : 0.0;
}

double ContactSystem::shear_dashpot(size_t c) const {
  return step_.dt > 0.0 && step_.dynamic ? step_.hot[c].cs / step_.dt : 0.0;
}

double ContactSystem::reversal_stiffness(size_t c) const {
  // The smallest backward slip of a sliding contact that counts as a reversal
  // is f_res / k, the slip a force residual f_res moves the vertex by. Static
  // steps, or unset: Shi's shear spring k_s. Dynamic steps
  // (ContactSettings::reversal_at_normal_resolution): the normal spring p_n
  // plus the step's inertia on the contact, m_red / (beta dt^2) (the Newmark
  // term the host adds to the block's stiffness; m_red the reduced mass of the
  // two blocks). Why: with a soft joint f_res / k_s exceeds a small step's
  // slip, so a vertex moving backwards would keep its friction force pushing it
  // on, friction doing negative work (docs/notes/contact-solves.md, "Friction
  // that pushed"); and with p_n alone the resolution is a fixed length while
  // the backward slip of a contact whose friction exceeds its drive shrinks as
  // dt^2 (the inertia holds it), so contacts that stop would stay sliding, the
  // more the smaller the step, and the joints' shear displacement would not
  // converge (docs/notes/contact-solves.md, "Contacts that stop").
  const Hot& h = step_.hot[c];
  if (!(settings_.reversal_at_normal_resolution && step_.dynamic)) return shear_stiffness(c);
  return h.pn + h.reduced_mass * step_.inertia;
}

double ContactSystem::shear_stiffness(size_t c) const {
  // Creep compliance folded into the spring: k_eff = k / (1 + k c) (laws/contact_rheology.hpp).
  const double k = step_.hot[c].ps;
  return k / (1.0 + k * step_.seams[c].compliance);
}

void ContactSystem::assemble(std::span<const BlockView>, SystemSink& sink) const {
  for (size_t c = 0; c < records_.work.contacts.size(); ++c) {
    const Contact& r = records_.work.contacts[c];
    const int i = r.key.vblock, j = r.key.eblock;
    if (r.state == ContactState::open) {
      // A zero block keeps the matrix pattern of the pair through the
      // open-close iteration, so the host can reuse its symbolic factorisation.
      sink.add_stiffness(i, j, Mat6::Zero());
      continue;
    }
    const Hot& h = step_.hot[c];
    // Normal spring: energy p_n d_n^2 / 2 (Shi 1988).
    Mat6 kii = h.pn * h.ni * h.ni.transpose();
    Mat6 kjj = h.pn * h.nj * h.nj.transpose();
    Mat6 kij = h.pn * h.ni * h.nj.transpose();
    Vec6 fi = -h.pn * h.dn0 * h.ni;
    Vec6 fj = -h.pn * h.dn0 * h.nj;
    if (const double kd = normal_dashpot(c); kd > 0.0) {
      // Normal dashpot, implicit over the step: force (c/dt)(d_n - d_ref).
      kii += kd * h.ni * h.ni.transpose();
      kjj += kd * h.nj * h.nj.transpose();
      kij += kd * h.ni * h.nj.transpose();
      fi -= kd * (h.dn0 - h.dn_ref) * h.ni;
      fj -= kd * (h.dn0 - h.dn_ref) * h.nj;
    }
    if (r.state == ContactState::locked) {
      // Shear spring: the seed's eqs. 28-29, with the locking point shifted by
      // the creep seam (zero without a law).
      const double ps = shear_stiffness(c);
      const double d0 = h.dt0 + step_.seams[c].locking_shift;
      kii += ps * h.ti * h.ti.transpose();
      kjj += ps * h.tj * h.tj.transpose();
      kij += ps * h.ti * h.tj.transpose();
      fi -= ps * d0 * h.ti;
      fj -= ps * d0 * h.tj;
      // Shear dashpot on the step's tangential motion: force (c_s/dt) slip.
      if (const double kd = shear_dashpot(c); kd > 0.0) {
        kii += kd * h.ti * h.ti.transpose();
        kjj += kd * h.tj * h.tj.transpose();
        kij += kd * h.ti * h.tj.transpose();
      }
    } else {
      // Sliding: Mohr-Coulomb friction F = N tan(phi) + c l against the slip
      // direction, N from the last iterate.
      const double f = mohr_coulomb_strength(h.normal_force, h.tan_phi, h.cohesion, r.length);
      fi -= r.slide_direction * f * h.ti;
      fj -= r.slide_direction * f * h.tj;
    }
    sink.add_stiffness(i, i, kii);
    sink.add_stiffness(j, j, kjj);
    sink.add_stiffness(i, j, kij);
    sink.add_load(i, fi);
    sink.add_load(j, fj);
  }
}

void ContactSystem::contact_forces(const Eigen::VectorXd& D, Eigen::VectorXd& f) const {
  for (size_t c = 0; c < records_.work.contacts.size(); ++c) {
    const Contact& r = records_.work.contacts[c];
    if (r.state == ContactState::open) continue;
    const Hot& h = step_.hot[c];
    const auto Di = D.segment<6>(6 * r.key.vblock);
    const auto Dj = D.segment<6>(6 * r.key.eblock);
    const double dn = h.dn0 + h.ni.dot(Di) + h.nj.dot(Dj);
    const double slip = h.ti.dot(Di) + h.tj.dot(Dj);
    // Normal: spring p_n d_n and dashpot (c/dt)(d_n - d_ref), as assemble.
    const double N = h.pn * dn + normal_dashpot(c) * (dn - h.dn_ref);
    double T = 0.0;
    if (r.state == ContactState::locked) {
      // Shear spring to the locking point shifted by the creep seam, and its dashpot.
      T = shear_stiffness(c) * (h.dt0 + step_.seams[c].locking_shift + slip) + shear_dashpot(c) * slip;
    } else {
      // Mohr-Coulomb friction from the spring's normal force at D.
      T = r.slide_direction * mohr_coulomb_strength(h.pn * dn, h.tan_phi, h.cohesion, r.length);
    }
    f.segment<6>(6 * r.key.vblock) += h.ni * N + h.ti * T;
    f.segment<6>(6 * r.key.eblock) += h.nj * N + h.tj * T;
  }
}

}  // namespace rheodda::contact
