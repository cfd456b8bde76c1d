// The energy balance of a run (energy.hpp; docs/reference/engine.md, "Energy balance").
//
// Why the time integration dissipates, and how much (derived, not a remainder).
// The engine solves, per block, M a' = F(D) with every force F evaluated at the
// END of the step (assemble_blocks, the contacts' springs) and the Newmark
// acceleration a' = (D - Dp)/(beta dt^2), Dp = r (v dt + (1/2 - beta) dt^2 a),
// r = dynamic_ratio. Hence the end forces do the work W_end = D^T F(D) = D^T M a'
// over the step, and
//   (1) for a linear spring k whose stretch goes from s to s + Delta:
//       end-force work = -(change of k s^2/2) - k Delta^2/2, so k Delta^2/2 >= 0
//       is lost to the integration: per block elasticity S eps^T E_e eps/2,
//       per fixed point p |T D|^2/2 (and k_r (g . D)^2/2 for a held rotation,
//       block_terms.hpp), per contact spring (contact_energy.cpp);
//   (2) the inertia: D^T M a' - (change of v^T M v/2), with v' = r v + dt ((1 -
//       gamma) r a + gamma a'):
//         shi (beta 1/2, gamma 1): v' = 2 D/dt - r v, D = dt (v' + r v)/2, so
//           D^T M a' = KE' - r^2 KE and the term is (1 - r^2) KE: what
//           dynamic_ratio < 1 removes of the carried velocity;
//         trapezoidal (beta 1/4, gamma 1/2): D = dt (v' + r v)/2 and
//           KE' - r^2 KE = D^T M (a' + r a)/2, so the term is (1 - r^2) KE +
//           D^T M (a' - r a)/2. With M a the start forces this is the end-force
//           vs mid-step-force difference: for linear springs it cancels (1) to
//           round-off (the rule keeps the energy of linear vibrations);
//         static (no velocity carried): D^T M D/(beta dt^2), all the work the
//           inertia term absorbs.
// The sum of (1) and (2) is the integration dissipation.
#include "rheodda/core/energy.hpp"

#include <algorithm>
#include <cmath>

#include "block_terms.hpp"
#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/block_state.hpp"

