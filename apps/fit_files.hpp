// The user's units of `rheodda fit` and the files it writes (fit_files.cpp): --json,
// --yaml (a law block for a scene, in the data's or a scene's units) and --plot.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rheodda/fit/fit.hpp"
#include "rheodda/units/units.hpp"

namespace rheodda::apps {

/// The user's unit names for the three dimensions of the laws' schemas.
struct Units {
  std::string text;  ///< as given, echoed in reports; empty if not given
  std::string stress = "stress", length = "length", time = "time";
  /// "stress*time/length" -> "MPa*h/mm" (rheodda::units spells it); "-" stays "-".
  std::string of(const std::string& dimension) const {
    return dimension == "-" ? dimension : units::unit_of(dimension, base());
  }
  units::Base base() const { return {.length = length, .force = "", .time = time, .stress = stress}; }
};

/// The units --yaml writes the law in: the data's, or a scene's (--scene-units, --scene).
struct YamlUnits {
  std::optional<units::Base> scene;  ///< none: the data's units
  std::string text;                  ///< "m, N, d" as the scene states them
};

/// gnuplot's terminal for --plot PATH (.png or .svg); throws std::invalid_argument otherwise.
std::string plot_terminal(const std::string& path);

/// --json: the data, every fit (parameters, errors, criteria, weights, what the data leave
/// undetermined) and the laws skipped, ranked by `rank_by`.
void write_json(const std::string& path, const fit::CreepData& d, const Units& u, const std::vector<fit::FitResult>& fits,
                const std::vector<std::string>& skipped, const std::string& rank_by);

/// --yaml: the law block of fit `r` for a scene, in the data's units or a scene's (`y`).
void write_yaml(const std::string& path, const fit::CreepData& d, const Units& u, const fit::FitResult& r,
                const YamlUnits& y);

/// --plot: the data, each fit's curve and its residuals, drawn by gnuplot into `path`.
void write_plot(const std::string& path, const std::string& terminal, const fit::CreepData& d, const Units& u,
                const std::vector<fit::FitResult>& fits);

}  // namespace rheodda::apps
