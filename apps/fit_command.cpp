// `rheodda fit`: fit rheology laws to a laboratory creep curve (docs/guide/fitting.md).
// Sample runs:
//   rheodda fit examples/creep-data/table1-row1.csv --law burgers --stress 0.232 --units "MPa, mm, h"
//   rheodda fit examples/creep-data/table1-row1.csv --law all --stress 0.232 --units "MPa, mm, h"
//       --json fit.json --yaml law.yaml --plot fit.png
//   rheodda fit steps.csv --law burgers --stress-column tau
//   rheodda fit table1-row1.csv --law burgers --stress 0.232 --fix E1=26.87 --bounds eta2=100:1e4
//       --initial E2=150 --sigma-column sigma --absolute-sigma
//   rheodda fit table1-row1.csv --law burgers --stress 0.232 --expr "eta2=12*E2" --max-iterations 5000
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fit_files.hpp"
#include "fit_verdict.hpp"
#include "rheodda/fit/fit.hpp"
#include "rheodda/laws/registry.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/progress.hpp"
#include "rheodda/units/units.hpp"

namespace rheodda::apps {
namespace {

using namespace rheodda::laws;
using rheodda::fit::CreepData;
using rheodda::fit::FitResult;

struct FitArgs {
  std::string data;
  std::string law;
  std::string stress, stress_column;
  std::string time_column = "t", displacement_column = "displacement";
  std::string units;
  std::string scene_units, scene_file;  // --scene-units, --scene: the units --yaml writes the law in
  std::string rank_by = "bic";
  int restarts = 4;
  int max_iterations = 500;
  std::string json, yaml, plot;
  // Parameter settings (fit::ParameterSetting), each NAME=...
  std::vector<std::string> fix, initial, bounds, expr;
  std::string sigma_column;
  bool absolute_sigma = false;
  bool quiet = false;
};

/// Three unit labels "A, B, C" of `option` (as given), trimmed; refused unless three non-empty.
std::vector<std::string> three_labels(const std::string& text, const char* option, const char* what) {
  std::vector<std::string> items;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = text.find(',', pos);
    std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    items.push_back(item);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  if (items.size() != 3 || items[0].empty() || items[1].empty() || items[2].empty())
    throw std::invalid_argument(fmt::format("{} '{}': expected three units {}", option, text, what));
  return items;
}


Units parse_units(const std::string& text) {
  Units u;
  if (text.empty()) return u;
  u.text = text;
  const auto items = three_labels(text, "--units", "'STRESS, LENGTH, TIME', e.g. \"MPa, mm, h\"");
  u.stress = items[0];
  u.length = items[1];
  u.time = items[2];
  return u;
}


YamlUnits yaml_units(const std::string& scene_units, const std::string& scene_file, const Units& data,
                     const std::string& yaml) {
  YamlUnits y;
  if (scene_units.empty() && scene_file.empty()) return y;
  if (yaml.empty())
    throw std::invalid_argument(fmt::format("{} gives the units of the --yaml law: give --yaml FILE",
                                            scene_units.empty() ? "--scene" : "--scene-units"));
  if (data.text.empty())
    throw std::invalid_argument(fmt::format("{} converts the law from the data's units: give them with --units "
                                            "\"STRESS, LENGTH, TIME\", e.g. \"MPa, mm, h\"",
                                            scene_units.empty() ? "--scene" : "--scene-units"));
  if (!scene_units.empty()) {
    const auto items = three_labels(scene_units, "--scene-units", "'LENGTH, FORCE, TIME', e.g. \"m, N, d\"");
    y.scene = units::Base{.length = items[0], .force = items[1], .time = items[2]};
  } else {
    const scene::Units u = scene::load_scene(scene_file).units;
    y.scene = units::Base{.length = u.length, .force = u.force, .time = u.time};
  }
  y.text = fmt::format("{}, {}, {}", y.scene->length, y.scene->force, y.scene->time);
  // Every label a unit UDUNITS-2 knows, before the fit runs.
  const std::string from = scene_units.empty() ? "--scene " + scene_file : "--scene-units";
  for (const auto& [option, label] : {std::pair{from, y.scene->length}, {from, y.scene->force}, {from, y.scene->time},
                                      {std::string("--units"), data.stress}, {std::string("--units"), data.length},
                                      {std::string("--units"), data.time}})
    if (!units::known(label))
      throw std::invalid_argument(fmt::format("{}: '{}' is not a unit UDUNITS-2 knows (m, mm, N, kN, MPa, s, h, d, ...), "
                                              "so the law cannot be converted",
                                              option, label));
  return y;
}

// A number of an option's text; `what` names it in the message.
double parse_number(const std::string& text, const std::string& what) {
  double v = 0.0;
  const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || p != text.data() + text.size())
    throw std::invalid_argument(fmt::format("{}: '{}' is not a number", what, text));
  return v;
}

/// A number of `dimension` in the data's units: bare as written (parse_number), or with its
/// unit ("0.232 MPa", "26.87 MPa/mm") converted into the data's units (--units) by UDUNITS-2.
double data_number(const std::string& text, const std::string& what, const std::string& dimension, const Units& u) {
  const std::optional<units::Quantity> q = units::split_quantity(text);
  if (!q || q->unit.empty()) return parse_number(text, what);
  if (u.text.empty())
    throw std::invalid_argument(fmt::format("{}: '{}' carries a unit: give the data's units with --units \"STRESS, "
                                            "LENGTH, TIME\" to convert it into",
                                            what, text));
  try {
    return units::convert(q->value, q->unit, u.of(dimension));
  } catch (const units::UnitError& e) {
    throw std::invalid_argument(fmt::format("{}: '{}': {}", what, text, e.what()));
  }
}

StagedHistory parse_stress(const std::string& text, const Units& u) {
  if (text.find(':') != std::string::npos) {
    // Staged, T:V[,T:V...]: each time and stress bare in the data's units or with its own
    // ("0 h:232 kPa,100 h:0.424 MPa"); plain numbers keep StagedHistory's own reading.
    if (text.find_first_of(" \t") == std::string::npos) return StagedHistory::parse(text, "--stress");
    std::vector<StagedHistory::Stage> stages;
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find(',', start), text.size());
      const std::string piece = text.substr(start, end - start);
      const std::size_t colon = piece.find(':');
      if (colon == std::string::npos)
        throw LawError("stress", fmt::format("--stress '{}': '{}' is not T:V", text, piece));
      auto trimmed = [](std::string x) {
        x.erase(0, x.find_first_not_of(" \t"));
        x.erase(x.find_last_not_of(" \t") + 1);
        return x;
      };
      stages.push_back({data_number(trimmed(piece.substr(0, colon)), "--stress (a stage's time)", "time", u),
                        data_number(trimmed(piece.substr(colon + 1)), "--stress (a stage's stress)", "stress", u)});
      start = end + 1;
    }
    return StagedHistory(std::move(stages));
  }
  const std::optional<units::Quantity> q = units::split_quantity(text);
  if (!q)
    throw LawError("stress", fmt::format("--stress '{}' is neither a number (with its unit or not) nor a staged "
                                         "history T:V[,T:V...]",
                                         text));
  return StagedHistory({{0.0, q->unit.empty() ? q->value : data_number(text, "--stress", "stress", u)}});
}

