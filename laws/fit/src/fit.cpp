#include "rheodda/fit/fit.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <optional>

#include "bounded_polish.hpp"
#include "fit_input.hpp"
#include "fit_settings.hpp"
#include "gsl_solver.hpp"
#include "identifiability.hpp"
#include "search.hpp"
#include "rheodda/laws/series_law.hpp"
#include "series_structure.hpp"
#include "starts.hpp"
#include "varpro.hpp"

namespace rheodda::fit {

laws::ParameterValues FitResult::values() const {
  laws::ParameterValues v;
  for (const auto& p : parameters) v[p.name] = p.value;
  return v;
}

std::vector<double> predict(const laws::ContactRheology& law, const laws::StagedHistory& history,
                            const std::vector<double>& times) {
  std::vector<double> out;
  out.reserve(times.size());
  for (double t : times) {
    const auto d = laws::exact_displacement(law, history, t);
    if (!d)
      throw FitError(std::string(law.name()),
                     fmt::format("law '{}' has no exact response to a staged stress history",
                                 law.name()));
    out.push_back(*d);
  }
  return out;
}

namespace {

using detail::check_input;
using detail::Constraints;
using detail::DataScale;
using detail::Search;
using detail::search_minimum;
using detail::Element;
using detail::Kind;
using detail::SeriesStructure;
using detail::analyse_curve;
using detail::Candidate;
using detail::combination_candidates;
using detail::CurveFeatures;
using detail::ErrorHandlerOff;
using detail::generic_start;
using detail::GslFree;
using detail::identify;
using detail::Mapping;
using detail::probe_structure;
using detail::read_settings;
using detail::Problem;
using detail::restart_start;
using detail::series_start;
using detail::Solver;
using detail::subsample;

std::string fmt_g(double v) { return fmt::format("{:.4g}", v); }

// ---- 1. The input (fit_input.cpp) and 2. the search (search.cpp) ------------------

// Kelvin elements in series are interchangeable; report them ordered by
// retardation time eta/E, shortest first (E2, eta2 the fast one), so the
// labels do not depend on which start won.
void order_kelvins(const SeriesStructure& s, std::vector<double>& x) {
  std::vector<const Element*> kelvins;
  for (const auto& el : s.elements)
    if (el.kind == Kind::kelvin) kelvins.push_back(&el);
  std::vector<std::pair<double, double>> pairs;  // (ln E, ln eta)
  for (const auto* el : kelvins) pairs.emplace_back(x[el->E], x[el->eta]);
  std::stable_sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    return a.second - a.first < b.second - b.first;
  });
  for (std::size_t i = 0; i < kelvins.size(); ++i) {
    x[kelvins[i]->E] = pairs[i].first;
    x[kelvins[i]->eta] = pairs[i].second;
  }
}

// ---- 3. The result: goodness of fit and how certain the minimum is ------------
// `best_rss`: the scaled sum of squares at the reported point; `weight` 1/sigma or empty.
void add_statistics(FitResult& res, const CreepData& data, const std::vector<double>& fitted_scaled,
                    double best_rss, const DataScale& ds, const std::vector<double>& weight, std::size_t np) {
  const std::size_t n = data.t.size();
  const double scale = ds.scale, mean = ds.mean, dmax = ds.dmax;
  res.chi_square = best_rss * scale * scale;
  res.rss = weight.empty() ? res.chi_square : 0.0;
  double tss = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    // scaled residual f = (d_model - d) * weight / scale
    res.fitted.push_back(data.displacement[j] + fitted_scaled[j] * scale / (weight.empty() ? 1.0 : weight[j]));
    if (!weight.empty()) res.rss += (res.fitted[j] - data.displacement[j]) * (res.fitted[j] - data.displacement[j]);
    tss += (data.displacement[j] - mean) * (data.displacement[j] - mean);
  }
  // R^2 = 1 - RSS/TSS is undefined when the data have no spread: TSS at the
  // level of rounding (rms spread below 1e-10 of the largest displacement).
  const double nd = static_cast<double>(n), k = static_cast<double>(np);
  res.r2 = tss > nd * (1e-10 * dmax) * (1e-10 * dmax) ? 1.0 - res.rss / tss
                                                      : std::numeric_limits<double>::quiet_NaN();
  res.rmse = std::sqrt(res.rss / nd);
  res.reduced_chi_square = res.chi_square / (nd - k);
  // Akaike and Bayesian information criteria of a least-squares fit with
  // Gaussian errors (Burnham & Anderson, Model Selection and Multimodel
  // Inference, 2nd ed. 2002, sec. 2.2; lmfit's aic and bic): n ln(chi^2/n) + 2k, + k ln n.
  const double log_mse = std::log(std::max(res.chi_square / nd, std::numeric_limits<double>::min()));
  res.aic = nd * log_mse + 2.0 * k;
  res.bic = nd * log_mse + k * std::log(nd);
}

