// Confidence intervals by profile likelihood (rheodda/fit/profile.hpp).
#include "rheodda/fit/profile.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_erf.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <memory>

namespace rheodda::fit {

namespace {

struct RootSolverFree {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};

// Brent's method on f over [a, b] (f(a) < 0 < f(b) or the reverse) to 1e-9 in
// the argument (GSL's gsl_root_fsolver_brent).
double brent(const std::function<double(double)>& f, double a, double b) {
  gsl_function F;
  F.function = [](double u, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(u); };
  F.params = const_cast<std::function<double(double)>*>(&f);
  std::unique_ptr<gsl_root_fsolver, RootSolverFree> s(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  gsl_root_fsolver_set(s.get(), &F, std::min(a, b), std::max(a, b));
  for (int i = 0; i < 100; ++i) {
    gsl_root_fsolver_iterate(s.get());
    const double lo = gsl_root_fsolver_x_lower(s.get()), hi = gsl_root_fsolver_x_upper(s.get());
    if (gsl_root_test_interval(lo, hi, 1e-9, 0.0) == GSL_SUCCESS) break;
  }
  return gsl_root_fsolver_root(s.get());
}

}  // namespace

std::vector<ProfileInterval> profile_intervals(const laws::LawInfo& law, const CreepData& data,
                                               const FitOptions& options, const FitResult& best,
                                               const std::vector<double>& sigmas,
                                               const std::vector<std::string>& names) {
  if (sigmas.empty()) throw FitError(law.name, "profile intervals: no level (sigmas) given");
  for (double s : sigmas)
    if (!(s > 0.0) || !std::isfinite(s))
      throw FitError(law.name, fmt::format("profile intervals: sigma {:g} is not a positive number", s));
  std::vector<std::string> wanted = names;
  if (wanted.empty())
    for (const auto& p : best.parameters)
      if (p.vary) wanted.push_back(p.name);
  const double n = static_cast<double>(best.points), k = static_cast<double>(best.varying);
  if (!(n - k > 0.0)) throw FitError(law.name, "profile intervals: no degrees of freedom left (n <= k)");
  // The chi^2 of each level (profile.hpp).
  std::vector<double> target;
  for (double s : sigmas) {
    const double prob = gsl_sf_erf(s / std::sqrt(2.0));
    target.push_back(options.scale_covariance ? best.chi_square * (1.0 + gsl_cdf_fdist_Pinv(prob, 1.0, n - k) / (n - k))
                                              : best.chi_square + gsl_cdf_chisq_Pinv(prob, 1.0));
  }
  std::vector<ProfileInterval> out;
  for (const auto& name : wanted) {
    const auto it = std::find_if(best.parameters.begin(), best.parameters.end(),
                                 [&](const ParameterEstimate& p) { return p.name == name; });
    if (it == best.parameters.end())
      throw FitError(law.name, fmt::format("profile intervals: law '{}' has no parameter '{}'", law.name, name));
    if (!it->vary)
      throw FitError(law.name, fmt::format("profile intervals: {} is not varied ({}): it has no interval", name,
                                           it->expr.empty() ? "fixed" : "given by '" + it->expr + "'"));
    ProfileInterval pi;
    pi.name = name;
    pi.value = it->value;
    // chi^2 with the parameter held at exp(u), the others started from the best fit.
    auto chi2_at = [&](double u) {
      FitOptions o = options;
      for (const auto& p : best.parameters) {
        if (p.name == name || !p.vary) continue;
        auto& set = o.parameters[p.name];
        if (p.value >= set.min && p.value <= set.max) set.value = p.value;
      }
      auto& held = o.parameters[name];
      held = ParameterSetting{};
      held.value = std::exp(u);
      held.vary = false;
      ++pi.fits;
      return fit_law(law, data, o).chi_square;
    };
    const double u0 = std::log(it->value);
    const double lo = it->min > 0.0 ? std::log(it->min) : -std::numeric_limits<double>::infinity();
    const double hi = std::isfinite(it->max) ? std::log(it->max) : std::numeric_limits<double>::infinity();
    const double se = it->std_error > 0.0 && it->identifiable ? it->std_error / it->value : 0.1;
    for (std::size_t l = 0; l < sigmas.size(); ++l) {
      ProfileLevel lv;
      lv.sigma = sigmas[l];
      lv.probability = gsl_sf_erf(sigmas[l] / std::sqrt(2.0));
      lv.chi_square = target[l];
      for (int dir : {-1, 1}) {
        const double limit = dir < 0 ? lo : hi;
        auto f = [&](double u) { return chi2_at(u) - target[l]; };
        double inner = u0, step = std::max(sigmas[l] * se, 1e-6), u = u0, fu = -1.0;
        bool found = false, cut = false;
        for (int i = 0; i < 60; ++i) {
          u = u0 + dir * step;
          if ((dir < 0 && u <= limit) || (dir > 0 && u >= limit)) u = limit, cut = true;
          if (std::abs(u - u0) > std::log(1e6)) break;
          fu = f(u);
          if (fu >= 0.0) {
            found = true;
            break;
          }
          if (cut) break;
          inner = u;
          step *= 2.0;
        }
        double end;
        if (found) end = std::exp(brent(f, inner, u));
        else if (cut) end = dir < 0 ? it->min : it->max;
        else end = dir < 0 ? 0.0 : std::numeric_limits<double>::infinity();
        (dir < 0 ? lv.lower : lv.upper) = end;
        (dir < 0 ? lv.lower_found : lv.upper_found) = found;
      }
      pi.levels.push_back(lv);
    }
    out.push_back(std::move(pi));
  }
  return out;
}

}  // namespace rheodda::fit