/// The dimension of the law parameter `name` (of `law`, or of any law for --law all); "" when
/// no law has it (fit::fit_law refuses it then).
std::string parameter_dimension(const std::string& law, const std::string& name) {
  for (const auto& info : LawRegistry::builtin().laws())
    if (law == "all" || info.name == law)
      for (const auto& p : info.parameters)
        if (p.name == name) return p.unit;
  return "";
}

// --fix NAME=VALUE, --initial NAME=VALUE, --bounds NAME=MIN:MAX (either side may
// be empty), --expr NAME=EXPRESSION into fit::FitOptions::parameters; the values themselves are
// checked by fit::fit_law against the law (FitError).
std::map<std::string, fit::ParameterSetting> parse_settings(const FitArgs& a, const Units& u) {
  // A value in the parameter's unit of the data, or with its own unit (data_number).
  const auto value_of = [&a, &u](const std::string& text, const std::string& what, const std::string& name) {
    return data_number(text, what, parameter_dimension(a.law, name), u);
  };
  std::map<std::string, fit::ParameterSetting> out;
  std::map<std::string, std::vector<std::string>> seen;  // name -> the options that set it
  auto split = [](const std::string& item, const char* flag) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw std::invalid_argument(fmt::format("{} '{}': expected NAME={}", flag, item,
                                              std::string(flag) == "--bounds" ? "MIN:MAX"
                                              : std::string(flag) == "--expr" ? "EXPRESSION"
                                                                              : "VALUE"));
    return std::pair{item.substr(0, eq), item.substr(eq + 1)};
  };
  auto claim = [&](const std::string& name, const std::string& flag) {
    auto& flags = seen[name];
    if (std::find(flags.begin(), flags.end(), flag) != flags.end())
      throw std::invalid_argument(fmt::format("{} {} is given twice", flag, name));
    flags.push_back(flag);
    // --expr first: it is read first, so with --fix on the same name both are in `flags`.
    if (flags.size() > 1 && std::find(flags.begin(), flags.end(), "--expr") != flags.end())
      throw std::invalid_argument(fmt::format(
          "--expr gives {} by an expression: --fix, --initial and --bounds on it are not supported", name));
    if (flags.size() > 1 && std::find(flags.begin(), flags.end(), "--fix") != flags.end())
      throw std::invalid_argument(fmt::format(
          "--fix {} holds {} at its value: --initial and --bounds on it would do nothing", name, name));
  };
  for (const auto& item : a.expr) {
    const auto [name, text] = split(item, "--expr");
    claim(name, "--expr");
    out[name].expr = text;
  }
  for (const auto& item : a.fix) {
    const auto [name, value] = split(item, "--fix");
    claim(name, "--fix");
    out[name].value = value_of(value, "--fix " + name, name);
    out[name].vary = false;
  }
  for (const auto& item : a.initial) {
    const auto [name, value] = split(item, "--initial");
    claim(name, "--initial");
    out[name].value = value_of(value, "--initial " + name, name);
  }
  for (const auto& item : a.bounds) {
    const auto [name, range] = split(item, "--bounds");
    claim(name, "--bounds");
    const std::size_t colon = range.find(':');
    if (colon == std::string::npos || range.find(':', colon + 1) != std::string::npos || range == ":")
      throw std::invalid_argument(fmt::format("--bounds {}: '{}' is not MIN:MAX (either may be empty, e.g. 100: "
                                              "or :1e4)",
                                              name, range));
    const std::string lo = range.substr(0, colon), hi = range.substr(colon + 1);
    if (!lo.empty()) out[name].min = value_of(lo, "--bounds " + name + " MIN", name);
    if (!hi.empty()) out[name].max = value_of(hi, "--bounds " + name + " MAX", name);
  }
  return out;
}