// Is the minimum certain? (docs/guide/fitting.md, "When the minimum is not certain")
// `not_optimal`: which optimality condition fails at the point reported (empty: none).
void judge_minimum(FitResult& res, const Search& sr, double scale, const std::string& not_optimal) {
  const double floor = sr.floor;
  res.starts_agreeing = sr.agreeing_sample;
  for (double rs : sr.rss_full) res.starts_agreeing += std::abs(rs - sr.best_rss) <= 1e-6 * sr.best_rss + floor;
  if (sr.structured > 0 && (sr.reference_lower || sr.best_rss < sr.structured_rss * (1.0 - 1e-6) - floor)) {
    res.minimum_certain = false;
    res.minimum_note = fmt::format(
        "the multi-start reference found a lower sum of squares than the variable-projection "
        "search ({} {:.6g} < {:.6g}): other minima may exist",
        res.weighted ? "chi-square" : "RSS", res.chi_square, sr.structured_rss * scale * scale);
  } else if (res.starts_agreeing < 2) {
    res.minimum_certain = false;
    res.minimum_note = res.starts > 1 ? fmt::format("it was reached from one start only (of {})", res.starts)
                                      : std::string("only one start was tried");
  }
  auto& warn = res.warnings;
  if (!res.converged && !not_optimal.empty())
    warn.push_back(fmt::format("the fit stopped before reaching the minimum ({} iterations): {}; raise the "
                               "iteration limit (--max-iterations, max_iterations=)",
                               sr.best_iter, not_optimal));
  else if (!res.converged)
    warn.push_back(fmt::format("the fit stopped before converging ({}, {} iterations)",
                               gsl_strerror(sr.best_status), sr.best_iter));
  if (!res.minimum_certain)
    warn.push_back(fmt::format("the minimum is not certain: {}; try --restarts 20", res.minimum_note));
}

// ---- 4. The parameters: values, identifiability, standard errors, correlations ----
// `jac`: the Jacobian of the scaled residuals with respect to the log of the
// parameters `cols` (those the errors are for: every parameter, or with
// constraints the varying ones not on a bound); `s` the residual standard
// deviation (scaled).
void add_parameters(FitResult& res, const laws::LawInfo& info, const gsl_matrix* jac,
                    const std::vector<std::size_t>& cols, double s, const std::vector<double>& best_x,
                    const std::optional<SeriesStructure>& structure, const CreepData& data,
                    const FitOptions& options, std::vector<double>& cov) {
  const std::size_t n = data.t.size(), np = info.parameters.size(), m = cols.size();
  for (std::size_t i = 0; i < np; ++i) {
    ParameterEstimate e;
    e.name = info.parameters[i].name;
    e.unit = info.parameters[i].unit;
    e.value = std::exp(best_x[i]);
    res.parameters.push_back(e);
  }
  res.correlation.assign(np * np, std::numeric_limits<double>::quiet_NaN());
  if (m == 0) return;
  // Identifiability and standard errors from the SVD of the Jacobian (identify()),
  // on the parameters of `cols` only: the others are held.
  FitResult sub;
  for (std::size_t a = 0; a < m; ++a) sub.parameters.push_back(res.parameters[cols[a]]);
  {
    std::unique_ptr<gsl_matrix, GslFree> jc(gsl_matrix_alloc(n, m));
    gsl_matrix_memcpy(jc.get(), jac);
    std::vector<Candidate> candidates;
    if (structure)
      for (auto& c : combination_candidates(*structure, res.parameters, data)) {
        std::vector<double> g(m);
        for (std::size_t a = 0; a < m; ++a) g[a] = c.grad[cols[a]];
        c.grad = std::move(g);
        candidates.push_back(std::move(c));
      }
    identify(sub, jc.get(), s, candidates, options, cov);
  }
  for (std::size_t a = 0; a < m; ++a) {
    auto& e = res.parameters[cols[a]];
    e.std_error = sub.parameters[a].std_error;
    e.identifiable = sub.parameters[a].identifiable;
    e.reason = sub.parameters[a].reason;
  }
  res.singular_values = sub.singular_values;
  res.combinations = sub.combinations;
  res.warnings.insert(res.warnings.end(), sub.warnings.begin(), sub.warnings.end());
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < m; ++b) {
      const std::size_t i = cols[a], j = cols[b];
      if (!res.parameters[i].identifiable || !res.parameters[j].identifiable) continue;
      const double d = cov[a * m + a] * cov[b * m + b];
      res.correlation[i * np + j] = a == b ? 1.0 : (d > 0 ? cov[a * m + b] / std::sqrt(d) : 0.0);
    }
}

