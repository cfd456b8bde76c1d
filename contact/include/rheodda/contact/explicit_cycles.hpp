// The explicit cycles of a step (contact_cycles.cpp; docs/reference/explicit-step.md): what
// they read and write per contact, apart from the contact records, and what the step keeps
// of them. A cycle visits every contact, so what it reads lies in one contiguous array, built
// by ContactSystem::begin_cycles from the records and their step-start linearization, and
// nothing else of the records is touched until end_cycles. Internal to ContactSystem, which
// holds one ExplicitCycles for the step being solved.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rheodda/contact/energy_book.hpp"
#include "rheodda/contact/kinematics.hpp"

namespace rheodda::contact {

enum class ContactState : std::uint8_t;
struct Contact;

namespace cycles {

/// One contact's springs over the cycles of a step: read-only while they run (the dashpots
/// are set once, by cycle_damping). The linearized gap and shear of the implicit step
/// (d_n = dn0 + ni.D_i + nj.D_j, d_t = dt0 + ti.D_i + tj.D_j; the seed's eqs. 17-18, 23-29).
struct Spring {
  Vec6 ni, nj, ti, tj;
  double dn0 = 0.0;    ///< [length]
  double reach0 = 0.0; ///< dt0 + the seam's locking shift: the spring's stretch at D = 0 [length]
  double pn = 0.0;     ///< normal spring [stress]
  double ks = 0.0;     ///< shear spring with the creep seam folded in [stress]
  double tension = 0.0;  ///< tensile strength times length while intact [force/length]
  double cohesion = 0.0, cohesion_residual = 0.0;  ///< cohesion times length [force/length]
  double tan_phi = 0.0, tan_phi_residual = 0.0;    ///< [-]
  double cn = 0.0, cs = 0.0;  ///< normal and shear dashpots [force time / length^2 per unit thickness]
  int i = 0, j = 0;           ///< vertex block, edge block
  int slot_i = 0, slot_j = 0; ///< where its forces on them go in ExplicitCycles::force
};

/// One contact's state, changed cycle by cycle.
struct State {
  double shift = 0.0;   ///< how far the cycles dragged the locking point along the edge [length]
  double nd = 0.0, ts = 0.0;  ///< its dashpots' forces at the last cycle times half that cycle's kick,
                              ///< for their work at the next cycle's rates [force x time per unit thickness]
  double damped = 0.0;  ///< work its dashpots took over the cycles [force x length per unit thickness]
  double slid = 0.0;    ///< friction's work over the cycles: T times the drag of the locking point [force x length per unit thickness]
  double released = 0.0;  ///< its springs' energy at the cycles it opened [force x length per unit thickness]
  double attached = 0.0;  ///< its springs' energy at the cycles they attached without work [force x length per unit thickness]
  ContactState state{};
  std::int8_t direction = 0;  ///< slide direction (+1 / -1) while sliding
  bool intact = true;         ///< cohesion and tensile strength still act
};

}  // namespace cycles

/// The explicit cycles of the step being solved: whether it is taken in cycles, on how many
/// threads, the cycles' arrays in the order of the contact records, and what they did to the
/// springs. What needs no more than these arrays is done here; ContactSystem fills
/// the springs and states from its records and hands the states back to them.
struct ExplicitCycles {
  bool active = false;  ///< the step being solved is taken in cycles (begin_cycles)
  int threads = 0;      ///< OpenMP threads of the cycles (0: OpenMP's default)
  CycleWork work;       ///< what the cycles of the step did to the springs (end_cycles)

  std::vector<cycles::Spring> springs;
  std::vector<cycles::State> states;
  /// Factors of the stiffness bound on the vertex and edge blocks (2 per contact): 2, or 1
  /// where the other block does not move (held: infinite mass), so the spring acts on one
  /// block alone.
  std::vector<double> bounds;
  /// The contacts' forces on their blocks, by block (CSR: block b's from block_first[b] to
  /// block_first[b + 1]) and within a block in the order of the records: the gather reads
  /// them in a row, in a fixed order.
  std::vector<Vec6> force;
  std::vector<int> block_first, next;
  /// Per block the first and the last contact on it (records' order; none: the contact
  /// count and -1), and the blocks by their last contact (completion order).
  std::vector<int> block_first_contact, block_last_contact, completion;

  /// Into a step (begin_step): not in cycles, no work.
  void reset() {
    active = false;
    work = {};
  }
  /// Lays out the force slots and the gather's order for the records `work` (the contacts in
  /// the order of the springs) on `block_count` blocks.
  void order_by_block(std::span<const Contact> work, int block_count);
  /// ContactSystem::cycle_stiffness: the springs' bound on each block into K.
  void add_stiffness(std::vector<Mat6>& K) const;
  /// ContactSystem::cycle_forces: one cycle, every contact's state decided at D and the
  /// forces f gathered per block; `kick`: the length of the kick the forces make (the
  /// dashpots' work, ContactSystem::cycle_forces); `dashpots`: the step is dynamic.
  void forces(const Eigen::VectorXd& D, const Eigen::VectorXd& V, double kick, bool dashpots, Eigen::VectorXd& f);
  /// The contacts' cycle work (dashpots, friction, springs detached and attached), summed in
  /// the records' order (the same sums whatever the threads).
  CycleWork summed() const;
};

}  // namespace rheodda::contact
