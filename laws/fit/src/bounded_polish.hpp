// Internal to rheodda_fit: a bounded fit taken to its constrained minimum, and
// the optimality (Karush-Kuhn-Tucker) conditions that say it is there
// (bounded_polish.cpp; docs/guide/fitting.md, "Initial values, bounds, fixed
// parameters and weights").
#pragma once

#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#include <cstddef>
#include <string>
#include <vector>

#include "gsl_solver.hpp"

namespace rheodda::fit::detail {

/// The optimality conditions of min ||f||^2 over box bounds at a point, from
/// the gradient g = J^T f of the half sum of squares in the free (log)
/// parameters: g_a = 0 for a parameter inside its bounds, g_a >= 0 at its
/// lower bound, g_a <= 0 at its upper one (Nocedal & Wright, Numerical
/// Optimization, 2nd ed. 2006, Theorem 12.1 and eq. 16.71 for bounds). Each g_a
/// is measured as the cosine of the angle between f and column a of J,
/// g_a / (||f|| ||J_a||) (MINPACK's gtol test, Moré, Garbow & Hillstrom,
/// ANL-80-74, 1980, sec. 2.3): a number in [-1, 1] whatever the units.
struct Optimality {
  bool holds = true;
  double worst = 0.0;         // the largest violation (a cosine)
  std::size_t worst_col = 0;  // its column of J
};

/// `side`: per column of J, -1 on its lower bound, +1 on its upper one, 0 inside.
/// A sum of squares below `floor` (rounding) holds trivially.
Optimality optimality(const gsl_matrix* J, const gsl_vector* f, const std::vector<int>& side, double tolerance,
                      double floor);

/// The cosine limit of optimality() for a fit reported as converged.
inline constexpr double kOptimalityTolerance = 1e-6;

struct BoundedOutcome {
  std::vector<double> x;  // log parameters (every parameter)
  double rss = 0.0;       // scaled, as Solver::Outcome::rss
  int iterations = 0;
  bool optimal = false;   // optimality() holds at x with kOptimalityTolerance
};

/// From `x` (log parameters), a projected Levenberg-Marquardt search over the
/// free parameters of the solver's mapping within their log bounds, with an
/// active set: a parameter on a bound whose gradient points out of the box
/// stays there; the others take the Levenberg-Marquardt step (Moré 1978) of
/// the Gauss-Newton model restricted to them, projected onto the box
/// (Bertsekas, Nonlinear Programming, 2nd ed. 1999, sec. 2.3, the projected
/// Newton method with its active set). At most `max_iterations` steps.
BoundedOutcome bounded_polish(Solver& solver, std::vector<double> x, int max_iterations);

}  // namespace rheodda::fit::detail
