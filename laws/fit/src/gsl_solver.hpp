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

// GSL's trust-region solver (Levenberg-Marquardt steps, modified Cholesky)
// set up for one data set; not copyable (GSL holds a pointer to the problem).
class Solver {
 public:
  Problem pr;

  Solver(const laws::LawInfo& info, const CreepData& data, const std::optional<SeriesStructure>& structure,
         double inv_scale);
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
  // that minimum. With `refine`, the linear part is then
  // re-solved exactly at the polished retardation times (varpro_refine):
  // GSL stops near, not on, a threshold equal to a stress level.
  Outcome polish(const std::vector<double>& start, double stop_at, double floor, const FitOptions& options,
                 bool refine);

  // The workspace initialised at `position` (log parameters): residuals and Jacobian there.
  gsl_multifit_nlinear_workspace* at(const std::vector<double>& position);

 private:
  gsl_multifit_nlinear_fdf fdf_{};
  std::unique_ptr<gsl_multifit_nlinear_workspace, GslFree> w_;
  std::unique_ptr<gsl_vector, GslFree> x_, fv_;
};

}  // namespace rheodda::fit::detail
