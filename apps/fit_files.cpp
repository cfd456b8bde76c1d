// The files `rheodda fit` writes (fit_files.hpp): --json, --yaml and --plot.
#include "fit_files.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "commands.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/plot.hpp"

namespace rheodda::apps {

using fit::CreepData;
using fit::FitResult;

std::string plot_terminal(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  // noenhanced: names are drawn as written (an underscore in a file name is no subscript).
  if (ext == ".png") return "pngcairo size 960,720 noenhanced font 'Sans,10'";
  if (ext == ".svg") return "svg size 960,720 noenhanced font 'Sans,10'";
  throw std::invalid_argument(
      fmt::format("--plot {}: the file name must end in .png or .svg", path));
}

namespace {

std::ofstream open_output(const std::string& path, const char* flag) {
  std::ofstream out(path);
  if (!out) throw std::invalid_argument(fmt::format("{} {}: cannot open the file for writing", flag, path));
  return out;
}

}  // namespace

void write_json(const std::string& path, const CreepData& d, const Units& u,
                const std::vector<FitResult>& fits, const std::vector<std::string>& skipped,
                const std::string& rank_by) {
  using nlohmann::json;
  json stages = json::array();
  for (const auto& s : d.stages) stages.push_back({{"t", s.t}, {"stress", s.stress}, {"points", s.count}});
  json out;
  out["data"] = {{"file", d.source},
                 {"points", d.t.size()},
                 {"time_column", d.time_column},
                 {"displacement_column", d.displacement_column},
                 {"stress_column", d.stress_column},
                 {"sigma_column", d.sigma_column},
                 {"stages", stages}};
  out["units"] = {{"text", u.text}, {"stress", u.stress}, {"length", u.length}, {"time", u.time}};
  json arr = json::array();
  for (const auto& r : fits) {
    json params = json::array();
    for (const auto& p : r.parameters)
      params.push_back({{"name", p.name},
                        {"value", p.value},
                        // A held parameter (fixed, or on a bound) has no spread: 0, so that `rheodda
                        // forecast` holds it too; null where the data cannot tell it.
                        {"std_error", p.identifiable ? json(p.std_error) : json(nullptr)},
                        {"unit", u.of(p.unit)},
                        {"identifiable", p.identifiable},
                        {"reason", p.reason},
                        {"vary", p.vary},
                        {"expr", p.expr},
                        {"at_bound", p.at_bound},
                        {"min", p.min},
                        {"max", std::isfinite(p.max) ? json(p.max) : json(nullptr)}});
    json combos = json::array();
    for (const auto& c : r.combinations)
      combos.push_back({{"expression", c.expression},
                        {"value", c.value},
                        {"std_error", c.std_error},
                        {"unit", u.of(c.unit)},
                        {"parameters", c.parameters}});
    auto finite_or_null = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
    // A held parameter is a constant: correlation 0 with the others (1 with itself).
    auto held = [&](std::size_t i) { return !r.parameters[i].vary || !r.parameters[i].at_bound.empty(); };
    json corr = json::array();
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      json row = json::array();
      for (std::size_t j = 0; j < r.parameters.size(); ++j)
        row.push_back(held(i) || held(j) ? json(i == j ? 1.0 : 0.0) : finite_or_null(r.correlation_at(i, j)));
      corr.push_back(row);
    }
    arr.push_back({{"law", r.law},
                   {"parameters", params},
                   {"correlation", corr},
                   {"points", r.points},
                   {"rss", r.rss},
                   {"chi_square", r.chi_square},
                   {"reduced_chi_square", r.reduced_chi_square},
                   {"varying", r.varying},
                   {"weighted", r.weighted},
                   {"scale_covariance", r.scale_covariance},
                   {"start_minima", r.start_minima},
                   {"r2", finite_or_null(r.r2)},
                   {"rmse", r.rmse},
                   {"aic", r.aic},
                   {"bic", r.bic},
                   {"iterations", r.iterations},
                   {"starts", r.starts},
                   {"starts_agreeing", r.starts_agreeing},
                   {"structured_starts", r.structured_starts},
                   {"minimum_certain", r.minimum_certain},
                   {"minimum_note", r.minimum_note},
                   {"combinations", combos},
                   {"converged", r.converged},
                   {"optimality", r.optimality},
                   {"warnings", r.warnings}});
  }
  {
    // The weights of evidence (fit::model_weights: Akaike weights on AIC) and what each fit leaves undetermined.
    std::vector<double> aic, bic;
    for (const auto& r : fits) {
      aic.push_back(r.aic);
      bic.push_back(r.bic);
    }
    const auto wa = fit::model_weights(aic), wb = fit::model_weights(bic);
    for (std::size_t i = 0; i < fits.size(); ++i) {
      arr[i]["akaike_weight"] = wa[i];
      arr[i]["bic_weight"] = wb[i];
      arr[i]["unidentified"] = fit::unidentified_parameters(fits[i]);
    }
    const fit::TestedRange tested = fit::tested_range(d);
    out["tested_stress"] = {tested.stress_min, tested.stress_max};
    out["tested_duration"] = tested.duration;
  }
  out["fits"] = arr;
  out["rank_by"] = rank_by;
  out["best"] = fits.front().law;
  out["skipped"] = skipped;
  auto f = open_output(path, "--json");
  f << out.dump(2) << '\n';
}