namespace rheodda::core {

namespace {

/// Applies f(a.x, b.x) to every flow x.
template <class F>
void each_flow(EnergyFlows& a, const EnergyFlows& b, F f) {
  f(a.work_gravity, b.work_gravity);
  f(a.work_loads, b.work_loads);
  f(a.work_contact_restart, b.work_contact_restart);
  f(a.dissipation_friction, b.dissipation_friction);
  f(a.dissipation_creep, b.dissipation_creep);
  f(a.dissipation_integration, b.dissipation_integration);
  f(a.integration_inertia, b.integration_inertia);
  f(a.dissipation_contact_damping, b.dissipation_contact_damping);
  f(a.dissipation_block_damping, b.dissipation_block_damping);
  f(a.dissipation_contact_closing, b.dissipation_contact_closing);
  f(a.dissipation_contact_release, b.dissipation_contact_release);
  f(a.dissipation_bolt, b.dissipation_bolt);
  f(a.dissipation_edits, b.dissipation_edits);
  f(a.residual, b.residual);
  f(a.scale, b.scale);
}

/// Current position of the material point whose initial position was p0 [length].
Vec2 position(const BlockState& b, const Vec2& p0) { return b.map_A * p0 + b.map_b; }

/// Work of the water pressure over the step D (water.hpp; docs/reference/water.md,
/// "Assumptions"): its six load terms at t_end on the step-start geometry, as
/// assembled, times the block's step D - the end-force work of the engine's
/// equations, as for gravity; 0 without water [force x length].
double water_work(const EnergyInputs& in, const Eigen::VectorXd& D, double t_end) {
  if (!in.model.water.active()) return 0.0;
  double work = 0.0;
  for (std::size_t k = 0; k < in.blocks.size(); ++k)
    work += water_block_load(in.model.water, in.blocks[k].vertices, in.blocks[k].centroid, t_end)
                .dot(D.segment<6>(6 * static_cast<Eigen::Index>(k)));
  return in.model.settings.gravity_factor(t_end) * work;  // ramped as assembled
}

/// Closes a step's flows against the stored energies before and after it.
void settle(EnergyFlows& f, const StoredEnergy& before, const StoredEnergy& after) {
  f.scale = std::abs(f.work_gravity) + std::abs(f.work_loads);
  f.residual = (after.total() - before.total()) - f.net_input();
}

}  // namespace

double EnergyFlows::net_input() const {
  return work_gravity + work_loads + work_contact_restart - dissipation_friction -
         dissipation_creep - dissipation_integration - dissipation_contact_damping -
         dissipation_block_damping -
         dissipation_contact_closing -
         dissipation_contact_release - dissipation_bolt - dissipation_edits;
}

EnergyFlows& EnergyFlows::operator+=(const EnergyFlows& o) {
  each_flow(*this, o, [](double& x, double y) { x += y; });
  return *this;
}

double inertia_share(const EnergyFlows& f) {
  return f.scale > 0.0 ? f.integration_inertia / f.scale : 0.0;
}

double EnergyBalance::relative_residual() const {
  const double scale = initial.total() + total.scale;
  return scale > 0.0 ? std::abs(total.residual) / scale : 0.0;
}

StoredEnergy EnergyAccount::stored_in_blocks(const EnergyInputs& in) {
  StoredEnergy e;
  std::vector<Eigen::Matrix3d> compliance(in.elastic.size());
  for (std::size_t m = 0; m < in.elastic.size(); ++m) compliance[m] = in.elastic[m].inverse();
  for (std::size_t k = 0; k < in.blocks.size(); ++k) {
    const BlockState& b = in.blocks[k];
    const PolygonIntegrals& g = in.moments[k];
    // Kinetic: the velocity field T v over the block, rho/2 int |T v|^2 dA = v^T M v/2
    // (zero in a static analysis, whose blocks carry no velocity).
    // A block in a density-scaled stage (BlockState::mass_scale) moves with the mass s M.
    e.kinetic += 0.5 * b.mass_scale * in.model.materials[b.material].density *
                 b.velocity.dot(unit_mass_matrix(g) * b.velocity);
    // Elastic strain energy S/2 eps^T E_e eps with eps = E_e^-1 sigma (Shi 1988).
    e.strain += 0.5 * g.S * b.stress.dot(compliance[b.material] * b.stress);
  }
  // Fixed points: the penalty spring p from the material point to its held position.
  // (held directions S only).
  // A held rotation: its spring k_r/2 (theta - theta_h)^2 (block_terms.hpp, RotationHold).
  for (const FixedPoint& fp : in.model.fixed_points) {
    const BlockState& b = in.blocks[fp.block];
    e.fixed += 0.5 * in.fixed_k * (fp.held() * (position(b, fp.material()) - fp.point)).squaredNorm();
    if (fp.hold_rotation) {
      const RotationHold h =
          rotation_hold(in.fixed_k, fp, in.model.blocks[fp.block].vertices, b.map_A, in.moments[fp.block]);
      e.fixed += 0.5 * h.stiffness * h.deflection * h.deflection;
    }
  }
  return e;
}

EnergyBalance EnergyAccount::start(const EnergyInputs& in) {
  EnergyBalance b;
  b.initial = b.stored = stored_in_blocks(in);
  return b;
}

void EnergyAccount::begin(const EnergyInputs& in, const Eigen::VectorXd& D, double dt,
                          double beta, double gamma, double t_end) {
  flows_ = {};
  const Settings& s = in.model.settings;
  const double r = in.ratio;  // the step's carried share (1 in a dynamic settling stage)
  const bool dynamic = r > 0.0;
  const bool shi = beta == 0.5 && gamma == 1.0;
  const bool trapezoidal = beta == 0.25 && gamma == 0.5;
  // Central difference (the explicit step's cycles, beta = 0): the cycles follow the forces
  // along the step, so neither the springs' end forces nor the inertia term lose energy the
  // way an implicit step's do; what the cycles miss is left to the residual.
  const bool central = beta == 0.0;
  const Vec2 gravity = s.gravity_at(t_end);  // the step's body force, as the engine assembles it
  double springs = 0.0;
  for (std::size_t k = 0; k < in.blocks.size(); ++k) {
    const BlockState& b = in.blocks[k];
    const PolygonIntegrals& g = in.moments[k];
    const double rho = in.model.materials[b.material].density;
    const Vec6 Dk = D.segment<6>(6 * static_cast<Eigen::Index>(k));
    // Gravity: the body force rho S g acts at the centroid, which moves by (u0, v0)
    // exactly (the post-correction rotates about the centroid).
    flows_.work_gravity += rho * g.S * (gravity.x() * Dk(0) + gravity.y() * Dk(1));
    // Block elasticity, end stress sigma + E_e eps: (1) with k = S E_e.
    const Vec3 eps = Dk.tail<3>();
    if (!central) springs += 0.5 * g.S * eps.dot(in.elastic[b.material] * eps);
    // Block damping: the viscous stress's end value (tau/dt) E_e eps over the strain eps.
    if (dynamic && !central)  // (the cycles book their own: EnergyAccount::add_block_damping)
      if (const double tau = strain_damping_time(g, in.model.materials[b.material], in.elastic[b.material]);
          tau > 0.0)
        flows_.dissipation_block_damping += (tau / dt) * g.S * eps.dot(in.elastic[b.material] * eps);
    // Inertia: (2) in the header comment.
    const Mat6 M = rho * unit_mass_matrix(g);
    if (!dynamic) {
      // A static step starts at rest: the velocity a dynamic settling stage
      // left (SettleStage::dynamic) is dropped, its kinetic energy with it.
      flows_.integration_inertia +=
          Dk.dot(M * Dk) / (beta * dt * dt) + 0.5 * b.mass_scale * b.velocity.dot(M * b.velocity);
      continue;
    }
    const double ke = 0.5 * b.mass_scale * b.velocity.dot(M * b.velocity);
    if (central) {
      flows_.integration_inertia += (1.0 - r * r) * ke;  // the velocity share not carried
      continue;
    }
    // The engine's predictor and end acceleration (engine.cpp, predictor, accept).
    const Vec6 Dp = r * (dt * b.velocity + (0.5 - beta) * dt * dt * b.acceleration);
    const Vec6 a_new = (Dk - Dp) / (beta * dt * dt);
    if (shi) {
      flows_.integration_inertia += (1.0 - r * r) * ke;
    } else if (trapezoidal) {
      flows_.integration_inertia += (1.0 - r * r) * ke + 0.5 * Dk.dot(M * (a_new - r * b.acceleration));
    } else {
      // Any other Newmark pair: D^T M a' - (KE' - KE).
      const Vec6 v_new = r * b.velocity + dt * ((1.0 - gamma) * r * b.acceleration + gamma * a_new);
      flows_.integration_inertia += Dk.dot(M * a_new) - 0.5 * v_new.dot(M * v_new) + ke;
    }
  }
  // Fixed points: (1) with the spring p and the point's step displacement T D; a held
  // rotation's with k_r and the step's rotation g . D (block_terms.hpp, RotationHold).
  for (const FixedPoint& fp : in.model.fixed_points) {
    if (central) break;
    const BlockState& b = in.blocks[fp.block];
    const auto Dk = D.segment<6>(6 * static_cast<Eigen::Index>(fp.block));
    const Vec2 u = fp.held() * contact::displacement_matrix(b.centroid, position(b, fp.material())) * Dk;
    springs += 0.5 * in.fixed_k * u.squaredNorm();
    if (fp.hold_rotation) {
      const RotationHold h =
          rotation_hold(in.fixed_k, fp, in.model.blocks[fp.block].vertices, b.map_A, in.moments[fp.block]);
      const double turn = h.row.dot(Dk);
      springs += 0.5 * h.stiffness * turn * turn;
    }
  }
  flows_.dissipation_integration = springs + flows_.integration_inertia;
  flows_.work_loads = water_work(in, D, t_end);
  load_start_.clear();
  for (const PointLoad& l : in.model.point_loads)
    load_start_.push_back(position(in.blocks[l.block], l.point));
}

double EnergyAccount::static_trial_share(const EnergyInputs& in, const Eigen::VectorXd& D, double dt,
                                         double beta, double t_end) {
  // (2) of the header comment for a static step, without the kinetic energy a
  // dynamic stage left (that is dropped whatever the step does); the work as
  // begin() and end() book it, the load points moved to first order (T D).
  const Settings& s = in.model.settings;
  double inertia = 0.0, gravity = 0.0, loads = 0.0;
  for (std::size_t k = 0; k < in.blocks.size(); ++k) {
    const BlockState& b = in.blocks[k];
    const PolygonIntegrals& g = in.moments[k];
    const double rho = in.model.materials[b.material].density;
    const Vec6 Dk = D.segment<6>(6 * static_cast<Eigen::Index>(k));
    const Vec2 g_end = s.gravity_at(t_end);
    gravity += rho * g.S * (g_end.x() * Dk(0) + g_end.y() * Dk(1));
    inertia += rho * Dk.dot(unit_mass_matrix(g) * Dk) / (beta * dt * dt);
  }
  for (const PointLoad& l : in.model.point_loads) {
    const BlockState& b = in.blocks[l.block];
    const Vec2 u = contact::displacement_matrix(b.centroid, position(b, l.point)) *
                   D.segment<6>(6 * static_cast<Eigen::Index>(l.block));
    loads += load_at(l.history, t_end).dot(u);
  }
  loads += water_work(in, D, t_end);
  const double scale = std::abs(gravity) + std::abs(loads);
  return scale > 0.0 ? inertia / scale : 0.0;
}

void EnergyAccount::end(const EnergyInputs& in, double t_end, const ContactEnergy& contacts,
                        EnergyBalance& balance) {
  // Point loads: the force of the step (evaluated at its end, as assembled) times
  // the displacement of the load point (exact, post-corrected geometry).
  for (std::size_t k = 0; k < in.model.point_loads.size(); ++k) {
    const PointLoad& l = in.model.point_loads[k];
    flows_.work_loads +=
        load_at(l.history, t_end).dot(position(in.blocks[l.block], l.point) - load_start_[k]);
  }
  flows_.work_contact_restart = contacts.restart;
  flows_.dissipation_friction = contacts.friction;
  flows_.dissipation_creep = contacts.creep;
  flows_.dissipation_integration += contacts.integration;
  flows_.dissipation_contact_damping = contacts.damping;
  flows_.dissipation_contact_closing = contacts.closing;
  flows_.dissipation_contact_release = contacts.release;
  StoredEnergy now = stored_in_blocks(in);
  now.contact_normal = contacts.normal;
  now.contact_shear = contacts.shear;
  now.bolt = bolt_stored_;
  flows_.dissipation_bolt = bolt_dissipation_;
  bolt_dissipation_ = 0.0;
  settle(flows_, balance.stored, now);
  balance.stored = now;
  balance.step = flows_;
  balance.total += flows_;
  balance.max_relative_residual = std::max(balance.max_relative_residual, balance.relative_residual());
}

void EnergyAccount::finish_doubling(const EnergyInputs& in, const EnergyBalance& start,
                                    const EnergyFlows& coarse, bool extrapolated,
                                    const ContactEnergy& contacts, EnergyBalance& balance, double bolts) {
  // The two half steps: their flows summed.
  EnergyFlows step = balance.total;
  each_flow(step, start.total, [](double& x, double y) { x -= y; });
  StoredEnergy now = balance.stored;
  if (extrapolated) {
    // Richardson on the flows, as on the states (2 y_f - y_c); the stored
    // energies are those of the extrapolated state.
    each_flow(step, coarse, [](double& x, double y) { x = 2.0 * x - y; });
    now = stored_in_blocks(in);
    now.contact_normal = contacts.normal;
    now.contact_shear = contacts.shear;
    now.bolt = bolts;
  }
  settle(step, start.stored, now);
  balance.stored = now;
  balance.step = step;
  balance.total = start.total;
  balance.total += step;
  balance.max_relative_residual = std::max(start.max_relative_residual, balance.relative_residual());
}

}  // namespace rheodda::core
