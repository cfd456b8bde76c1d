// Internal to rheodda_fit: starting points of the nonlinear fit from a
// separable (variable-projection) least-squares search.
//
// Once the retardation times tau = eta/E of the Kelvin elements are fixed, the
// staged response of every series law is linear in its compliances
// (1/E1, 1/E of each Kelvin element, 1/eta of a dashpot), each >= 0; the
// Bingham element of Nishihara adds c*A(t) - v*B(t) with c = 1/eta3 and
// v = Fs/eta3, linear too while the set of stages that flow is fixed, i.e. for
// Fs within one interval [lo, hi] between two consecutive stress levels
// (constraints c >= 0, lo c <= v <= hi c). For every node of a log-spaced grid
// of retardation times over the data's time span, the linear subproblem is
// solved exactly (a convex quadratic programme on a polyhedral cone: the best
// of the equality-constrained least-squares solutions of its faces that is
// feasible), which is the variable projection of Golub & Pereyra (SIAM J.
// Numer. Anal. 10 (1973) 413-432; Inverse Problems 19 (2003) R1-R26) with the
// few nonlinear parameters searched on a grid instead of by descent. The best
// nodes (local minima of the projected sum of squares over the grid) are the
// starts that GSL then polishes on the full parameter set.
#pragma once

#include <cstddef>
#include <vector>

#include "rheodda/fit/creep_data.hpp"
#include "series_structure.hpp"

namespace rheodda::fit::detail {

struct VarProStart {
  std::vector<double> values;  ///< parameters in registry order, all > 0
  double rss = 0.0;            ///< projected sum of squares at the node (scaled, on the sample)
};

struct VarProSettings {
  int per_decade = 10;            ///< grid nodes of tau per decade
  /// The search uses at most about this many points (every stride-th point of
  /// each stage); the polish uses them all.
  std::size_t max_points = 400;
  int max_starts = 3;             ///< local minima of the grid returned, best first
};

/// Grid nodes of the retardation-time search, for the report (0 for a law without Kelvin element).
struct VarProStats {
  std::size_t nodes = 0;   ///< grid nodes evaluated
  std::size_t points = 0;  ///< points used by the search
};

/// Starts for a series law; empty for a law with more than two Kelvin
/// elements (the fit then relies on its multi-start search alone).
/// `inv_scale` scales displacements as the nonlinear fit does.
std::vector<VarProStart> varpro_starts(const SeriesStructure& s, std::size_t np,
                                       const CreepData& data, double inv_scale,
                                       const VarProSettings& settings, VarProStats* stats = nullptr);

/// The linear part re-solved exactly, on every data point, at the
/// retardation times of `values` (parameters in registry order): the
/// compliances and the Nishihara threshold of `values` are replaced by the
/// exact solution of the linear subproblem there. Used after GSL's polish,
/// which cannot settle exactly on a threshold equal to a stress level (the
/// curve has a kink in Fs there). false when it does not apply.
bool varpro_refine(const SeriesStructure& s, const CreepData& data, double inv_scale,
                   std::vector<double>& values);

}  // namespace rheodda::fit::detail
