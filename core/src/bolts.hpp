// The bolts of a model in the engine (docs/reference/bolts.md): their terms in a step's
// block equations, the check of their yield state against a trial D, and their
// state update when the step is accepted. Engine::Impl holds one BoltSet; a
// model without bolts never calls it (Model::bolts empty: no bolt work at all).
//
// Per step the bolt's force acts along its axis at the end of the step, found
// by Newton's method within the step's open-close iteration (docs/reference/bolts.md,
// "Equations"). With the ends of the step start x_a, x_b, the centroids c_a, c_b
// and a block's step unknowns D = (u, r0, eps), an end moves as the engine moves
// the block when the step is accepted (the exact-rotation post-correction,
// docs/reference/engine.md, "A step"):
//     x'(D) = c + u + R(r0) (I + eps) (x - c),                                   (1)
// whose Jacobian G = dx'/dD is Shi's T at D = 0 (contact/kinematics.hpp) and whose
// second derivative in r0 is -rho, rho = R(r0)(I + eps)(x - c). The bolt vector
// d = x'_b - x'_a, its length L = |d| and axis n = d/L give the axial force, elastic,
//     N = k (e0 + Delta - e_p - e_c - Delta e_c),  Delta e_c = h + c N,  Delta = L - L0   (2)
// (e0 the elongation and L0 the length at the step start, e_p the plastic and e_c
// the creep elongation, h and c the law's affine increment, laws/contact_rheology.hpp
// eq. 1), i.e. N = k_eff (s0 + Delta), k_eff = k / (1 + k c), s0 = e0 - e_p - e_c - h;
// yielding, N = s N_y (s = +1 in tension). Its potential Pi (k_eff/2 (s0 + Delta)^2,
// or s N_y Delta) has the gradient
//     dPi/dD_a = -N G_a^T n,   dPi/dD_b = N G_b^T n                              (3)
// and, at the iterate D^j, the Hessian (a tensioned bar: the axial stiffness and the
// geometric stiffness N/L across the axis; Crisfield, "Non-linear Finite
// Element Analysis of Solids and Structures", vol. 1, 1991, ch. 3, the truss
// element's tangent stiffness; Bathe, "Finite Element Procedures", 1996, ch. 6)
//     K2 = k_ax n n^T + (N+/L) (I - n n^T),   k_ax = k_eff (elastic) or 0 (yielding),
//     H_aa = G_a^T K2 G_a + N+ (n . rho_a)+ e_r e_r^T,  H_bb = G_b^T K2 G_b + (-N n . rho_b)+ e_r e_r^T,
//     H_ab = -G_a^T K2 G_b                                                       (4)
// (N+ = max(N, 0) and (.)+ = max(., 0): the tangent keeps its non-negative parts,
// so that a compressed bolt does not make the step's matrix indefinite; e_r the
// rotation unknown; the rotation-strain cross terms of the second derivative of (1),
// of the order of N |x - c| against the block's elastic stiffness E S, are left out).
// The step's equations get the Newton terms of the iterate,
//     K += H,   F += H D^j - dPi/dD(D^j),                                        (5)
// which are Shi's axial spring along the start axis at D^0 = 0 (K_aa += k_eff g_a g_a^T,
// F_a += N0 g_a, g = T^T n, N0 = k_eff s0) plus the geometric stiffness. check()
// moves the iterate to the new D; the step goes on iterating while the bolt's
// generalized force (3) at the new D differs from what (5) predicted by more than
// kNewtonTolerance of the force and the force of the ends' coordinates' round-off, so that the accepted step is in equilibrium with
// the bolt's force along its end-of-step axis on the geometry the blocks are moved to.
#pragma once

#include <utility>
#include <vector>

#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/block_state.hpp"
#include "rheodda/core/model.hpp"

namespace rheodda::core {

/// The bolts' terms of the energy balance (docs/reference/engine.md, "Energy balance";
/// docs/reference/bolts.md, "Energy") [force x length].
struct BoltEnergy {
  double stored = 0.0;       ///< sum over intact bolts of N^2 / (2 k)
  double dissipation = 0.0;  ///< of the last step: (N1 - N0)^2/(2k) (integration) + N1 Delta e_p
                             ///< (plastic) + N1 Delta e_c (creep) + N0^2/(2k) of a bolt that ruptured
                             ///< + N1 (n1 . (G_b D_b - G_a D_a) - Delta L) (the axis's turn)
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
  /// step-start geometry: the iterate D = 0, the law's linearization, trial modes.
  void begin_step(const Model& m, const std::vector<BlockState>& blocks,
                  const std::vector<BoltState>& committed, double dt);
  /// Adds (5) of every intact bolt at its iterate for its trial mode.
  void assemble(contact::SystemSink& sink) const;
  /// Moves every bolt's iterate to D and checks it: elastic beyond N_y ->
  /// yielding; yielding whose elastic trial force falls below N_y -> elastic; a
  /// nonlinear law's linearization moved; the force (3) at D not yet what (5)
  /// predicted (Newton not converged). Returns the number of such changes.
  int check(const Eigen::VectorXd& D);
  /// The creep error estimate of the step just solved (after the last check,
  /// before commit) [length]: the largest over the intact bolts with a law of
  /// the creep elongation's local error (docs/reference/step-controls.md, "Adaptive
  /// creep stepping"; bolt_creep_error.cpp).
  double creep_error_estimate() const;
  /// The step is accepted and the blocks have moved (`blocks`: end-of-step
  /// geometry): updates `states` (exact elongation, plastic and creep increments,
  /// rupture at t_end) and returns the step's energy terms.
  BoltEnergy commit(const Model& m, const std::vector<BlockState>& blocks, double t_end,
                    std::vector<BoltState>& states);

