// Internal to rheodda_fit: GSL's nonlinear least-squares solver driven on one
// data set (gsl_solver.cpp), and what the fit shares to hold GSL objects.
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>

#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "expression.hpp"
#include "residuals.hpp"
#include "rheodda/fit/fit.hpp"

namespace rheodda::fit::detail {

struct ErrorHandlerOff {
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  ~ErrorHandlerOff() { gsl_set_error_handler(old); }
};

struct GslFree {
  void operator()(gsl_multifit_nlinear_workspace* w) const { gsl_multifit_nlinear_free(w); }
  void operator()(gsl_vector* v) const { gsl_vector_free(v); }
  void operator()(gsl_matrix* m) const { gsl_matrix_free(m); }
};

/// Every stride-th point of each stage (its first and last always), at most
/// about max_points in all.
CreepData subsample(const CreepData& d, std::size_t max_points);

// Which log parameters GSL varies and how bounds are kept (docs/guide/fitting.md,
// "Initial values, bounds, fixed parameters and weights"): GSL works on z, one
// entry per free parameter, and the log parameter x = ln p is
//   both bounds  x = lo + (sin z + 1)(hi - lo)/2
//   lo only      x = lo - 1 + sqrt(z^2 + 1)
//   hi only      x = hi + 1 - sqrt(z^2 + 1)
//   none         x = z
// (the transforms of MINUIT, F. James, MINUIT Reference Manual, CERN D506,
// sec. 1.3, as lmfit uses them), so every z is inside the bounds. The
// parameters that are not free keep their entry of `x`, but for those given by
// an expression of the others (lmfit's expr), recomputed from them:
// x_k = ln e(p), its derivative by the chain rule (chain()).
struct Derived {
  std::size_t k = 0;  // registry index of the parameter
  Expression e;       // of the parameters' values
};

struct Mapping {
  std::vector<std::size_t> free;  // registry indices of the free parameters
  std::vector<double> x;          // log value of every parameter (the fixed ones are used)
  std::vector<double> lo, hi;     // log bounds of each free parameter (-inf, +inf: none)
  std::vector<Derived> derived;   // parameters given by expressions, in an order that evaluates each after its uses

  /// x_k = ln e(exp(x)) of every derived parameter, in order (ln of a value <= 0: -700).
  void apply_derived(std::vector<double>& xs) const;
  /// d x_k / d x_j (row-major np x np) at the log parameters `xs`: the identity
  /// in the rows of parameters that are not derived; for a derived k,
  /// sum_m (p_m/e) de/dp_m d x_m/d x_j.
  std::vector<double> chain(const std::vector<double>& xs) const;
  /// Any finite bound on a free parameter.
  bool bounded() const;

  /// Every log parameter at free values z.
  std::vector<double> to_full(const double* z) const;
  /// The free values z of the log parameters `x`, clamped into the bounds;
  /// with `margin`, moved inside them by 1e-3 of the range (at most 1e-3):
  /// a start on a bound has no gradient in z.
  std::vector<double> to_free(const std::vector<double>& x, bool margin = true) const;
  /// dx/dz of free parameter a at z.
  double derivative(std::size_t a, double z) const;
};

// GSL's trust-region solver (Levenberg-Marquardt steps, modified Cholesky)
// set up for one data set; not copyable (GSL holds a pointer to the problem).
class Solver {
 public:
  Problem pr;

  /// `weight`: per point (1/sigma), empty for none; `mapping`: GSL varies
  /// the free parameters of it only (none: every log parameter, unbounded).
  Solver(const laws::LawInfo& info, const CreepData& data, const std::optional<SeriesStructure>& structure,
         double inv_scale, std::vector<double> weight = {}, std::optional<Mapping> mapping = std::nullopt);
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  struct Outcome {
    double rss = std::numeric_limits<double>::infinity();  // scaled
    std::vector<double> position;                           // log parameters
    int status = GSL_FAILURE;
    int iterations = 0;
  };

  // From `start` (log parameters): the loop of gsl_multifit_nlinear_driver
  // (step tolerance 1e-10 on the log parameters), except that it stops as soon
  // as the sum of squares reaches stop_at (relative 1e-7, within the 1e-6 at
  // which starts count as agreeing; stop_at < 0: never): the start has found
  // that minimum. With a bound on a free parameter, the projected
  // Levenberg-Marquardt of bounded_polish.hpp then takes the point to the
  // constrained minimum (MINUIT's transforms reach a bound in the limit only:
  // their derivative vanishes there and the steps stall short of it); the
  // status is GSL_SUCCESS only where the optimality conditions hold there.
  // With `refine`, the linear part is then
  // re-solved exactly at the polished retardation times (varpro_refine):
  // GSL stops near, not on, a threshold equal to a stress level.
  Outcome polish(const std::vector<double>& start, double stop_at, double floor, const FitOptions& options,
                 bool refine);

  // The workspace initialised at `position` (log parameters): residuals and
  // Jacobian there (with a mapping: with respect to its z).
  gsl_multifit_nlinear_workspace* at(const std::vector<double>& position);

  const std::optional<Mapping>& mapping() const { return mapping_; }

 private:
  static int mapped_residual_cb(const gsl_vector* z, void* params, gsl_vector* f);
  static int mapped_jacobian_cb(const gsl_vector* z, void* params, gsl_matrix* jac);
  void set_full(const gsl_vector* z);

  std::optional<Mapping> mapping_;
  std::unique_ptr<gsl_vector, GslFree> x_full_;   // with a mapping: the log parameters
  std::unique_ptr<gsl_matrix, GslFree> jac_full_;  // with a mapping: the Jacobian in them
  gsl_multifit_nlinear_fdf fdf_{};
  std::unique_ptr<gsl_multifit_nlinear_workspace, GslFree> w_;
  std::unique_ptr<gsl_vector, GslFree> x_, fv_;
};

}  // namespace rheodda::fit::detail
