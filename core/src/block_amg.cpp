#include "block_amg.hpp"

#include "rheodda/core/solver.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace rheodda::core {

namespace {

using contact::Vec2;
using contact::Vec6;

/// P_i of the header: the block displacement of the aggregate's affine field
/// at offset (dx, dy) from the aggregate's centre.
Mat6 transfer_block(const Vec2& d) {
  Mat6 P = Mat6::Identity();
  P(0, 2) = -d.y();
  P(0, 3) = d.x();
  P(0, 5) = 0.5 * d.y();
  P(1, 2) = d.x();
  P(1, 4) = d.y();
  P(1, 5) = 0.5 * d.x();
  return P;
}

Mat6 inverse_spd(const Mat6& a, int block, int level) {
  Eigen::LLT<Mat6> llt(a);
  if (llt.info() != Eigen::Success)
    throw SingularSystemError("amg: diagonal block " + std::to_string(block) + " of level " +
                                  std::to_string(level) + " is not positive definite",
                              level == 0 ? block : -1, -1);
  return llt.solve(Mat6::Identity());
}

}  // namespace

bool BlockAmg::same_pattern(const BlockSystem& s) const {
  // A restored hierarchy not yet rebuilt (restore()) has its level-0 points.
  const std::size_t built = pending_         ? pending_->positions.size()
                            : levels_.empty() ? 0
                                              : static_cast<std::size_t>(levels_[0].n);
  if (built == 0 || static_cast<std::size_t>(s.block_count()) != built ||
      s.off_diagonal().size() != pattern_.size())
    return false;
  const auto& off = s.off_diagonal();
  for (std::size_t k = 0; k < off.size(); ++k)
    if (off[k].i != pattern_[k].first || off[k].j != pattern_[k].second) return false;
  return true;
}

void BlockAmg::build_columns(Level& L) const {
  L.col_start.assign(static_cast<std::size_t>(L.n) + 1, 0);
  for (const auto& o : *L.off) ++L.col_start[o.j + 1];
  std::partial_sum(L.col_start.begin(), L.col_start.end(), L.col_start.begin());
}

void BlockAmg::invert_diagonal(Level& L) const {
  L.diag_inv.resize(static_cast<std::size_t>(L.n));
  const int level = static_cast<int>(&L - levels_.data());
  for (int i = 0; i < L.n; ++i) L.diag_inv[i] = inverse_spd((*L.diag)[i], i, level);
}