// ---- Screen report -------------------------------------------------------------
std::string g6(double v) { return fmt::format("{:.6g}", v); }

void print_data(const CreepData& d, const Units& u) {
  // Unit names after numbers only when the user stated them.
  auto unit = [&](const std::string& name) { return u.text.empty() ? std::string() : " " + name; };
  fmt::print("data: {} ({} points, {} stage{}, t from {} to {}{}); units: {}\n", d.source,
             d.t.size(), d.stages.size(), d.stages.size() == 1 ? "" : "s", g6(d.t.front()),
             g6(d.t.back()), unit(u.time), u.text.empty() ? "not stated (--units)" : u.text);
  for (std::size_t i = 0; i < d.stages.size(); ++i)
    fmt::print("  stage {}: stress {}{} from t = {} ({} points)\n", i + 1, g6(d.stages[i].stress),
               unit(u.stress), g6(d.stages[i].t), d.stages[i].count);
}

/// The correlation matrix of the estimates, lower triangle: Python's FitResult.correlation
/// (and --json's "correlation", which gives 0 for a held parameter); '-' where the fit gives
/// none: a parameter held (fixed, given by --expr) or not identifiable.
void print_correlation(const FitResult& r) {
  const std::size_t n = r.parameters.size();
  if (n < 2) return;
  std::size_t width = 8;
  for (const auto& p : r.parameters) width = std::max(width, p.name.size() + 1);
  auto cell = [&](std::size_t i, std::size_t j) {
    const double c = r.correlation_at(i, j);
    return std::isfinite(c) ? fmt::format("{:+.4f}", c) : std::string("-");
  };
  fmt::print("  correlation of the estimates ('-': none, the parameter held or not identifiable):\n  {:<{}}", "",
             width);
  for (std::size_t j = 0; j < n; ++j) fmt::print(" {:>{}}", r.parameters[j].name, width);
  fmt::print("\n");
  for (std::size_t i = 0; i < n; ++i) {
    fmt::print("  {:<{}}", r.parameters[i].name, width);
    for (std::size_t j = 0; j <= i; ++j) fmt::print(" {:>{}}", cell(i, j), width);
    fmt::print("\n");
  }
}

