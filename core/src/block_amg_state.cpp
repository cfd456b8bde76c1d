// Saving and restoring the amg hierarchy's memory of earlier systems
// (block_amg.hpp, "Reuse"): the aggregates are chosen from the matrix values
// at the setup, and the smoothing weights and transfers are computed where
// the blocks stood at the last refresh that moved them. A hierarchy set up
// afresh from a later system would differ in the last bits of every solve, so
// a resumed run rebuilds the saved one instead.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "block_amg.hpp"

namespace rheodda::core {

void BlockAmg::save(SolverState& out) const {
  out.pattern.clear();
  out.positions.clear();
  out.aggregates.clear();
  out.coarse_blocks.clear();
  out.omega.clear();
  if (pending_) {  // restored and not yet used: as it was saved
    out.pattern = pending_->pattern;
    out.positions = pending_->positions;
    out.aggregates = pending_->aggregates;
    out.coarse_blocks = pending_->coarse_blocks;
    out.omega = pending_->omega;
    return;
  }
  if (levels_.empty()) return;
  out.pattern = pattern_;
  out.positions = levels_[0].pos;
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    out.aggregates.push_back(levels_[l].agg);
    out.coarse_blocks.push_back(levels_[l + 1].n);
    out.omega.push_back(levels_[l].omega);
  }
}

void BlockAmg::restore(const SolverState& saved) {
  if (saved.positions.empty()) {  // no hierarchy: the next solve sets one up
    levels_.clear();
    pattern_.clear();
    pending_.reset();
    return;
  }
  // The sizes must chain: level l's aggregates index level l + 1's blocks.
  const std::size_t levels = saved.aggregates.size();
  bool fits = saved.coarse_blocks.size() == levels && saved.omega.size() == levels;
  std::size_t n = saved.positions.size();
  for (std::size_t l = 0; fits && l < levels; ++l) {
    const auto& agg = saved.aggregates[l];
    const int coarse = saved.coarse_blocks[l];
    fits = agg.size() == n && coarse > 0 &&
           std::all_of(agg.begin(), agg.end(), [&](int a) { return a >= 0 && a < coarse; });
    n = static_cast<std::size_t>(coarse);
  }
  for (const auto& [i, j] : saved.pattern)
    fits = fits && i >= 0 && j >= 0 && static_cast<std::size_t>(std::max(i, j)) < saved.positions.size();
  if (!fits) throw std::invalid_argument("amg: the saved hierarchy is inconsistent (its levels do not chain)");
  levels_.clear();
  pattern_ = saved.pattern;
  pending_ = std::make_unique<SolverState>(saved);
}

void BlockAmg::rebuild(const BlockSystem& s) {
  // setup() with the saved aggregates and weights in place of aggregate().
  const std::unique_ptr<SolverState> saved = std::move(pending_);
  levels_.clear();
  levels_.reserve(saved->aggregates.size() + 1);  // no reallocation: coarse levels point into themselves
  Level fine;
  fine.n = s.block_count();
  fine.diag = &s.diagonals();
  fine.off = &s.off_diagonal();
  fine.pos = saved->positions;
  levels_.push_back(std::move(fine));
  for (std::size_t l = 0;; ++l) {
    Level& L = levels_.back();
    build_columns(L);
    build_rows(L);
    invert_diagonal(L);
    if (l == saved->aggregates.size()) break;
    Level C;
    L.agg = saved->aggregates[l];
    C.n = saved->coarse_blocks[l];
    place_aggregates(L, C);
    L.omega = saved->omega[l];
    levels_.push_back(std::move(C));
    Level& Lf = levels_[levels_.size() - 2];
    Level& Lc = levels_.back();
    Lc.diag = &Lc.own_diag;
    Lc.off = &Lc.own_off;
    galerkin(Lf, Lc, true);
  }
  factor_coarsest();
}

}  // namespace rheodda::core
