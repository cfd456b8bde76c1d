// The block sub-matrices of one step (Shi 1988; docs/reference/engine.md, "Sub-matrices"):
// per step, with D_i = (u0, v0, r0, ex, ey, gxy) the unknowns of block i at
// its centroid (x0, y0) and T_i(x, y) the first-order displacement matrix
// (contact/kinematics.hpp, the seed's eq. 27):
//   K_ii += S E_e                              elastic strain energy
//   F_i  -= S sigma                            initial (carried) stress
//   F_i  += T_i(p)^T f(t + dt)                 point load at p
//   F_i  += rho S (gx, gy, 0, 0, 0, 0)         body force
//   K_ii += 2/dt^2 M_i,  F_i += 2/dt M_i v_i   inertia, M_i = rho int T^T T dA (implicit step only)
//   K_ii += p T^T S T,   F_i += p T^T S (x0 - x) fixed point (penalty spring; S =
//                                            diag(hold_x, hold_y), the directions held)
//   K_ii += k_r g g^T,   F_i -= k_r (theta - theta_h) g   a held rotation (rotational penalty
//                                            spring k_r = p J/S; block_terms.hpp, RotationHold)
//   F_i  += int T_i^T (-p n) ds                water pressure on the edges (water.hpp)
// No term couples two blocks: the contacts add those (step_trial.cpp).
#include "block_terms.hpp"
#include "engine_impl.hpp"

namespace rheodda::core {

void Engine::Impl::assemble_blocks(double dt, double t_end, std::vector<Mat6>& diag,
                                   Eigen::VectorXd& rhs, bool inertia) const {
  const Settings& s = model.settings;
  const std::size_t n = st.blocks.size();
  diag.resize(n);
  rhs.resize(6 * static_cast<Eigen::Index>(n));
  const Newmark nm = newmark();
  for (std::size_t k = 0; k < n; ++k) {
    const BlockState& b = st.blocks[k];
    const PolygonIntegrals& g = moments[k];
    const double rho = model.materials[b.material].density;
    Mat6& K = diag[k];
    auto F = rhs.segment<6>(6 * static_cast<Eigen::Index>(k));
    // Inertia (Shi 1988; Newmark): the end-of-step acceleration is
    // a' = (D - Dp)/(beta dt^2), Dp = v dt + (1/2 - beta) dt^2 a, so
    // K += M/(beta dt^2) and F += M Dp/(beta dt^2). Shi's beta = 1/2, gamma = 1
    // gives K += 2 M/dt^2 and F += 2 M v/dt with v the carried velocity.
    const Mat6 M = rho * unit_mass_matrix(g);
    if (inertia)
      K = (1.0 / (nm.beta * dt * dt)) * M;
    else
      K.setZero();  // the explicit step: inertia and block damping are its cycles' (explicit_step.cpp)
    // Elastic strain energy S/2 e^T E_e e: K(ex..gxy) += S E_e.
    K.block<3, 3>(3, 3) += g.S * elastic[b.material];
    // Block damping (Material::damping_ratio), implicit over the step: the
    // viscous stress E_e tau eps_dot with eps_dot = eps/dt adds (tau/dt) S E_e.
    if (const double tau = strain_damping_time(g, model.materials[b.material], elastic[b.material]);
        inertia && tau > 0.0 && dynamic_now())
      K.block<3, 3>(3, 3) += (tau / dt) * g.S * elastic[b.material];
    // Body force rho g over the area; the other rows vanish about the centroid.
    F.setZero();
    // With a gravity ramp (SettleStage::gravity_ramp) its value at the
    // step's end, where the step's equilibrium is written.
    const Vec2 gravity = s.gravity_at(t_end);
    F(0) = rho * gravity.x() * g.S;
    F(1) = rho * gravity.y() * g.S;
    // Initial stress: potential S e^T sigma gives F(ex..gxy) -= S sigma.
    F.tail<3>() -= g.S * b.stress;
    if (inertia && dynamic_now()) F.noalias() += (1.0 / (nm.beta * dt * dt)) * M * predictor(b, dt, nm);
    // A block a stage removed (model_edits.cpp) keeps its positive definite
    // K and no load: nothing couples it (no contact, fixed point or load), so
    // its six unknowns solve to zero.
    if (!removed.empty() && removed[k]) F.setZero();
  }
  // Point loads: F += T(p)^T f at the current position p of the material point.
  for (const auto& l : model.point_loads) {
    const BlockState& b = st.blocks[l.block];
    const Vec2 p = b.map_A * l.point + b.map_b;
    const Vec2 f = load_at(l.history, t_end);
    rhs.segment<6>(6 * l.block) += contact::displacement_matrix(b.centroid, p).transpose() * f;
  }
  // Water in the joints (water.hpp): the pressure at the step's end time on the
  // step-start edges, as the point loads; its weight ramps with gravity's
  // (Settings::gravity_factor: gamma_w = rho_w g).
  if (model.water.active()) {
    const double share = model.settings.gravity_factor(t_end);
    for (std::size_t k = 0; k < n; ++k)
      if (removed.empty() || !removed[k])  // a removed block carries no load
        rhs.segment<6>(6 * static_cast<Eigen::Index>(k)) +=
            share * water_block_load(model.water, st.blocks[k].vertices, st.blocks[k].centroid, t_end);
  }
  // Fixed points: spring p between the material point x and its held position x0
  // in the held directions S (S^2 = S), energy p/2 |S (T D - (x0 - x))|^2.
  for (const auto& fp : model.fixed_points) {
    const BlockState& b = st.blocks[fp.block];
    const Vec2 x = b.map_A * fp.material() + b.map_b;
    const contact::Mat26 T = contact::displacement_matrix(b.centroid, x);
    const Mat2 S = fp.held();
    diag[fp.block].noalias() += fixed_k * T.transpose() * S * T;
    rhs.segment<6>(6 * fp.block).noalias() += fixed_k * T.transpose() * S * (fp.point - x);
    // The rotation held: spring k_r on the block's mean rotation theta, energy
    // k_r/2 (theta + g D - theta_h)^2 (block_terms.hpp, RotationHold).
    if (fp.hold_rotation) {
      const RotationHold h = rotation_hold(fixed_k, fp, model.blocks[fp.block].vertices, b.map_A, moments[fp.block]);
      diag[fp.block].noalias() += h.stiffness * h.row * h.row.transpose();
      rhs.segment<6>(6 * fp.block) -= h.stiffness * h.deflection * h.row;
    }
  }
}

}  // namespace rheodda::core