bool BlockAmg::aggregate(Level& L, Level& C) const {
  const int n = L.n;
  const auto& off = *L.off;
  const auto& diag = *L.diag;
  // Strong neighbours, both ways (CSR).
  std::vector<double> dnorm(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) dnorm[i] = diag[i].norm();
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  std::vector<char> strong(off.size(), 0);
  for (std::size_t k = 0; k < off.size(); ++k) {
    const auto& o = off[k];
    const double s = o.k.norm();
    if (s > kStrength * std::sqrt(dnorm[o.i] * dnorm[o.j])) {
      strong[k] = 1;
      ++start[o.i + 1];
      ++start[o.j + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> nbr(static_cast<std::size_t>(start[n]));
  std::vector<double> weight(nbr.size());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < off.size(); ++k) {
      if (!strong[k]) continue;
      const auto& o = off[k];
      const double w = o.k.norm() / std::sqrt(dnorm[o.i] * dnorm[o.j]);
      nbr[fill[o.i]] = o.j;
      weight[fill[o.i]++] = w;
      nbr[fill[o.j]] = o.i;
      weight[fill[o.j]++] = w;
    }
  }
  // Pass 1: a block whose strong neighbours are all free starts an aggregate
  // with them. Pass 2: a free block joins the aggregate of its strongest
  // aggregated neighbour. Pass 3: what is left groups with its free strong
  // neighbours (or stands alone).
  L.agg.assign(static_cast<std::size_t>(n), -1);
  int count = 0;
  for (int i = 0; i < n; ++i) {
    if (L.agg[i] >= 0 || start[i] == start[i + 1]) continue;
    bool free = true;
    for (int q = start[i]; q < start[i + 1] && free; ++q) free = L.agg[nbr[q]] < 0;
    if (!free) continue;
    L.agg[i] = count;
    for (int q = start[i]; q < start[i + 1]; ++q) L.agg[nbr[q]] = count;
    ++count;
  }
  std::vector<int> joined(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (L.agg[i] >= 0) continue;
    double best = 0.0;
    for (int q = start[i]; q < start[i + 1]; ++q)
      if (L.agg[nbr[q]] >= 0 && weight[q] > best) {
        best = weight[q];
        joined[i] = L.agg[nbr[q]];
      }
  }
  for (int i = 0; i < n; ++i)
    if (joined[i] >= 0) L.agg[i] = joined[i];
  for (int i = 0; i < n; ++i) {
    if (L.agg[i] >= 0) continue;
    L.agg[i] = count;
    for (int q = start[i]; q < start[i + 1]; ++q)
      if (L.agg[nbr[q]] < 0) L.agg[nbr[q]] = count;
    ++count;
  }
  if (count > n * 3 / 4) return false;  // too little coarsening to be worth a level

  // Coarse centres and tentative transfer blocks.
  C.n = count;
  place_aggregates(L, C);
  L.omega = 4.0 / (3.0 * lambda_max(L));
  return true;
}

void BlockAmg::build_rows(Level& L) const {
  const auto& off = *L.off;
  L.row_start.assign(static_cast<std::size_t>(L.n) + 1, 0);
  for (const auto& o : off) {
    ++L.row_start[o.i + 1];
    ++L.row_start[o.j + 1];
  }
  std::partial_sum(L.row_start.begin(), L.row_start.end(), L.row_start.begin());
  const std::size_t m = static_cast<std::size_t>(L.row_start[L.n]);
  L.row_nbr.resize(m);
  L.row_off.resize(m);
  L.row_t.resize(m);
  std::vector<int> fill(L.row_start.begin(), L.row_start.end() - 1);
  for (std::size_t k = 0; k < off.size(); ++k) {
    const auto& o = off[k];
    int q = fill[o.i]++;
    L.row_nbr[q] = o.j, L.row_off[q] = static_cast<int>(k), L.row_t[q] = 0;  // A_ij = K
    q = fill[o.j]++;
    L.row_nbr[q] = o.i, L.row_off[q] = static_cast<int>(k), L.row_t[q] = 1;  // A_ji = K^T
  }
}

double BlockAmg::lambda_max(const Level& L) const {
  // Power iteration on D^-1 A (its eigenvalues are real and positive: it is
  // similar to D^-1/2 A D^-1/2); a few steps from a rough start, then 10 %
  // margin, since omega only has to stay below 2 / lambda_max.
  Eigen::VectorXd v(6 * L.n), w(6 * L.n);
  for (Eigen::Index k = 0; k < v.size(); ++k) v(k) = 1.0 + 0.37 * static_cast<double>(k % 7);
  double lambda = 1.0;
  for (int it = 0; it < 12; ++it) {
    v /= v.norm();
    for (int i = 0; i < L.n; ++i) w.segment<6>(6 * i).noalias() = (*L.diag)[i] * v.segment<6>(6 * i);
    for (const auto& o : *L.off) {
      w.segment<6>(6 * o.i).noalias() += o.k * v.segment<6>(6 * o.j);
      w.segment<6>(6 * o.j).noalias() += o.k.transpose() * v.segment<6>(6 * o.i);
    }
    for (int i = 0; i < L.n; ++i) v.segment<6>(6 * i) = L.diag_inv[i] * w.segment<6>(6 * i);
    lambda = v.norm();
  }
  return 1.1 * lambda;
}

namespace {

/// Adds m to the entry of column col in a short list of (column, block).
void accumulate(std::vector<std::pair<int, Mat6>>& row, int col, const Mat6& m) {
  for (auto& e : row)
    if (e.first == col) {
      e.second += m;
      return;
    }
  row.emplace_back(col, m);
}

}  // namespace

void BlockAmg::smooth_prolongator(Level& L) const {
  // P_i* = P0_i (1 - omega) at agg(i) - omega A_ii^-1 sum_j A_ij P0_j at agg(j).
  const auto& off = *L.off;
  L.p_start.assign(1, 0);
  L.p_col.clear();
  L.p_val.clear();
  std::vector<std::pair<int, Mat6>> row;
  for (int i = 0; i < L.n; ++i) {
    row.clear();
    row.emplace_back(L.agg[i], (1.0 - L.omega) * L.P0[i]);
    const Mat6 w = -L.omega * L.diag_inv[i];
    for (int q = L.row_start[i]; q < L.row_start[i + 1]; ++q) {
      const int j = L.row_nbr[q];
      const Mat6& K = off[L.row_off[q]].k;
      const Mat6 aij_p = L.row_t[q] ? Mat6(K.transpose() * L.P0[j]) : Mat6(K * L.P0[j]);
      accumulate(row, L.agg[j], w * aij_p);
    }
    for (const auto& [col, m] : row) {
      L.p_col.push_back(col);
      L.p_val.push_back(m);
    }
    L.p_start.push_back(static_cast<int>(L.p_col.size()));
  }
}

void BlockAmg::galerkin(Level& L, Level& C, bool build) const {
  // A_c = P^T A P = sum_i P_i*^T (A P)_i*, upper blocks only (a <= b), with
  // (A P)_i* = A_ii P_i* + sum_j A_ij P_j*. The sequence of (i, a, b) products
  // depends only on the pattern, so setup records each one's coarse slot and
  // a refresh replays them.
  smooth_prolongator(L);
  const auto& off = *L.off;
  std::vector<std::pair<int, Mat6>> ap;
  std::vector<std::pair<int, int>> keys;  // build: (a, b) of each product
  if (build) keys.reserve(static_cast<std::size_t>(L.n) * 16);
  if (!build) {
    for (auto& d : C.own_diag) d.setZero();
    for (auto& o : C.own_off) o.k.setZero();
  }
  std::size_t t = 0;
  for (int i = 0; i < L.n; ++i) {
    ap.clear();
    for (int q = L.p_start[i]; q < L.p_start[i + 1]; ++q)
      accumulate(ap, L.p_col[q], (*L.diag)[i] * L.p_val[q]);
    for (int r = L.row_start[i]; r < L.row_start[i + 1]; ++r) {
      const int j = L.row_nbr[r];
      const Mat6& K = off[L.row_off[r]].k;
      for (int q = L.p_start[j]; q < L.p_start[j + 1]; ++q)
        accumulate(ap, L.p_col[q],
                   L.row_t[r] ? Mat6(K.transpose() * L.p_val[q]) : Mat6(K * L.p_val[q]));
    }
    for (int q = L.p_start[i]; q < L.p_start[i + 1]; ++q) {
      const int a = L.p_col[q];
      for (const auto& [b, m] : ap) {
        if (a > b) continue;
        if (build) {
          keys.emplace_back(a, b);
          continue;
        }
        const int slot = L.g_slot[t++];
        const Mat6 prod = L.p_val[q].transpose() * m;
        if (slot < 0)
          C.own_diag[-1 - slot] += prod;
        else
          C.own_off[slot].k += prod;
      }
    }
  }
  if (!build) return;
  // Coarse pattern: distinct (a < b) sorted by column b, then row a.
  std::vector<std::pair<int, int>> upper;
  for (const auto& k : keys)
    if (k.first < k.second) upper.emplace_back(k.second, k.first);
  std::sort(upper.begin(), upper.end());
  upper.erase(std::unique(upper.begin(), upper.end()), upper.end());
  C.own_off.resize(upper.size());
  for (std::size_t k = 0; k < upper.size(); ++k) C.own_off[k] = {upper[k].second, upper[k].first, Mat6::Zero()};
  C.own_diag.assign(static_cast<std::size_t>(C.n), Mat6::Zero());
  L.g_slot.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const auto [a, b] = keys[k];
    if (a == b) {
      L.g_slot[k] = -1 - a;
    } else {
      const auto it = std::lower_bound(upper.begin(), upper.end(), std::make_pair(b, a));
      L.g_slot[k] = static_cast<int>(it - upper.begin());
    }
  }
  galerkin(L, C, false);
}

