// The verdict of `rheodda fit --law all` (docs/guide/fitting.md, "The verdict"): which laws
// the data support and by how much, which parameters they leave undetermined and what that
// means.
#pragma once

#include <string>
#include <vector>

#include "rheodda/fit/fit.hpp"

namespace rheodda::apps {

/// The weight of each law of `ranked` (best first) on the ranking criterion (BIC, or AIC:
/// the Akaike weights), fit::model_weights.
std::vector<double> ranking_weights(const std::vector<fit::FitResult>& ranked, bool bic);

/// The verdict paragraph, ending in a newline.
std::string fit_verdict(const std::vector<fit::FitResult>& ranked, bool bic);

}  // namespace rheodda::apps