  /// Step doubling (docs/reference/step-controls.md, "Step doubling"; bolt_doubling.cpp):
  /// the largest difference of a bolt's creep elongation between `fine` (two
  /// steps of dt/2) and `coarse` (one step of dt) from the same start [length].
  static double creep_difference(const std::vector<BoltState>& fine, const std::vector<BoltState>& coarse);
  /// Whether every bolt ends both runs in the same mode (elastic, yielding in
  /// the same sense, ruptured), which Richardson extrapolation needs.
  static bool same_modes(const std::vector<BoltState>& fine, const std::vector<BoltState>& coarse);
  /// Richardson extrapolation of the bolts' states, fine := 2 fine - coarse
  /// (the law's internal displacements and the plastic elongation; the length
  /// and elongation measured on the extrapolated `blocks`, the force from them
  /// by (1) of docs/reference/bolts.md). Needs same_modes.
  static void extrapolate(const Model& m, const std::vector<BlockState>& blocks, std::vector<BoltState>& fine,
                          const std::vector<BoltState>& coarse);

  // The explicit step's cycles (bolt_cycles.cpp; docs/reference/explicit-step.md), between
  // begin_step and commit instead of assemble/check: begin_cycles -> { cycle_forces }* ->
  // end_cycles.

  /// Adds to K (6x6 per block) a bound of the bolts' stiffness on each block (4) at the
  /// step start, for the stable cycle [force/length ...].
  void cycle_stiffness(std::vector<contact::Mat6>& K) const;
  /// Adds to C a bound of the bolts' dashpots c = tau k_eff on each block [tau: time].
  void cycle_damping(double tau, std::vector<contact::Mat6>& C) const;
  /// Starts the cycles of the step begun: the dashpots c = tau k_eff (tau: time; 0 none), the
  /// bolts of each block in a fixed order for the gather, on `threads` OpenMP threads (0:
  /// OpenMP's default).
  void begin_cycles(double tau, int block_count, int threads);
  /// Adds the bolts' resisting forces (3) at the displacements D since the step start and the
  /// rates V to f (6 per block), each bolt's mode decided at D; kick: the length of the kick
  /// these forces make [time] (the cycle, half of it at the step's first and last), for the
  /// dashpot's work, its force times kick (its rate + the rate after the kick)/2 ((C4) of
  /// bolt_cycles.cpp), as ContactModel::cycle_forces books the contacts'.
  void cycle_forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, Eigen::VectorXd& f);
  /// After the last cycle at D, V the rates its kick led to: each bolt's trial mode, plastic
  /// elongation and iterate where the cycles left them, its dashpot's work completed, ready
  /// for commit.
  void end_cycles(const Eigen::VectorXd& D, const Eigen::VectorXd& V);

  /// Where an end of a bolt goes for the block unknowns D, by (1).
  struct EndMotion {
    Vec2 x = Vec2::Zero();                                      ///< x'(D) [length]
    Eigen::Matrix<double, 2, 6> G = Eigen::Matrix<double, 2, 6>::Zero();  ///< dx'/dD [-, length]
    Vec2 rho = Vec2::Zero();  ///< R(r0)(I + eps)(x - c); d^2 x'/dr0^2 = -rho [length]
  };
  /// (1) for the end at x (step start) of a block whose centroid is c (step start).
  static EndMotion end_motion(const Vec2& c, const Vec2& x, const contact::Vec6& D);