void print_fit(const FitResult& r, const Units& u) {
  const auto& info = LawRegistry::builtin().get(r.law);
  fmt::print("\nlaw {}: {}\n  {}\n", r.law, info.summary, info.equation);
  fmt::print("  {:<9} {:>14} {:>14} {:>10}  {}\n", "parameter", "value", "std. error", "rel. error",
             "unit");
  for (const auto& p : r.parameters) {
    const bool held = !p.vary || !p.at_bound.empty();
    std::string bounds;
    if (p.min > 0.0 || std::isfinite(p.max))
      bounds = fmt::format("  bounds [{:g}, {:g}]", p.min, p.max);
    fmt::print("  {:<9} {:>14.7g} {:>14} {:>10}  {}{}\n", p.name, p.value,
               !p.expr.empty() ? (p.identifiable ? fmt::format("{:.3g}", p.std_error) : "-")
               : !p.vary ? "fixed" : !p.at_bound.empty() ? "at " + p.at_bound
                                 : p.identifiable ? fmt::format("{:.3g}", p.std_error) : "-",
               p.identifiable && (!held || !p.expr.empty()) ? fmt::format("{:.3g}%", 100.0 * p.std_error / p.value)
                                                            : "-",
               u.of(p.unit), p.expr.empty() ? bounds : "  = " + p.expr);
  }
  for (const auto& c : r.combinations)
    fmt::print("  fixed by the data: {} = {:.7g} +- {:.3g} ({:.3g}%)  {}\n", c.expression, c.value,
               c.std_error, 100.0 * c.std_error / c.value, u.of(c.unit));
  print_correlation(r);
  fmt::print("  R^2 {}   RMSE {:.4g} {}   AIC {:.2f}   BIC {:.2f}   (n = {}, k = {})\n",
             r.r2_defined() ? fmt::format("{:.8f}", r.r2) : "undefined (the data have no spread)",
             r.rmse, u.length, r.aic, r.bic, r.points, r.varying);
  if (r.weighted)
    fmt::print("  chi-square {:.6g}   reduced chi-square {:.6g}   (sigma: {}; standard errors {})\n", r.chi_square,
               r.reduced_chi_square, "measurement", r.scale_covariance ? "scaled by sqrt(reduced chi-square)"
                                                                        : "from sigma as absolute errors");
  fmt::print("  best of {} starts ({} from the variable-projection search; {} reached it), {} "
             "iterations, {}{}\n",
             r.starts, r.structured_starts, r.starts_agreeing, r.iterations,
             r.converged ? "converged" : "NOT converged",
             r.minimum_certain ? "" : ", minimum NOT certain");
  std::string minima;
  for (double m : r.start_minima) minima += fmt::format("{}{:.6g}", minima.empty() ? "" : " ", m);
  fmt::print("  minima of the starts ({}): {}\n", r.weighted ? "chi-square" : fmt::format("RSS [{}^2]", u.length),
             minima);
  for (const auto& w : r.warnings) fmt::print("  warning: {}\n", w);
}