void write_yaml(const std::string& path, const CreepData& d, const Units& u, const FitResult& r, const YamlUnits& y) {
  auto f = open_output(path, "--yaml");
  f << fmt::format("# rheodda fit: law {} fitted to {} ({} points, R^2 {}){}\n", r.law, d.source,
                   r.points, r.r2_defined() ? fmt::format("{:.6f}", r.r2) : "undefined",
                   u.text.empty() ? "" : fmt::format("; units {}", u.text));
  if (y.scene)
    f << fmt::format("# in the scene's units {} (length, force, time), converted from the data's {}\n", y.text, u.text);
  f << "# paste under a joint set of a scene; the comments give the standard errors\n";
  if (!r.minimum_certain) f << fmt::format("# warning: the minimum is not certain: {}\n", r.minimum_note);
  for (const auto& c : r.combinations)
    f << fmt::format("# fixed by the data: {} = {:.7g} +- {:.3g} {}\n", c.expression, c.value,
                     c.std_error, u.of(c.unit));
  // What the fit says of the law, in keys the scene loader reads (docs/reference/scene-format.md, "law").
  const fit::TestedRange tested = fit::tested_range(d);
  const std::vector<std::string> unidentified = fit::unidentified_parameters(r);
  if (!unidentified.empty())
    f << fmt::format("# the data do not determine {}: the value{} below {} one of many they allow (unidentified)\n",
                     fmt::join(unidentified, ", "), unidentified.size() == 1 ? "" : "s",
                     unidentified.size() == 1 ? "is" : "are");
  if (y.scene)
    f << "# tested_stress and tested_duration: the stresses and duration of the data, in the scene's units\n";
  else
    f << fmt::format("# tested_stress and tested_duration: the stresses and duration of the data{}; the scene's "
                     "units must be the data's (or write it with --scene-units)\n",
                     u.text.empty() ? "" : fmt::format(" [{}], [{}]", u.stress, u.time));
  f << "law:\n";
  f << fmt::format("  name: {}\n", r.law);
  for (const auto& p : r.parameters) {
    // In the scene's units: the value and its error times the factor UDUNITS-2 gives.
    const std::string unit = !y.scene ? u.of(p.unit) : p.unit == "-" ? p.unit : units::unit_of(p.unit, *y.scene);
    const double factor = !y.scene || p.unit == "-" ? 1.0 : units::convert(1.0, u.of(p.unit), unit);
    f << fmt::format("  {}: {:.7g}   # {} {}{}\n", p.name, p.value * factor,
                     !p.expr.empty()        ? "= " + p.expr
                     : !p.vary              ? std::string("fixed")
                     : !p.at_bound.empty()  ? "at its bound " + p.at_bound
                     : p.identifiable       ? fmt::format("+- {:.3g}", p.std_error * factor)
                                            : std::string("+- (not identifiable)"),
                     unit, y.scene ? fmt::format(" (fitted {:.7g} {})", p.value, u.of(p.unit)) : "");
  }
  // The tested range in the units the law is written in (the data's, or the scene's).
  auto written = [&](double v, const std::string& dimension) {
    return y.scene ? units::convert(v, u.of(dimension), units::unit_of(dimension, *y.scene)) : v;
  };
  if (!unidentified.empty()) f << fmt::format("  unidentified: [{}]\n", fmt::join(unidentified, ", "));
  f << fmt::format("  tested_stress: [{:.7g}, {:.7g}]\n", written(tested.stress_min, "stress"),
                   written(tested.stress_max, "stress"));
  f << fmt::format("  tested_duration: {:.7g}\n", written(tested.duration, "time"));
}

