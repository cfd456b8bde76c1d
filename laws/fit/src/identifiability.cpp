// Identifiability of a fit's parameters (identifiability.hpp; docs/guide/fitting.md, "Identifiability").
#include "identifiability.hpp"

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_vector.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>

#include "gsl_solver.hpp"

namespace rheodda::fit::detail {

// The combinations that a series law's curve can depend on when single
// parameters drop out (docs/guide/fitting.md, "Identifiability"):
//   (L - Fs)/eta3 for each stress level L > Fs [length/time]: the Bingham rate under L
//     (d/dln eta3 = -q, d/dln Fs = -Fs/eta3);
//   1/E1 + 1/E (spring and a fast Kelvin element merge into one jump), 1/E2 + 1/E3
//     (two Kelvin elements with close retardation times) [length/stress] (d/dln E = -1/E);
//   1/eta1 + 1/eta (a slow Kelvin element acting as a dashpot) [length/(stress*time)];
//   eta/E, the retardation time [time] (d/dln eta = q, d/dln E = -q).
std::vector<Candidate> combination_candidates(const SeriesStructure& s,
                                              const std::vector<ParameterEstimate>& p,
                                              const CreepData& data) {
  const std::size_t np = p.size();
  std::vector<Candidate> out;
  std::vector<const Element*> kelvins;
  const Element* dashpot = nullptr;
  for (const auto& el : s.elements) {
    if (el.kind == Kind::kelvin) kelvins.push_back(&el);
    if (el.kind == Kind::dashpot) dashpot = &el;
    if (el.kind == Kind::bingham) {
      const double eta = p[el.eta].value, fs = p[el.threshold].value;
      std::vector<double> levels;
      for (const auto& st : data.stages)
        if (std::abs(st.stress) > fs) levels.push_back(std::abs(st.stress));
      std::sort(levels.begin(), levels.end());
      levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
      for (double level : levels) {
        Candidate c;
        c.expression = fmt::format("({:g} - {})/{}", level, p[el.threshold].name, p[el.eta].name);
        c.unit = "length/time";
        c.value = (level - fs) / eta;
        c.grad.assign(np, 0.0);
        c.grad[el.eta] = -c.value;
        c.grad[el.threshold] = -fs / eta;
        out.push_back(std::move(c));
      }
    }
  }
  auto inverse_sum = [&](const std::vector<int>& idx, const char* unit) {
    Candidate c;
    c.unit = unit;
    c.grad.assign(np, 0.0);
    for (int k : idx) {
      c.expression += (c.expression.empty() ? "1/" : " + 1/") + p[k].name;
      c.value += 1.0 / p[k].value;
      c.grad[k] = -1.0 / p[k].value;
    }
    out.push_back(std::move(c));
  };
  for (const auto* el : kelvins) {
    if (s.spring >= 0) inverse_sum({s.spring, el->E}, "length/stress");
    if (dashpot) inverse_sum({dashpot->eta, el->eta}, "length/(stress*time)");
  }
  if (kelvins.size() == 2) {
    inverse_sum({kelvins[0]->E, kelvins[1]->E}, "length/stress");
    if (s.spring >= 0) inverse_sum({s.spring, kelvins[0]->E, kelvins[1]->E}, "length/stress");
  }
  for (const auto* el : kelvins) {
    Candidate c;
    c.expression = p[el->eta].name + "/" + p[el->E].name;
    c.unit = "time";
    c.value = p[el->eta].value / p[el->E].value;
    c.grad.assign(np, 0.0);
    c.grad[el->eta] = c.value;
    c.grad[el->E] = -c.value;
    out.push_back(std::move(c));
  }
  return out;
}

namespace {

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

}  // namespace

// Singular value decomposition of the Jacobian J of the scaled residuals with
// respect to the log parameters (GSL, one-sided Jacobi after QR for n >> p):
// J = U S V^T. With s the residual standard deviation, the standard error of
// ln p along direction v_i is s/S_i. A direction with S_i below
// null_tolerance * S_max is one the curve does not depend on: every parameter
// with a weight |v_ki| >= 1e-3 in it is not identifiable. A direction with
// s/S_i > relative_error_limit (ln p free by more than that) flags every
// parameter with a weight >= 0.1. The covariance of ln p is
// C = sum over the other directions of v_i v_i^T (s/S_i)^2: the pseudo-inverse
// of J^T J / s^2 (Golub & Van Loan, Matrix Computations, 4th ed., sec. 5.5),
// so no standard error is conditioned on a dropped partner. J is overwritten.
void identify(FitResult& res, gsl_matrix* jac, double s, const std::vector<Candidate>& candidates,
              const FitOptions& options, std::vector<double>& cov) {
  const std::size_t np = res.parameters.size();
  std::unique_ptr<gsl_matrix, GslFree> V(gsl_matrix_alloc(np, np)), X(gsl_matrix_alloc(np, np));
  std::unique_ptr<gsl_vector, GslFree> S(gsl_vector_alloc(np)), work(gsl_vector_alloc(np));
  for (std::size_t i = 0; i < jac->size1 * jac->tda; ++i)
    if (!std::isfinite(jac->data[i])) jac->data[i] = 0.0;
  gsl_linalg_SV_decomp_mod(jac, X.get(), V.get(), S.get(), work.get());
  double smax = 0.0;
  for (std::size_t i = 0; i < np; ++i) smax = std::max(smax, gsl_vector_get(S.get(), i));
  std::vector<char> null(np), weak(np);
  for (std::size_t i = 0; i < np; ++i) {
    const double si = gsl_vector_get(S.get(), i);
    null[i] = !(si > options.null_tolerance * smax);
    weak[i] = !null[i] && s > 0 && s / si > options.relative_error_limit;
    res.singular_values.push_back(s > 0 ? si / s : std::numeric_limits<double>::infinity());
  }
  cov.assign(np * np, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    if (null[i]) continue;
    const double w = s / gsl_vector_get(S.get(), i);
    for (std::size_t a = 0; a < np; ++a)
      for (std::size_t b = 0; b < np; ++b)
        cov[a * np + b] += gsl_matrix_get(V.get(), a, i) * gsl_matrix_get(V.get(), b, i) * w * w;
  }
  // Groups of flagged parameters: those sharing a direction the data do not fix.
  std::vector<int> group(np, -1);
  struct Group {
    std::vector<std::size_t> params;
    bool null = false;
    double worst = 0.0;  // largest s/S_i among its weak directions
  };
  std::vector<Group> groups;
  for (std::size_t i = 0; i < np; ++i) {
    if (!null[i] && !weak[i]) continue;
    std::vector<std::size_t> members;
    for (std::size_t k = 0; k < np; ++k)
      if (std::abs(gsl_matrix_get(V.get(), k, i)) >= (null[i] ? 1e-3 : 0.1)) members.push_back(k);
    int g = -1;
    for (std::size_t k : members)
      if (group[k] >= 0) g = group[k];
    if (g < 0) {
      g = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    for (std::size_t k : members) {
      if (group[k] >= 0 && group[k] != g) {  // merge the other group into g
        const int other = group[k];
        for (std::size_t m : groups[other].params) {
          group[m] = g;
          groups[g].params.push_back(m);
        }
        groups[g].null = groups[g].null || groups[other].null;
        groups[g].worst = std::max(groups[g].worst, groups[other].worst);
        groups[other].params.clear();
      } else if (group[k] < 0) {
        group[k] = g;
        groups[g].params.push_back(k);
      }
    }
    groups[g].null = groups[g].null || null[i];
    if (weak[i]) groups[g].worst = std::max(groups[g].worst, s / gsl_vector_get(S.get(), i));
  }
  for (std::size_t k = 0; k < np; ++k) {
    auto& e = res.parameters[k];
    e.identifiable = group[k] < 0;
    const double var = cov[k * np + k];
    e.std_error = e.identifiable ? e.value * std::sqrt(var) : 0.0;  // delta method: dp = p dln p
  }
  // Combinations the data fix: no component along a direction the curve does
  // not depend on, relative standard error within the limit, and a part that
  // is not identifiable on its own.
  for (const auto& c : candidates) {
    double norm = 0.0;
    for (double g : c.grad) norm += g * g;
    norm = std::sqrt(norm);
    if (!(norm > 0) || !(c.value > 0)) continue;
    bool involves = false;
    for (std::size_t k = 0; k < np; ++k)
      involves = involves || (group[k] >= 0 && std::abs(c.grad[k]) >= 0.01 * norm);
    if (!involves) continue;
    bool fixed = true;
    for (std::size_t i = 0; i < np && fixed; ++i) {
      if (!null[i]) continue;
      double along = 0.0;
      for (std::size_t k = 0; k < np; ++k) along += gsl_matrix_get(V.get(), k, i) * c.grad[k];
      fixed = std::abs(along) <= 1e-4 * norm;
    }
    double var = 0.0;
    for (std::size_t a = 0; a < np; ++a)
      for (std::size_t b = 0; b < np; ++b) var += c.grad[a] * cov[a * np + b] * c.grad[b];
    const double se = std::sqrt(std::max(var, 0.0));
    if (!fixed || !(se <= options.relative_error_limit * c.value)) continue;
    FixedCombination f;
    f.expression = c.expression;
    f.unit = c.unit;
    f.value = c.value;
    f.std_error = se;
    for (std::size_t k = 0; k < np; ++k)
      if (c.grad[k] != 0.0) f.parameters.push_back(res.parameters[k].name);
    res.combinations.push_back(std::move(f));
  }
  for (const auto& g : groups) {
    if (g.params.empty()) continue;
    std::vector<std::string> names;
    for (std::size_t k : g.params) names.push_back(res.parameters[k].name);
    const bool one = names.size() == 1;
    std::string reason;
    if (g.null && one)
      reason = "the curve does not depend on it at the fitted values (its element adds nothing "
               "measurable, or acts as part of another)";
    else if (g.null)
      reason = fmt::format("the curve depends on {} only through a combination of them", join_names(names));
    else
      reason = fmt::format("the data leave {} free by more than a factor e (standard error of the "
                           "log {:.3g} along a direction of the parameters)",
                           one ? "it" : "them together", g.worst);
    for (std::size_t k : g.params) res.parameters[k].reason = reason;
    std::string fixed;
    for (const auto& f : res.combinations) {
      bool shares = false;
      for (const auto& n : f.parameters)
        shares = shares || std::find(names.begin(), names.end(), n) != names.end();
      if (shares)
        fixed += fmt::format("{}{} = {:.4g} +- {:.2g}", fixed.empty() ? "; the data fix " : ", ",
                             f.expression, f.value, f.std_error);
    }
    res.warnings.push_back(fmt::format("{} {} not identifiable: {}{}; no standard error is given for {}",
                                       join_names(names), one ? "is" : "are", reason, fixed,
                                       one ? "it" : "them"));
  }
}

}  // namespace rheodda::fit::detail
