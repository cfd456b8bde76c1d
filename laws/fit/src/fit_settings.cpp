// The user's settings of a fit checked and mapped for GSL (fit_settings.hpp).
#include "fit_settings.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rheodda::fit::detail {

namespace {

std::string names_of(const laws::LawInfo& info) {
  std::string out;
  for (const auto& p : info.parameters) out += (out.empty() ? "" : ", ") + p.name;
  return out;
}

// The parameters given by expressions (ParameterSetting::expr), parsed and put
// in an order that evaluates each after the derived parameters it uses; a
// cycle is refused.
void add_expressions(const laws::LawInfo& info, const Constraints& c, Mapping& m) {
  const std::size_t np = info.parameters.size();
  std::vector<std::string> names;
  for (const auto& p : info.parameters) names.push_back(p.name);
  std::vector<std::optional<Expression>> parsed(np);
  for (std::size_t k = 0; k < np; ++k) {
    if (c.expr[k].empty()) continue;
    try {
      parsed[k] = Expression::parse(c.expr[k], names);
    } catch (const std::invalid_argument& e) {
      throw FitError(info.name, fmt::format("law '{}': {}: {}", info.name, names[k], e.what()));
    }
    if (parsed[k]->uses().empty())
      throw FitError(info.name, fmt::format("law '{}': {}: the expression '{}' names no parameter: to hold {} "
                                            "at a value, fix it (vary = false, --fix)",
                                            info.name, names[k], c.expr[k], names[k]));
  }
  std::vector<int> state(np, 0);  // 0 not placed, 1 being placed, 2 placed
  std::vector<std::size_t> path;
  auto place = [&](auto&& self, std::size_t k) -> void {
    if (state[k] == 2 || !parsed[k]) return;
    if (state[k] == 1) {
      std::string cycle;
      for (std::size_t i : path) cycle += names[i] + " -> ";
      throw FitError(info.name, fmt::format("law '{}': the expressions refer to each other in a cycle: {}{}",
                                            info.name, cycle, names[k]));
    }
    state[k] = 1;
    path.push_back(k);
    for (std::size_t u : parsed[k]->uses()) self(self, u);
    path.pop_back();
    state[k] = 2;
    m.derived.push_back({k, *parsed[k]});
  };
  for (std::size_t k = 0; k < np; ++k) place(place, k);
}

}  // namespace

Constraints read_settings(const laws::LawInfo& info, const CreepData& data, const FitOptions& options) {
  const std::size_t np = info.parameters.size();
  Constraints c;
  c.fixed.assign(np, 0);
  c.expr.assign(np, "");
  c.initial.assign(np, std::nullopt);
  c.min.assign(np, 0.0);
  c.max.assign(np, std::numeric_limits<double>::infinity());
  for (const auto& [name, set] : options.parameters) {
    std::size_t k = np;
    for (std::size_t i = 0; i < np; ++i)
      if (info.parameters[i].name == name) k = i;
    if (k == np)
      throw FitError(info.name, fmt::format("law '{}' has no parameter '{}' (its parameters: {})", info.name,
                                            name, names_of(info)));
    if (!set.expr.empty()) {
      if (set.value || !set.vary || set.min != 0.0 || set.max != std::numeric_limits<double>::infinity())
        throw FitError(info.name, fmt::format("law '{}': {} is given by the expression '{}': a value, vary = "
                                              "false or bounds on it are not supported (bound the parameters "
                                              "it is made of)",
                                              info.name, name, set.expr));
      c.expr[k] = set.expr;
      c.active = true;
      continue;
    }
    if (std::isnan(set.min) || set.min < 0.0 || std::isinf(set.min))
      throw FitError(info.name, fmt::format("law '{}': {}: min {:g} is not a finite number >= 0 (fits work on "
                                            "positive parameters)",
                                            info.name, name, set.min));
    if (std::isnan(set.max) || !(set.max > set.min))
      throw FitError(info.name, fmt::format("law '{}': {}: the bounds [{:g}, {:g}] are empty: max must be above "
                                            "min",
                                            info.name, name, set.min, set.max));
    if (set.value) {
      const double v = *set.value;
      if (!std::isfinite(v) || v <= 0.0)
        throw FitError(info.name, fmt::format("law '{}': {}: value {:g} is not a finite positive number (fits "
                                              "work on positive parameters)",
                                              info.name, name, v));
      if (v < set.min || v > set.max)
        throw FitError(info.name, fmt::format("law '{}': {}: value {:g} is outside its bounds [{:g}, {:g}]",
                                              info.name, name, v, set.min, set.max));
    }
    if (!set.vary && !set.value)
      throw FitError(info.name, fmt::format("law '{}': {} is fixed (vary = false) but has no value", info.name,
                                            name));
    c.fixed[k] = !set.vary;
    c.initial[k] = set.value;
    c.min[k] = set.min;
    c.max[k] = set.max;
    c.active = c.active || !set.is_default();
  }
  if (!data.sigma.empty()) {
    if (data.sigma.size() != data.t.size())
      throw FitError(info.name, fmt::format("{}: {} sigma values for {} points", data.source, data.sigma.size(),
                                            data.t.size()));
    for (std::size_t j = 0; j < data.sigma.size(); ++j) {
      if (!(data.sigma[j] > 0.0) || !std::isfinite(data.sigma[j]))
        throw FitError(info.name, fmt::format("{}: sigma {:g} of point {} is not a finite positive number",
                                              data.source, data.sigma[j], j + 1));
      c.weight.push_back(1.0 / data.sigma[j]);
    }
    c.active = true;
  } else if (!options.scale_covariance) {
    throw FitError(info.name, "absolute standard errors (--absolute-sigma, scale_covariance = false) need the "
                              "measurement sigma of each point (--sigma-column, sigma=)");
  }
  Mapping m;
  m.x.assign(np, 0.0);
  add_expressions(info, c, m);
  for (std::size_t k = 0; k < np; ++k) {
    if (!c.expr[k].empty()) continue;
    if (c.fixed[k]) {
      m.x[k] = std::log(*c.initial[k]);
      continue;
    }
    m.free.push_back(k);
    m.lo.push_back(c.min[k] > 0.0 ? std::log(c.min[k]) : -std::numeric_limits<double>::infinity());
    m.hi.push_back(std::isfinite(c.max[k]) ? std::log(c.max[k]) : std::numeric_limits<double>::infinity());
  }
  c.varying = m.free.size();
  if (c.varying == 0)
    throw FitError(info.name, fmt::format("law '{}': every parameter is fixed (vary = false): nothing to fit",
                                          info.name));
  if (c.active) c.mapping = std::move(m);
  return c;
}

}  // namespace rheodda::fit::detail