void print_ranking(const std::vector<FitResult>& ranked, bool bic, const Units& u) {
  const auto w = ranking_weights(ranked, bic);  // fit_verdict.cpp
  fmt::print("\nranking by {} (lower is better; weight = exp(-delta/2), normalized):\n",
             bic ? "BIC" : "AIC");
  fmt::print("  {:>4}  {:<20} {:>2} {:>12} {:>12} {:>12} {:>10} {:>12} {:>10} {:>8}\n", "rank", "law",
             "k", fmt::format("RMSE [{}]", u.length), "R^2", "AIC", "dAIC", "BIC", "dBIC", "weight");
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    const auto& r = ranked[i];
    fmt::print("  {:>4}  {:<20} {:>2} {:>12.4g} {:>12} {:>12.2f} {:>10.2f} {:>12.2f} {:>10.2f} {:>8.4f}\n",
               i + 1, r.law, r.varying, r.rmse,
               r.r2_defined() ? fmt::format("{:.8f}", r.r2) : "undefined", r.aic, r.aic - ranked.front().aic,
               r.bic, r.bic - ranked.front().bic, w[i]);
  }
}

// ---- Files ---------------------------------------------------------------------------
void run_fit(const FitArgs& a) {
  if (a.stress.empty() && a.stress_column.empty())
    throw std::invalid_argument(
        "no applied stress: give one stress for the file (--stress VALUE or --stress T:V,...) or "
        "a stress column (--stress-column NAME)");
  if (!a.stress.empty() && !a.stress_column.empty())  // CLI11 refuses this first (excludes)
    throw std::invalid_argument(
        "--stress and --stress-column both given: give one stress for the file or a stress "
        "column, not both");
  const Units units = parse_units(a.units);
  const YamlUnits yunits = yaml_units(a.scene_units, a.scene_file, units, a.yaml);
  const std::string terminal = a.plot.empty() ? "" : plot_terminal(a.plot);
  if (a.restarts < 0 || a.restarts > 100)
    throw std::invalid_argument(fmt::format("--restarts {}: expected 0 to 100", a.restarts));
  if (a.max_iterations < 1 || a.max_iterations > 1000000)
    throw std::invalid_argument(fmt::format("--max-iterations {}: expected 1 to 1000000", a.max_iterations));
  const bool all = a.law == "all";
  const LawInfo* single = all ? nullptr : &LawRegistry::builtin().get(a.law);

  fit::CsvOptions csv;
  csv.time_column = a.time_column;
  csv.displacement_column = a.displacement_column;
  csv.stress_column = a.stress_column;
  csv.sigma_column = a.sigma_column;
  if (!a.stress.empty()) csv.stress = parse_stress(a.stress, units);
  if (a.absolute_sigma && a.sigma_column.empty())
    throw std::invalid_argument("--absolute-sigma takes the --sigma-column values as absolute errors; give "
                                "--sigma-column NAME");
  fit::FitOptions opt;
  opt.restarts = a.restarts;
  opt.max_iterations = a.max_iterations;
  opt.parameters = parse_settings(a, units);
  opt.scale_covariance = !a.absolute_sigma;
  const CreepData data = fit::read_creep_csv(a.data, csv);

  std::vector<FitResult> fits;
  std::vector<std::string> skipped;
  if (all) {
    scene::Progress display(a.quiet ? nullptr : stderr);  // docs/reference/cli.md, "Progress"
    std::optional<scene::ProgressPhase> phase;
    fits = fit::fit_all(LawRegistry::builtin(), data,
                        a.rank_by == "aic" ? fit::Criterion::aic : fit::Criterion::bic, skipped, opt,
                        [&](const std::string& law, std::size_t k, std::size_t n) {
                          std::string text = fmt::format("rheodda fit --law all: law {} of {} ({})", k + 1, n, law);
                          if (phase) phase->set(std::move(text));
                          else phase.emplace(display, std::move(text));
                        });
    if (phase) phase->set(fmt::format("rheodda fit --law all: {} laws", LawRegistry::builtin().laws().size()));
    phase.reset();
    if (fits.empty()) {
      std::string why;
      for (const auto& s : skipped) why += "\n  " + s;
      throw std::invalid_argument(fmt::format("{}: no law can be fitted to these data:{}", a.data, why));
    }
  } else {
    fits.push_back(fit::fit_law(*single, data, opt));
  }

  print_data(data, units);
  for (const auto& r : fits) print_fit(r, units);
  for (const auto& s : skipped) fmt::print("\nskipped {}\n", s);
  if (all) {
    print_ranking(fits, a.rank_by != "aic", units);
    fmt::print("\nbest: {}\n", fits.front().law);
    fmt::print("{}", fit_verdict(fits, a.rank_by != "aic"));  // fit_verdict.cpp
  }
  if (!a.json.empty()) write_json(a.json, data, units, fits, skipped, a.rank_by);
  if (!a.yaml.empty()) write_yaml(a.yaml, data, units, fits.front(), yunits);
  if (!a.plot.empty()) write_plot(a.plot, terminal, data, units, fits);
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto a = std::make_shared<FitArgs>();
  auto* cmd = app.add_subcommand(
      "fit", "Fit laws to a laboratory creep curve (CSV of time and shear displacement)");
  cmd->add_option("DATA", a->data, "CSV file with a header row")->required();
  cmd->add_option("--law", a->law, "Law to fit (see `rheodda law list`), or 'all' to fit and rank every law")
      ->required();
  auto* s = cmd->add_option("--stress", a->stress,
                            "Applied shear stress of the whole file: VALUE, or staged T:V[,T:V...]")
                ->type_name("VALUE|T:V,...");
  auto* sc = cmd->add_option("--stress-column", a->stress_column,
                             "Column holding the applied shear stress of each row (multi-stage tests)")
                 ->type_name("NAME");
  s->excludes(sc);
  cmd->add_option("--time-column", a->time_column, "Column of the time")->capture_default_str();
  cmd->add_option("--displacement-column", a->displacement_column,
                  "Column of the total shear displacement")
      ->capture_default_str();
  cmd->add_option("--units", a->units, "Units 'STRESS, LENGTH, TIME' of the data, e.g. \"MPa, mm, h\"");
  auto* rank = cmd->add_option("--rank-by", a->rank_by, "Criterion ranking the laws with --law all")
                   ->check(CLI::IsMember({"aic", "bic"}))
                   ->capture_default_str();
  cmd->add_option("--restarts", a->restarts, "Extra starts besides the one derived from the curve")
      ->capture_default_str();
  cmd->add_option("--max-iterations", a->max_iterations,
                  "Iteration limit per start (and again for a bounded fit's refinement)")
      ->capture_default_str();
  cmd->add_option("--expr", a->expr,
                  "A parameter given by an expression of the others (repeatable; + - * / ^ ( ) numbers names), "
                  "e.g. --expr eta2=12*E2")
      ->type_name("NAME=EXPRESSION");
  cmd->add_option("--fix", a->fix, "Hold a parameter at a value (repeatable), e.g. --fix E1=26.87")
      ->type_name("NAME=VALUE");
  cmd->add_option("--initial", a->initial, "Initial value of a parameter, tried as the first start (repeatable)")
      ->type_name("NAME=VALUE");
  cmd->add_option("--bounds", a->bounds,
                  "Bounds of a parameter (repeatable), either may be empty, e.g. --bounds eta2=100:1e4")
      ->type_name("NAME=MIN:MAX");
  cmd->add_option("--sigma-column", a->sigma_column,
                  "Column of each row's measurement standard deviation: minimizes sum ((model - data)/sigma)^2")
      ->type_name("NAME");
  cmd->add_flag("--absolute-sigma", a->absolute_sigma,
                "Standard errors from sigma as absolute errors (default: scaled by sqrt(reduced chi-square))");
  cmd->add_option("--json", a->json, "Write the full report as JSON")->type_name("FILE");
  cmd->add_option("--yaml", a->yaml, "Write the (best) law as a YAML block for a joint set")
      ->type_name("FILE");
  auto* su = cmd->add_option("--scene-units", a->scene_units,
                             "Units 'LENGTH, FORCE, TIME' of the scene the --yaml law goes into, e.g. \"m, N, d\" "
                             "(converted from --units)")
                 ->type_name("UNITS");
  auto* sf = cmd->add_option("--scene", a->scene_file, "Scene file whose units the --yaml law is written in")
                 ->type_name("FILE");
  su->excludes(sf);
  cmd->add_option("--plot", a->plot, "Draw data, fit and residuals with gnuplot (.png or .svg)")
      ->type_name("FILE");
  add_quiet_flag(*cmd, a->quiet);
  cmd->callback([a, rank] {
    if (rank->count() > 0 && a->law != "all")
      throw std::invalid_argument("--rank-by ranks the laws of --law all; it does nothing with one law");
    run_fit(*a);
  });
}

}  // namespace rheodda::apps
