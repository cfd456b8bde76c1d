// What a forecast's band covers and what it does not (forecast.hpp, band_coverage;
// docs/guide/forecast.md, "What the band covers").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "rheodda/fit/fit.hpp"
#include "rheodda/forecast/forecast.hpp"
#include "rheodda/laws/registry.hpp"

namespace rheodda::forecast {

std::string band_coverage(const FittedLaw& fit, const Samples& drawn, const Unidentified& u) {
  std::vector<std::string> drawn_names;
  for (std::size_t i = 0; i < fit.names.size(); ++i)
    if (fit.identifiable[i]) drawn_names.push_back(fit.names[i]);
  std::string out = fmt::format(
      "what the band covers: the uncertainty of the parameters of law {} that the data determine ({}), drawn from "
      "the fit's covariance{}\n",
      fit.law, drawn_names.empty() ? std::string("none") : fmt::format("{}", fmt::join(drawn_names, ", ")),
      drawn.spread.empty() ? std::string()
                           : fmt::format(", and of {} drawn log-uniformly within a factor {:g} of the fit "
                                         "(--unidentified-spread: a range chosen by the user, not by the data)",
                                         fmt::join(drawn.spread, ", "), u.spread));
  out += "what it does not cover:\n";
  // The law's form: a forecast runs one law; the report's weights say which others the data support.
  const std::string crit = fit.rank_by == "aic" ? "AIC" : "BIC";
  std::string best_law = fit.law;
  double best = 0.0, self = 0.0;
  for (const auto& [law, w] : fit.weights) {
    if (w > best) {
      best = w;
      best_law = law;
    }
    if (law == fit.law) self = w;
  }
  std::vector<std::string> others;  // within kSupportedDelta of the best: exp(-Delta/2) >= exp(-kSupportedDelta/2)
  for (const auto& [law, w] : fit.weights)
    if (law != fit.law && w > 0.0 && -2.0 * std::log(w / best) <= fit::kSupportedDelta)
      others.push_back(fmt::format("{} (weight {:.3g})", law, w));
  if (fit.weights.size() <= 1)
    out += fmt::format("  the uncertainty of the law's form: the report fitted law {} only; whether another law fits "
                       "the data as well was not asked (rheodda fit --law all)\n",
                       fit.law);
  else if (best_law != fit.law)
    out += fmt::format("  the uncertainty of the law's form: every member runs {} (weight {:.3g} on {}), and the data "
                       "prefer {} (weight {:.3g}, {:.3g} times more; docs/guide/fitting.md, \"The verdict\"){}\n",
                       fit.law, self, crit, best_law, best, self > 0.0 ? best / self : INFINITY,
                       others.size() > 1 ? fmt::format("; supported: {}", fmt::join(others, ", ")) : std::string());
  else if (!others.empty())
    out += fmt::format("  the uncertainty of the law's form: the data support {} about as well as {} (weight {:.3g} "
                       "on {}; docs/guide/fitting.md, \"The verdict\"), and every member runs {}: forecast with each "
                       "supported law and compare\n",
                       fmt::join(others, ", "), fit.law, self, crit, fit.law);
  else
    out += fmt::format("  the uncertainty of the law's form: every member runs {} (weight {:.3g} on {}); of the "
                       "report's laws the data support no other, but laws it did not fit are not excluded\n",
                       fit.law, self, crit);
  const auto& specs = laws::LawRegistry::builtin().get(fit.law).parameters;
  for (const auto& name : drawn.held) {
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const auto& p) { return p.name == name; });
    const auto i = static_cast<std::size_t>(std::find(fit.names.begin(), fit.names.end(), name) - fit.names.begin());
    out += fmt::format("  the choice of {}, which the data do not determine: every member holds it at the fit's {:g}{}; "
                       "{}\n",
                       name, fit.values[i], fit.units[i].empty() ? "" : " " + fit.units[i],
                       spec == specs.end() ? std::string() : spec->what_its_value_decides());
  }
  for (const auto& name : drawn.spread)
    out += fmt::format("  the values of {} beyond the factor {:g} of --unidentified-spread: the data bound it no "
                       "tighter\n",
                       name, u.spread);
  out += "  the law's extrapolation beyond the stresses and duration of the tests (check and run warn with the law's "
         "tested_stress and tested_duration)\n";
  return out;
}

}  // namespace rheodda::forecast