void BlockAmg::factor_coarsest() {
  const Level& L = levels_.back();
  const int n = L.n;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int b = 0; b < n; ++b) K.block<6, 6>(6 * b, 6 * b) = (*L.diag)[b];
  for (const auto& o : *L.off) {
    K.block<6, 6>(6 * o.i, 6 * o.j) += o.k;
    K.block<6, 6>(6 * o.j, 6 * o.i) += o.k.transpose();
  }
  coarse_llt_.compute(K);
  coarse_definite_ = coarse_llt_.info() == Eigen::Success;
  // A semi-definite coarse matrix (a static model with a free rigid motion)
  // still gives a usable correction through LDL'.
  if (!coarse_definite_) coarse_ldlt_.compute(K);
}

void BlockAmg::setup(const BlockSystem& s) {
  pending_.reset();
  levels_.clear();
  levels_.reserve(16);
  pattern_.clear();
  for (const auto& o : s.off_diagonal()) pattern_.emplace_back(o.i, o.j);
  Level fine;
  fine.n = s.block_count();
  fine.diag = &s.diagonals();
  fine.off = &s.off_diagonal();
  fine.pos = s.centroids();
  fine.pos.resize(static_cast<std::size_t>(fine.n), Vec2::Zero());
  levels_.push_back(std::move(fine));
  for (;;) {
    Level& L = levels_.back();
    build_columns(L);
    build_rows(L);
    invert_diagonal(L);
    if (L.n <= kCoarsest) break;
    Level C;
    if (!aggregate(L, C)) {
      L.agg.clear();
      break;
    }
    levels_.push_back(std::move(C));
    Level& Lf = levels_[levels_.size() - 2];
    Level& Lc = levels_.back();
    Lc.diag = &Lc.own_diag;  // the move invalidated the pointers into C
    Lc.off = &Lc.own_off;
    galerkin(Lf, Lc, true);
  }
  factor_coarsest();
}