 private:
  /// A bolt's linearization point: the iterate D^j and the bolt there, (2)-(4).
  struct Point {
    contact::Vec6 D_a = contact::Vec6::Zero(), D_b = contact::Vec6::Zero();  ///< D^j of the ends' blocks
    EndMotion a, b;        ///< the ends at D^j (b: a fixed anchor has G = 0)
    Vec2 n = Vec2::Zero(); ///< axis at D^j [-]
    double L = 0.0;        ///< length at D^j [length]
    double N = 0.0;        ///< axial force at D^j, (2) or s N_y [force]
    Eigen::Matrix2d K2 = Eigen::Matrix2d::Zero();  ///< (4) [force/length]
    double curv_a = 0.0, curv_b = 0.0;  ///< the rotation terms of (4) [force x length]
    double work = 0.0;     ///< n . (G_b D_b - G_a D_a): the step's work of the force (3) per unit N [length]
  };
  struct Trial {
    bool active = false;  ///< intact (a ruptured bolt adds nothing)
    double length_start = 0.0;  ///< L0, the length at the step start [length]
    Vec2 c_a = Vec2::Zero(), x_a = Vec2::Zero();  ///< centroid and end of block a at the step start
    Vec2 c_b = Vec2::Zero(), x_b = Vec2::Zero();  ///< of block b, or (x_b) the fixed anchor
    double k_eff = 0.0;    ///< k / (1 + k c) [force/length]
    double s0 = 0.0;       ///< e0 - e_p - e_c - h [length]
    double force_start = 0.0;  ///< N at the step start [force]
    double guess = 0.0;    ///< force the law was linearized at [force]
    int sign = 0;          ///< 0: elastic; +1 / -1: yielding in tension / compression
    Point at;              ///< the iterate the assembly linearizes at
    laws::StepConstants constants;
    laws::Linearization lin;
    // The explicit step's cycles (bolt_cycles.cpp); 0 in an implicit step.
    bool cycled = false;        ///< the step was taken in cycles
    double cycle_plastic = 0.0; ///< plastic elongation the cycles took so far [length]
    double cycle_work = 0.0;    ///< the plastic work and the dashpot's work in the cycles [force x length]
    double damper = 0.0;        ///< dashpot coefficient c = tau k_eff [force x time/length]
    double damper_half = 0.0;   ///< the last cycle's dashpot force times half its kick, for its
                                ///< work at the rates the kick led to ((C4); 0: none) [force x time]
    contact::Vec6 damper_g_a = contact::Vec6::Zero(), damper_g_b = contact::Vec6::Zero();  ///< g = G^T n of
                                ///< the ends at that cycle [-, length]
    /// (2) on the elastic branch at the length L: k_eff (s0 - cycle_plastic + L - L0) [force].
    double elastic_force(double L) const { return k_eff * (s0 - cycle_plastic + L - length_start); }
  };
  /// The force of the previous accepted step, for the curvature of a bolt's force
  /// in the creep error estimate (bolt_creep_error.cpp): valid while the
  /// committed state it was recorded against is the one a step starts from.
  struct Previous {
    bool valid = false;
    double force_start = 0.0;  ///< N at the start of the previous step [force]
    double dt = 0.0;           ///< its length [time]
    double force_end = 0.0, elongation_end = 0.0;  ///< the committed state it led to
  };
  std::vector<Trial> trials_;
  std::vector<Previous> previous_;
  const Model* model_ = nullptr;
  std::vector<BoltState> start_;  ///< the states at the step start
  // The cycles' gather (bolt_cycles.cpp): each bolt's generalized forces on its two ends'
  // blocks, and per block the entries into them in the bolts' order (CSR).
  std::vector<contact::Vec6> cycle_force_;
  std::vector<int> block_first_, block_entries_;
  int cycle_threads_ = 0;
  void linearize(std::size_t k, double guess);
  /// (C4) of bolt_cycles.cpp, second half: bolt k's last dashpot force at the rates V its kick
  /// led to, into its cycle work.
  void book_damper(std::size_t k, const Eigen::VectorXd& V);
  /// The Hessian block (4) of an end: G^T K2 G with its rotation term curv on e_r.
  static contact::Mat6 end_hessian(const EndMotion& e, const Eigen::Matrix2d& K2, double curv);
  /// The bolt k at the iterate D (its blocks' segments of D), in its trial mode.
  Point point(std::size_t k, const Eigen::VectorXd& D) const;
};

/// Relative tolerance of the bolts' Newton iteration on their force (bolts.hpp, (5)) [-];
/// bolt_step.cpp adds the force of the round-off of the ends' coordinates.
constexpr double kNewtonTolerance = 1e-9;

/// The two ends of a bolt on the blocks now [length] (bolt_step.cpp).
std::pair<Vec2, Vec2> bolt_ends(const Bolt& bolt, const std::vector<BlockState>& blocks);
/// Unstressed length L_rest = L0 - pretension / k of a bolt (bolt.hpp) [length].
double bolt_rest_length(const Bolt& bolt);

/// Refuses a model's bolts that are out of range (ModelError naming
/// "bolts[k].key"), called by Engine::Impl::validate.
void validate_bolts(const Model& m);
/// Refuses a bolt whose values are out of range or whose two ends coincide
/// (ModelError naming "<key>.field"); its ends' blocks and points are the caller's.
void validate_bolt_values(const Bolt& b, const ModelEntry& key);
/// Refuses the settings that do not carry bolts (the newton contact solve).
void validate_bolt_settings(const Settings& s);

}  // namespace rheodda::core
