// The choice of a law among those fitted (fit.hpp, "The choice of a law"): model weights,
// the parameters a fit leaves undetermined, what the data cover.
#include <algorithm>
#include <cmath>

#include "rheodda/fit/fit.hpp"

namespace rheodda::fit {

std::vector<double> model_weights(const std::vector<double>& criterion) {
  // Burnham & Anderson 2002, ch. 2, "Akaike weights": w_i = exp(-Delta_i/2) / sum_r exp(-Delta_r/2).
  std::vector<double> w;
  if (criterion.empty()) return w;
  const double best = *std::min_element(criterion.begin(), criterion.end());
  double sum = 0.0;
  for (double c : criterion) {
    w.push_back(std::exp(-0.5 * (c - best)));
    sum += w.back();
  }
  for (double& x : w) x /= sum;
  return w;
}

std::vector<std::string> unidentified_parameters(const FitResult& r) {
  std::vector<std::string> out;
  for (const auto& p : r.parameters)
    if (p.vary && p.at_bound.empty() && p.expr.empty() && !p.identifiable) out.push_back(p.name);
  return out;
}

TestedRange tested_range(const CreepData& data) {
  TestedRange r;
  bool any = false;
  for (const auto& s : data.stages) {
    const double f = std::abs(s.stress);
    if (f == 0.0) continue;  // an unloading: no stress the law was tested at
    r.stress_min = any ? std::min(r.stress_min, f) : f;
    r.stress_max = any ? std::max(r.stress_max, f) : f;
    any = true;
  }
  if (!data.t.empty() && !data.stages.empty()) r.duration = data.t.back() - data.stages.front().t;
  return r;
}

}  // namespace rheodda::fit