void BlockAmg::refresh(const BlockSystem& s) {
  if (pending_) rebuild(s);
  levels_[0].diag = &s.diagonals();
  levels_[0].off = &s.off_diagonal();
  // Blocks that moved since the last setup or refresh (a pattern can hold for
  // many steps; the iterates of one step share their geometry): the centres,
  // tentative transfers and smoothing weights follow them.
  std::vector<Vec2> pos = s.centroids();
  pos.resize(static_cast<std::size_t>(levels_[0].n), Vec2::Zero());
  const bool moved = pos != levels_[0].pos;
  if (moved) levels_[0].pos = std::move(pos);
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    if (l > 0) {
      Level& F = levels_[l - 1];
      Level& C = levels_[l];
      if (moved) {
        place_aggregates(F, C);
        F.omega = 4.0 / (3.0 * lambda_max(F));
      }
      galerkin(F, C, false);
    }
    invert_diagonal(levels_[l]);
  }
  factor_coarsest();
}

void BlockAmg::place_aggregates(Level& L, Level& C) const {
  C.pos.assign(static_cast<std::size_t>(C.n), Vec2::Zero());
  std::vector<int> members(static_cast<std::size_t>(C.n), 0);
  for (int i = 0; i < L.n; ++i) {
    C.pos[L.agg[i]] += L.pos[i];
    ++members[L.agg[i]];
  }
  for (int a = 0; a < C.n; ++a) C.pos[a] /= members[a];
  L.P0.resize(static_cast<std::size_t>(L.n));
  for (int i = 0; i < L.n; ++i) L.P0[i] = transfer_block(L.pos[i] - C.pos[L.agg[i]]);
}