// The standard error of a parameter given by an expression (ParameterSetting::expr):
// se(ln p_k) = sqrt(g^T C g) with g_a = d ln p_k / d ln p_cols[a] (Mapping::chain)
// and C the covariance of the log parameters `cols` (delta method, as lmfit
// propagates its uncertainties to constrained parameters).
void add_derived_errors(FitResult& res, const Mapping& m, const std::vector<double>& x,
                        const std::vector<std::size_t>& cols, const std::vector<double>& cov) {
  if (m.derived.empty()) return;
  const std::size_t np = x.size(), mc = cols.size();
  const std::vector<double> D = m.chain(x);
  for (const auto& d : m.derived) {
    auto& e = res.parameters[d.k];
    double var = 0.0;
    for (std::size_t a = 0; a < mc; ++a) {
      const double ga = D[d.k * np + cols[a]];
      if (ga == 0.0) continue;
      if (!res.parameters[cols[a]].identifiable) {
        e.identifiable = false;
        e.reason = fmt::format("it is given by '{}', which depends on {}, not identifiable", e.expr,
                               res.parameters[cols[a]].name);
      }
      for (std::size_t b = 0; b < mc; ++b) var += ga * D[d.k * np + cols[b]] * cov[a * mc + b];
    }
    e.std_error = e.identifiable && var > 0.0 ? e.value * std::sqrt(var) : 0.0;
    if (e.value <= std::exp(-699.0))
      res.warnings.push_back(fmt::format("{} = {} is not positive at the fit: the law needs it > 0", e.name,
                                         e.expr));
  }
}

// ---- 5. Warnings: what the data cannot tell ----
void warn_data_limits(FitResult& res, const std::optional<SeriesStructure>& structure, const CreepData& data,
                      const CurveFeatures& features, const FitOptions& options) {
  const std::size_t n = data.t.size(), np = res.parameters.size();
  auto& warn = res.warnings;
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t j = i + 1; j < np; ++j)
      if (res.parameters[i].identifiable && res.parameters[j].identifiable &&
          std::abs(res.correlation_at(i, j)) > options.correlation_limit)
        warn.push_back(fmt::format("{} and {} are strongly correlated (corr = {:.4f}): the data "
                                   "fix a combination of them, not each",
                                   res.parameters[i].name, res.parameters[j].name,
                                   res.correlation_at(i, j)));
  for (const auto& e : res.parameters)
    if (e.identifiable && e.std_error > options.relative_error_limit * e.value)
      warn.push_back(fmt::format("{} is poorly constrained: its standard error is {:.0f}% of its "
                                 "value",
                                 e.name, 100.0 * e.std_error / e.value));
  if (structure) {
    const double duration = data.t.back() - data.stages.front().t;
    double first_step = duration;
    for (std::size_t j = 0; j < n; ++j)
      if (data.t[j] > data.stages.front().t) {
        first_step = data.t[j] - data.stages.front().t;
        break;
      }
    for (const auto& el : structure->elements) {
      const auto& p = res.parameters;
      if (el.kind == Kind::kelvin) {
        const double tau = p[el.eta].value / p[el.E].value;
        if (duration < options.retardation_factor * tau)
          warn.push_back(fmt::format(
              "the test lasts {}, shorter than {} x {}/{} = {}: the Kelvin element has not "
              "settled, so {} and {} trade off with the other parameters",
              fmt_g(duration), fmt_g(options.retardation_factor), p[el.eta].name, p[el.E].name,
              fmt_g(options.retardation_factor * tau), p[el.E].name, p[el.eta].name));
        if (tau < first_step)
          warn.push_back(fmt::format(
              "{}/{} = {} is shorter than the first sampling interval {}: that Kelvin "
              "element acts as part of the instantaneous response",
              p[el.eta].name, p[el.E].name, fmt_g(tau), fmt_g(first_step)));
      } else if (el.kind == Kind::bingham) {
        if (p[el.threshold].value >= features.f_max)
          warn.push_back(fmt::format("the threshold {} = {} is above every applied stress (max {}): "
                                     "{} is not constrained by the data",
                                     p[el.threshold].name, fmt_g(p[el.threshold].value),
                                     fmt_g(features.f_max), p[el.eta].name));
      }
    }
  }
}

}  // namespace