void write_plot(const std::string& path, const std::string& terminal, const CreepData& d,
                const Units& u, const std::vector<FitResult>& fits) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / fmt::format("rheodda-fit-{}", ::getpid());
  fs::create_directories(dir);
  // Data and residuals of each law at the data points.
  {
    std::ofstream f(dir / "data.csv");
    for (std::size_t j = 0; j < d.t.size(); ++j) {
      f << fmt::format("{:.10g},{:.10g}", d.t[j], d.displacement[j]);
      for (const auto& r : fits) f << fmt::format(",{:.10g}", d.displacement[j] - r.fitted[j]);
      f << '\n';
    }
  }
  // Fitted curves on a fine grid, with the value just before each stage start
  // so the instantaneous jumps are drawn vertical.
  {
    std::vector<double> grid;
    const double t0 = d.stages.front().t, t1 = d.t.back();
    for (int i = 0; i <= 1000; ++i) grid.push_back(t0 + (t1 - t0) * i / 1000.0);
    for (std::size_t i = 1; i < d.stages.size(); ++i) {
      grid.push_back(d.stages[i].t);
      grid.push_back(std::nextafter(d.stages[i].t, -1.0));
    }
    std::sort(grid.begin(), grid.end());
    std::vector<std::vector<double>> curves;
    for (const auto& r : fits) {
      const auto law = laws::LawRegistry::builtin().create(r.law, r.values());
      curves.push_back(fit::predict(*law, d.history, grid));
    }
    std::ofstream f(dir / "curve.csv");
    for (std::size_t i = 0; i < grid.size(); ++i) {
      f << fmt::format("{:.12g}", grid[i]);
      for (const auto& c : curves) f << fmt::format(",{:.10g}", c[i]);
      f << '\n';
    }
  }
  auto quote = [](const std::string& s) {
    std::string q;
    for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
    return "'" + q + "'";
  };
  std::string top, bottom;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    // Ten colours, then dashed (scene::curve_style): every law of --law all told apart.
    const scene::CurveStyle style = scene::curve_style(i);
    top += fmt::format(", {} using 1:{} with lines lw 2 {} title {}", quote((dir / "curve.csv").string()), i + 2,
                       style.line(), quote(fits[i].law));
    bottom += fmt::format("{}{} using 1:{} with points pt {} ps 0.35 lc rgb '{}' title {}", i ? ", " : "",
                          quote((dir / "data.csv").string()), i + 3, style.point, style.colour, quote(fits[i].law));
  }
  std::string script = fmt::format(
      "set terminal {}\nset output {}\nset datafile separator ','\n"
      "set multiplot\nset lmargin 12\nset rmargin 24\nset grid\n"
      "set key outside right top Left reverse\n"
      "set origin 0,0.33\nset size 1,0.67\n"
      "set title {}\nset ylabel 'shear displacement [{}]'\nset format x ''\n"
      "plot {} using 1:2 with points pt 6 ps 0.5 lc rgb 'black' title 'data'{}\n"
      "set origin 0,0\nset size 1,0.35\nunset title\nset format x '%g'\n"
      "set xlabel 'time [{}]'\nset ylabel 'residual [{}]'\n"
      "plot {}, 0 with lines lc rgb 'gray' notitle\nunset multiplot\n",
      terminal, quote(path),
      quote(fmt::format("{}: {} fit{}", fs::path(d.source).filename().string(),
                        fits.size() == 1 ? fits.front().law : "law",
                        fits.size() == 1 ? "" : "s by rank")),
      u.length, quote((dir / "data.csv").string()), top, u.time, u.length, bottom);
  {
    std::ofstream f(dir / "plot.gp");
    f << script;
  }
  // The pictures' one gnuplot runner (scene::run_gnuplot): gnuplot missing or failing is
  // reported with its messages, and exit 1.
  std::string failed;
  try {
    scene::run_gnuplot((dir / "plot.gp").string());
  } catch (const std::runtime_error& e) {
    failed = e.what();
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (!failed.empty()) {
    fmt::print(stderr, "rheodda: error: --plot {}: {}\n", path, failed);
    throw CLI::RuntimeError(1);
  }
}

}  // namespace rheodda::apps