void BlockAmg::residual(Level& L) const {
  // After a forward sweep from x = 0, (D + L) x = b holds row by row, so
  // r = b - A x = -U x: only the upper blocks, one product each.
  L.r.setZero(6 * L.n);
  for (const auto& o : *L.off) L.r.segment<6>(6 * o.i).noalias() -= o.k * L.x.segment<6>(6 * o.j);
}

void BlockAmg::forward_sweep(Level& L) const {
  // Forward Gauss-Seidel with the upper blocks stored by column: the upper
  // part of row j uses the old x (here zero), the lower part of row j
  // (column j's upper blocks, transposed) the x already updated.
  // Called from x = 0 (the pre-smoothing of a V-cycle), so U x_old = 0.
  const auto& off = *L.off;
  for (int j = 0; j < L.n; ++j) {
    Vec6 s = L.b.segment<6>(6 * j);
    for (int q = L.col_start[j]; q < L.col_start[j + 1]; ++q)
      s.noalias() -= off[q].k.transpose() * L.x.segment<6>(6 * off[q].i);
    L.x.segment<6>(6 * j).noalias() = L.diag_inv[j] * s;
  }
}

void BlockAmg::backward_sweep(Level& L) const {
  // Backward Gauss-Seidel: the lower part of row j uses the old x (column j,
  // computed before x_j changes), the upper part the x already updated
  // (scattered from column j' > j as soon as x_j' is new).
  const auto& off = *L.off;
  L.t.setZero(6 * L.n);
  for (int j = L.n - 1; j >= 0; --j) {
    Vec6 s = L.b.segment<6>(6 * j) - L.t.segment<6>(6 * j);
    for (int q = L.col_start[j]; q < L.col_start[j + 1]; ++q)
      s.noalias() -= off[q].k.transpose() * L.x.segment<6>(6 * off[q].i);
    L.x.segment<6>(6 * j).noalias() = L.diag_inv[j] * s;
    for (int q = L.col_start[j]; q < L.col_start[j + 1]; ++q)
      L.t.segment<6>(6 * off[q].i).noalias() += off[q].k * L.x.segment<6>(6 * j);
  }
}

void BlockAmg::vcycle(std::size_t l) {
  Level& L = levels_[l];
  if (l + 1 == levels_.size()) {
    L.x = coarse_definite_ ? Eigen::VectorXd(coarse_llt_.solve(L.b))
                           : Eigen::VectorXd(coarse_ldlt_.solve(L.b));
    return;
  }
  L.x.setZero(6 * L.n);
  forward_sweep(L);
  residual(L);
  Level& C = levels_[l + 1];
  C.b.setZero(6 * C.n);
  for (int i = 0; i < L.n; ++i)
    for (int q = L.p_start[i]; q < L.p_start[i + 1]; ++q)
      C.b.segment<6>(6 * L.p_col[q]).noalias() += L.p_val[q].transpose() * L.r.segment<6>(6 * i);
  vcycle(l + 1);
  for (int i = 0; i < L.n; ++i)
    for (int q = L.p_start[i]; q < L.p_start[i + 1]; ++q)
      L.x.segment<6>(6 * i).noalias() += L.p_val[q] * C.x.segment<6>(6 * L.p_col[q]);
  backward_sweep(L);
}

void BlockAmg::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  levels_[0].b = r;
  vcycle(0);
  z = levels_[0].x;
}

}  // namespace rheodda::core
