// Internal to rheodda_fit: the least-squares problem of a fit (one law on one
// data set) and its residual and Jacobian callbacks for GSL (residuals.cpp).
// The residuals are analytic for a series law (series_structure.hpp), through
// laws::exact_displacement for any other registered law.
#pragma once

#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#include <cstddef>
#include <optional>
#include <vector>

#include "rheodda/fit/creep_data.hpp"
#include "rheodda/laws/registry.hpp"
#include "series_structure.hpp"

namespace rheodda::fit::detail {

// ---- The least-squares problem ------------------------------------------------
struct Problem {
  const laws::LawInfo* info = nullptr;
  const CreepData* data = nullptr;
  std::optional<SeriesStructure> structure;
  std::size_t n = 0, np = 0;
  // residuals are (model - data) * weight * inv_scale, inv_scale = 1/max|data * weight|, so that they are O(1)
  double inv_scale = 1.0;
  std::vector<double> weight;  // per point, 1/sigma (CreepData::sigma); empty: 1 for every point
  std::vector<double> stage_t, stage_f, flow_before;  // flow_before[k] = sum_{i<k} F_i (t_{i+1} - t_i)
  // Cache: the analytic Jacobian is computed with the residuals, at no extra exp() cost.
  std::vector<double> cached_x, cached_jac;
  std::vector<double> values;  // scratch: exp(x)
  std::vector<double> scratch_f;  // residuals when GSL's f is not contiguous
};

/// GSL's residual callback (gsl_multifit_nlinear_fdf::f): f = (model - data) * weight * inv_scale
/// at the parameters exp(x); `params` is the Problem.
int residual_cb(const gsl_vector* x, void* params, gsl_vector* f);
/// GSL's Jacobian callback (gsl_multifit_nlinear_fdf::df) for a series law,
/// with respect to the log parameters x.
int jacobian_cb(const gsl_vector* x, void* params, gsl_matrix* jac);

}  // namespace rheodda::fit::detail
