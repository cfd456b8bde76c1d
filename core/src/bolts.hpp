// The bolts of a model in the engine (docs/reference/bolts.md): their terms in a step's
// block equations, the check of their yield state against a trial D, and their
// state update when the step is accepted. Engine::Impl holds one BoltSet; a
// model without bolts never calls it (Model::bolts empty: no bolt work at all).
//
// Per step, with the ends x_a, x_b at the step start, L = |x_b - x_a|, the axis
// n = (x_b - x_a)/L and T_a, T_b the displacement matrices of the ends
// (contact/kinematics.hpp), the elongation increment is, to first order,
//     Delta = n . (T_b D_b - T_a D_a) = g_b . D_b - g_a . D_a,   g = T^T n     (1)
// (the axis of the step start, as the contact normals are). The axial force at
// the end of the step is, elastic (docs/reference/bolts.md, "Equations"),
//     N = k (e0 + Delta - e_p - e_c - Delta e_c),  Delta e_c = h + c N          (2)
// (e0 the elongation at the step start, e_p the plastic and e_c the creep
// elongation, h and c the law's affine increment, laws/contact_rheology.hpp eq. 1),
// i.e. N = k_eff (s0 + Delta), k_eff = k / (1 + k c), s0 = e0 - e_p - e_c - h.
// Its energy k_eff/2 (s0 + Delta)^2 adds
//     K_aa += k_eff g_a g_a^T,  K_bb += k_eff g_b g_b^T,  K_ab -= k_eff g_a g_b^T,
//     F_a  += N0 g_a,           F_b  -= N0 g_b,           N0 = k_eff s0          (3)
// and a yielding bolt adds only its force s N_y (s = +1 in tension):
//     F_a += s N_y g_a,  F_b -= s N_y g_b.                                       (4)
#pragma once

#include <vector>

#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/engine.hpp"

namespace rheodda::core {

/// The bolts' terms of the energy balance (docs/reference/engine.md, "Energy balance";
/// docs/reference/bolts.md, "Energy") [force x length].
struct BoltEnergy {
  double stored = 0.0;       ///< sum over intact bolts of N^2 / (2 k)
  double dissipation = 0.0;  ///< of the last step: (N1 - N0)^2/(2k) (integration) + N1 Delta e_p
                             ///< (plastic) + N1 Delta e_c (creep) + N0^2/(2k) of a bolt that ruptured
};

class BoltSet {
 public:
  /// The bolts' states at t = 0 (force = pretension).
  static std::vector<BoltState> initial_states(const Model& m);
  /// The state of a bolt where it is installed: length L0, force = pretension.
  static BoltState installed_state(const Bolt& bolt);
  /// Stored energy of the states [force x length].
  static double stored_energy(const Model& m, const std::vector<BoltState>& states);

  /// A new attempt at a step of dt from the accepted states `committed` and the
  /// step-start geometry: axes, (1), the law's linearization, trial modes.
  void begin_step(const Model& m, const std::vector<BlockState>& blocks,
                  const std::vector<BoltState>& committed, double dt);
  /// Adds (3) or (4) of every intact bolt for its trial mode.
  void assemble(contact::SystemSink& sink) const;
  /// Checks D against the trial modes (elastic beyond N_y -> yielding; yielding
  /// whose elastic trial force falls below N_y -> elastic; a nonlinear law's
  /// linearization moved) and updates them; returns the number of changes.
  int check(const Eigen::VectorXd& D);
  /// The step is accepted and the blocks have moved (`blocks`: end-of-step
  /// geometry): updates `states` (exact elongation, plastic and creep increments,
  /// rupture at t_end) and returns the step's energy terms.
  BoltEnergy commit(const Model& m, const std::vector<BlockState>& blocks, double t_end,
                    std::vector<BoltState>& states);

 private:
  struct Trial {
    bool active = false;  ///< intact (a ruptured bolt adds nothing)
    contact::Vec6 g_a = contact::Vec6::Zero(), g_b = contact::Vec6::Zero();  ///< (1) [-, length]
    double k_eff = 0.0;    ///< k / (1 + k c) [force/length]
    double s0 = 0.0;       ///< e0 - e_p - e_c - h [length]
    double force_start = 0.0;  ///< N at the step start [force]
    double guess = 0.0;    ///< force the law was linearized at [force]
    int sign = 0;          ///< 0: elastic; +1 / -1: yielding in tension / compression
    laws::StepConstants constants;
    laws::Linearization lin;
  };
  std::vector<Trial> trials_;
  const Model* model_ = nullptr;
  std::vector<BoltState> start_;  ///< the states at the step start
  void linearize(std::size_t k, double guess);
  double elongation_increment(std::size_t k, const Eigen::VectorXd& D) const;
};

/// Refuses a model's bolts that are out of range (ModelError naming
/// "bolts[k].key"), called by Engine::Impl::validate.
void validate_bolts(const Model& m);
/// Refuses a bolt whose values are out of range or whose two ends coincide
/// (ModelError naming "<key>.field"); its ends' blocks and points are the caller's.
void validate_bolt_values(const Bolt& b, const ModelEntry& key);
/// Refuses the settings that do not carry bolts (step doubling, the newton contact solve).
void validate_bolt_settings(const Settings& s);

}  // namespace rheodda::core
