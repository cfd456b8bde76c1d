// The linear solver's memory between solves, saved and restored (SolverState,
// engine.hpp): whether automatic has left amg for CHOLMOD, and amg's warm
// start and hierarchy. CHOLMOD needs nothing: its symbolic analysis depends
// on the pattern alone, and a fresh one of the same pattern is the same.
#include "block_amg.hpp"
#include "rheodda/core/solver.hpp"

namespace rheodda::core {

SolverState LinearSolver::state() const {
  SolverState s;
  s.amg_failed = amg_failed_;
  s.amg_fallback_solve = stats_.amg_fallback_solve;
  s.warm_start.assign(last_.data(), last_.data() + last_.size());
  if (amg_) amg_->save(s);
  return s;
}

void LinearSolver::restore(const SolverState& s) {
  if (amg_ || !s.positions.empty()) {  // first: it refuses an inconsistent hierarchy before anything changes
    if (!amg_) amg_ = std::make_unique<BlockAmg>();
    amg_->restore(s);
  }
  amg_failed_ = s.amg_failed;
  stats_.amg_fallback_solve = s.amg_fallback_solve;
  last_ = Eigen::Map<const Eigen::VectorXd>(s.warm_start.data(), static_cast<Eigen::Index>(s.warm_start.size()));
}

}  // namespace rheodda::core
