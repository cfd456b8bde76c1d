// The verdict of `rheodda fit --law all` (fit_verdict.hpp): the laws by the weight of
// evidence the data give them (fit::model_weights; Burnham & Anderson 2002), the
// parameters each leaves undetermined.
#include "fit_verdict.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "rheodda/laws/registry.hpp"

namespace rheodda::apps {

std::vector<double> ranking_weights(const std::vector<fit::FitResult>& ranked, bool bic) {
  std::vector<double> c;
  for (const auto& r : ranked) c.push_back(bic ? r.bic : r.aic);
  return fit::model_weights(c);
}

std::string fit_verdict(const std::vector<fit::FitResult>& ranked, bool bic) {
  const std::vector<double> w = ranking_weights(ranked, bic);
  const std::string crit = bic ? "BIC" : "AIC";
  const auto& best = ranked.front();
  auto delta = [&](const fit::FitResult& r) { return bic ? r.bic - best.bic : r.aic - best.aic; };
  std::vector<std::string> supported, less, none;
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    const double d = delta(ranked[i]);
    const std::string name = ranked[i].law;
    if (d <= fit::kSupportedDelta)
      supported.push_back(fmt::format("{} (weight {:.3g})", name, w[i]));
    else if (d <= fit::kUnsupportedDelta)
      less.push_back(fmt::format("{} (weight {:.3g}, {:.3g} times less than {})", name, w[i], w[0] / w[i], best.law));
    else
      none.push_back(name);
  }
  std::string out = fmt::format(
      "\nverdict: weights w = exp(-d{0}/2) / sum exp(-d{0}/2) on {0}{1} (Burnham & Anderson 2002, Model Selection "
      "and Multimodel Inference): supported within d{0} <= {2:g} of the best (evidence ratio <= {3:.3g}), not "
      "supported beyond d{0} > {4:g} (ratio > {5:.3g})\n",
      crit, bic ? "" : ", the Akaike weights", fit::kSupportedDelta, std::exp(0.5 * fit::kSupportedDelta),
      fit::kUnsupportedDelta, std::exp(0.5 * fit::kUnsupportedDelta));
  if (bic) {
    // The Akaike weights too (on AIC, which penalises a parameter less than BIC does at more
    // than 7 points): where the two criteria disagree, the laws' support is not settled.
    const std::vector<double> a = ranking_weights(ranked, false);
    std::vector<std::string> akaike;
    for (std::size_t i = 0; i < ranked.size(); ++i) akaike.push_back(fmt::format("{} {:.3g}", ranked[i].law, a[i]));
    out += fmt::format("  Akaike weights (on AIC): {}\n", fmt::join(akaike, ", "));
  }
  out += fmt::format("  the data support: {}\n", fmt::join(supported, ", "));
  if (!less.empty()) out += fmt::format("  they support less: {}\n", fmt::join(less, ", "));
  if (!none.empty())
    out += fmt::format("  they do not support: {} (more than {:.3g} times less than {})\n", fmt::join(none, ", "),
                       std::exp(0.5 * fit::kUnsupportedDelta), best.law);
  if (supported.size() > 1)
    out += fmt::format("  the data do not choose among the {} supported laws: a forecast with one of them leaves out "
                       "the uncertainty of the law's form (its band covers that law's parameters only)\n",
                       supported.size());
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    if (delta(ranked[i]) > fit::kUnsupportedDelta) continue;
    const std::vector<std::string> u = fit::unidentified_parameters(ranked[i]);
    if (u.empty()) continue;
    // What each value decides (laws::ParameterSpec::what_its_value_decides), by the law's declaration.
    std::string decides;
    for (const auto& p : laws::LawRegistry::builtin().get(ranked[i].law).parameters)
      if (std::find(u.begin(), u.end(), p.name) != u.end()) decides += "; " + p.what_its_value_decides();
    out += fmt::format(
        "  {}: the data do not determine {}: the value{} reported {} one of many the data allow, and a forecast "
        "with this law depends on that choice, not on the data{}{}\n",
        ranked[i].law, fmt::join(u, ", "), u.size() == 1 ? "" : "s", u.size() == 1 ? "is" : "are each", decides,
        i == 0 ? fmt::format("; --yaml writes it marked (unidentified: [{}]), and check and run warn where a scene "
                             "uses it",
                             fmt::join(u, ", "))
               : "");
  }
  return out;
}

}  // namespace rheodda::apps