FitResult fit_law(const laws::LawInfo& info, const CreepData& data, const FitOptions& options) {
  if (!info.fittable)
    throw FitError(info.name, fmt::format("law '{}' cannot be fitted yet: its creep is nonlinear in the "
                                          "stress (docs/reference/laws.md, \"Nonlinear laws\"); compare it with the "
                                          "data through `rheodda law curve {}`",
                                          info.name, info.name));
  const ErrorHandlerOff handler_off;
  const std::size_t n = data.t.size(), np = info.parameters.size();
  const Constraints cons = read_settings(info, data, options);
  const DataScale ds = check_input(info, data, cons);

  const std::optional<SeriesStructure> structure = probe_structure(info);
  Solver full(info, data, structure, ds.inv_scale, cons.weight, cons.mapping);
  const CurveFeatures features = analyse_curve(data);
  Search sr = search_minimum(info, data, full, features, ds.dmax, options, cons);
  // (With settings the labels are the user's: a swap would move a setting to another element.)
  if (structure && options.parameters.empty()) order_kelvins(*structure, sr.best_x);

  // The model saw exp(clamp(x, -700, 700)) (to_values): report that.
  // (`sr.best_x` holds the derived parameters' values too: Mapping::to_full.)
  for (double& v : sr.best_x) v = std::clamp(v, -700.0, 700.0);
  // A parameter within 1e-6 (relative) of a bound is on it: MINUIT's transforms
  // reach a bound only in the limit.
  std::vector<std::string> at_bound(np);
  if (cons.mapping) {
    const auto& m = *cons.mapping;
    for (std::size_t a = 0; a < m.free.size(); ++a) {
      double& x = sr.best_x[m.free[a]];
      if (x - m.lo[a] < 1e-6) x = m.lo[a], at_bound[m.free[a]] = "min";
      else if (m.hi[a] - x < 1e-6) x = m.hi[a], at_bound[m.free[a]] = "max";
    }
    m.apply_derived(sr.best_x);
  }
  // Residuals and Jacobian at the best point.
  gsl_multifit_nlinear_workspace* w = full.at(sr.best_x);
  std::vector<double> fitted_scaled(gsl_multifit_nlinear_residual(w)->data,
                                    gsl_multifit_nlinear_residual(w)->data + n);
  double best_rss = sr.best_rss;
  if (cons.active) {  // at the point reported (a bound snapped to)
    best_rss = 0.0;
    for (double f : fitted_scaled) best_rss += f * f;
  }

  FitResult res;
  res.law = info.name;
  res.points = n;
  res.starts = sr.starts_total;
  res.structured_starts = sr.structured;
  res.iterations = sr.best_iter;
  res.converged = sr.best_status == GSL_SUCCESS || sr.best_status == GSL_ENOPROG;
  // With settings: converged only where the optimality conditions hold at the
  // point reported (bounded_polish.hpp), in the log of every varying parameter.
  std::string not_optimal;
  if (cons.mapping) {
    const Mapping& m = *cons.mapping;
    Mapping plain = m;
    plain.lo.assign(m.free.size(), -std::numeric_limits<double>::infinity());
    plain.hi.assign(m.free.size(), std::numeric_limits<double>::infinity());
    std::vector<int> side(m.free.size(), 0);
    for (std::size_t a = 0; a < m.free.size(); ++a)
      side[a] = at_bound[m.free[a]] == "min" ? -1 : at_bound[m.free[a]] == "max" ? 1 : 0;
    Solver ks(info, data, structure, ds.inv_scale, cons.weight, std::move(plain));
    gsl_multifit_nlinear_workspace* kw = ks.at(sr.best_x);
    const auto o = detail::optimality(gsl_multifit_nlinear_jac(kw), gsl_multifit_nlinear_residual(kw), side,
                                      detail::kOptimalityTolerance, sr.floor);
    res.optimality = o.worst;
    if (!o.holds) {
      const std::size_t k = m.free[o.worst_col];
      not_optimal = fmt::format(
          "the gradient of the sum of squares in {} is {:.2g} (as a cosine; at most {:g} at a minimum){}",
          info.parameters[k].name, o.worst, detail::kOptimalityTolerance,
          side[o.worst_col] != 0 ? fmt::format(", pointing into its bound {}", at_bound[k]) : std::string());
      res.converged = false;
    }
  }
  res.varying = static_cast<int>(cons.varying);
  res.weighted = !cons.weight.empty();
  res.scale_covariance = options.scale_covariance;
  const double scale = ds.scale;
  for (double r : sr.rss_full) res.start_minima.push_back(r * scale * scale);
  add_statistics(res, data, fitted_scaled, best_rss, ds, cons.weight, cons.varying);
  judge_minimum(res, sr, scale, not_optimal);

  // Standard errors: residual standard deviation sqrt(chi^2/(n - k)) (scaled),
  // or with absolute sigma the scale itself (the Jacobian of chi = f/inv_scale).
  const double s = options.scale_covariance
                       ? std::sqrt(best_rss / (static_cast<double>(n) - static_cast<double>(cons.varying)))
                       : ds.inv_scale;
  std::vector<double> cov;
  std::vector<std::size_t> cols;
  if (!cons.active) {
    cols.resize(np);
    for (std::size_t k = 0; k < np; ++k) cols[k] = k;
    add_parameters(res, info, gsl_multifit_nlinear_jac(w), cols, s, sr.best_x, structure, data, options, cov);
  } else {
    // The Jacobian in the log of the varying parameters not on a bound (the others held).
    Mapping held;
    held.x = sr.best_x;
    for (std::size_t k = 0; k < np; ++k)
      if (!cons.fixed[k] && cons.expr[k].empty() && at_bound[k].empty()) {
        held.free.push_back(k);
        held.lo.push_back(-std::numeric_limits<double>::infinity());
        held.hi.push_back(std::numeric_limits<double>::infinity());
      }
    held.derived = cons.mapping->derived;
    cols = held.free;
    Solver js(info, data, structure, ds.inv_scale, cons.weight, std::move(held));
    add_parameters(res, info, gsl_multifit_nlinear_jac(js.at(sr.best_x)), cols, s, sr.best_x, structure, data,
                   options, cov);
  }
  for (std::size_t k = 0; k < np; ++k) {
    auto& e = res.parameters[k];
    e.vary = !cons.fixed[k] && cons.expr[k].empty();
    e.expr = cons.expr[k];
    e.at_bound = at_bound[k];
    e.min = cons.min[k];
    e.max = cons.max[k];
    if (cons.fixed[k]) e.value = *cons.initial[k];
    else if (!e.at_bound.empty()) e.value = e.at_bound == "min" ? e.min : e.max;
  }
  if (cons.mapping) add_derived_errors(res, *cons.mapping, sr.best_x, cols, cov);
  warn_data_limits(res, structure, data, features, options);
  for (const auto& e : res.parameters)
    if (!e.at_bound.empty())
      res.warnings.push_back(fmt::format("{} ended on its bound {} = {:g}: it is held there for the standard "
                                         "errors, which do not include it",
                                         e.name, e.at_bound, e.at_bound == "min" ? e.min : e.max));
  return res;
}

std::vector<FitResult> fit_all(const laws::LawRegistry& registry, const CreepData& data,
                               Criterion criterion, std::vector<std::string>& skipped,
                               const FitOptions& options,
                               const std::function<void(const std::string&, std::size_t, std::size_t)>& on_law) {
  std::vector<FitResult> out;
  std::size_t index = 0;
  for (const auto& info : registry.laws()) {
    if (on_law) on_law(info.name, index++, registry.laws().size());
    try {
      out.push_back(fit_law(info, data, options));
    } catch (const FitError& e) {
      skipped.push_back(fmt::format("{}: {}", info.name, e.what()));
    }
  }
  std::stable_sort(out.begin(), out.end(), [criterion](const FitResult& a, const FitResult& b) {
    return criterion == Criterion::aic ? a.aic < b.aic : a.bic < b.bic;
  });
  return out;
}

}  // namespace rheodda::fit
