// `rheodda forecast`: a scene's histories with the uncertainty of a fitted law (docs/guide/forecast.md).
// Sample runs:
//   rheodda fit examples/creep-data/table1-row1.csv --law burgers --stress 0.232 --units "MPa, mm, h" --json out/fit.json
//   rheodda forecast examples/shear-creep-test.yaml --fit out/fit.json --joint-set plane -o out/forecast
//   mpirun -np 3 rheodda forecast examples/shear-creep-test.yaml --fit out/fit.json --joint-set plane -o out/forecast
//
// The law parameters of one joint set are drawn from the fit's covariance (forecast.hpp),
// the ensemble is written as a study file (OUT/ensemble.yaml) and run as a study
// (OUT/cases/sampleNNN/, locally or over MPI ranks), then every history column's
// percentiles across the members are taken at the scene's output times.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rheodda/forecast/bands.hpp"
#include "rheodda/forecast/forecast.hpp"
#include "rheodda/scene/history_columns.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/progress.hpp"
#include "rheodda/study/study.hpp"
#include "rheodda/units/units.hpp"
#ifdef RHEODDA_WITH_MPI
#include "mpi_study.hpp"
#endif


namespace rheodda::apps {
namespace {

namespace fs = std::filesystem;
namespace fc = rheodda::forecast;

volatile std::sig_atomic_t g_forecast_stop = 0;
extern "C" void on_forecast_stop(int signo) { g_forecast_stop = signo; }

struct ForecastArgs {
  std::string scene;
  std::string fit;
  std::string joint_set;
  std::string law;
  std::size_t samples = 100;
  std::uint64_t seed = 1;
  std::vector<double> percentiles{5, 50, 95};
  double unidentified_spread = 0.0;
  std::string column;
  std::string threshold_text;  ///< --threshold: a length, bare in the scene's unit or with its own ("50 mm")
  std::string by;  ///< --by: a time, bare in the scene's unit or with its own ("100 d"); empty: the end
  std::string out;
  int jobs = 0;
  bool no_plot = false;
  bool resume = false;
  bool quiet = false;
  std::string case_program;
};


/// A dimension ("stress*time/length") in a scene's unit labels ("N/mm^2*h/mm"); "-" stays "-".
std::string scene_unit(const std::string& dimension, const scene::Units& u) {
  return dimension == "-" ? dimension : units::unit_of(dimension, {.length = u.length, .force = u.force, .time = u.time});
}

/// A YAML double-quoted scalar.
std::string yaml_quoted(const std::string& s) {
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') q += '\\';
    q += ch;
  }
  return q + "\"";
}

/// Columns of history.csv that are not results (time stepping bookkeeping).
bool bookkeeping(const std::string& c) {
  const std::vector<std::string> step = scene::history_part_columns(scene::HistoryPart::step);
  return std::find(step.begin(), step.end(), c) != step.end();
}

/// The ensemble as a study file: one case per accepted sample, the law's parameters set
/// on the joint set (in the scene's units).
std::string ensemble_text(const ForecastArgs& a, const scene::SceneDescription& s, const fc::FittedLaw& fit,
                          const std::vector<laws::ParameterValues>& samples, const std::string& output, double by) {
  const auto& js = *std::find_if(s.joint_sets.begin(), s.joint_sets.end(),
                                 [&](const auto& j) { return j.name == a.joint_set; });
  const bool same_law = js.law && js.law->name == fit.law;
  std::string t = fmt::format(
      "# The ensemble of `rheodda forecast`: {} samples of law {} of joint set {} drawn from {}.\n"
      "# `rheodda study` runs it again (with --resume: only what is missing).\n"
      "title: {}\n"
      "scene: {}\n"
      "outputs: [{}]\n"
      "times: [{}]\n"
      "cases:\n",
      samples.size(), fit.law, a.joint_set, fit.file,
      yaml_quoted(fmt::format("forecast of {} with the uncertainty of {}", s.title, fs::path(fit.file).filename().string())),
      fs::absolute(a.scene).string(), output, by);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    std::vector<std::string> sets;
    if (same_law) {  // the scene's law keeps its other keys (scheme, ...); its parameters change
      for (const auto& [name, v] : samples[k]) sets.push_back(fmt::format("joint_sets.{}.law.{}: {}", a.joint_set, name, v));
    } else {
      std::vector<std::string> ps{fmt::format("name: {}", fit.law)};
      for (const auto& [name, v] : samples[k]) ps.push_back(fmt::format("{}: {}", name, v));
      sets.push_back(fmt::format("joint_sets.{}.law: {{{}}}", a.joint_set, fmt::join(ps, ", ")));
    }
    t += fmt::format("  - {{name: {}, set: {{{}}}}}\n", study::drawn_case_name(k, samples.size()), fmt::join(sets, ", "));
  }
  return t;
}

void forecast_command(const ForecastArgs& a, study::CaseExecutor* executor) {
  // --- Inputs, all checked before anything runs (exit 2).
  require_readable(a.scene);
  require_readable(a.fit);
  const scene::SceneDescription s = scene::load_scene(a.scene);
  const auto js = std::find_if(s.joint_sets.begin(), s.joint_sets.end(), [&](const auto& j) { return j.name == a.joint_set; });
  if (js == s.joint_sets.end()) {
    std::vector<std::string> names;
    for (const auto& j : s.joint_sets) names.push_back(j.name);
    throw std::invalid_argument(fmt::format("--joint-set {}: the scene {} has no such joint set; it has: {}", a.joint_set,
                                            a.scene, fmt::join(names, ", ")));
  }
  for (double p : a.percentiles)
    if (!(p >= 0 && p <= 100)) throw std::invalid_argument(fmt::format("--percentiles: {:g} is not in [0, 100]", p));
  if (a.unidentified_spread != 0.0 && !(a.unidentified_spread > 1.0))
    throw std::invalid_argument(fmt::format("--unidentified-spread {:g}: a factor > 1 (or 0: held at the fitted value)",
                                            a.unidentified_spread));
  if (!a.by.empty() && a.threshold_text.empty()) throw std::invalid_argument("--by needs --threshold (the probability of exceeding it by that time)");
  const double by = a.by.empty() ? s.analysis.duration : option_quantity("--by", a.by, "time", s.units);
  if (by < 0 || by > s.analysis.duration * (1 + 1e-12))
    throw std::invalid_argument(fmt::format("--by {} is outside the run (0 to {:g} {})", a.by, s.analysis.duration, s.units.time));
  const fc::FittedLaw fit = fc::read_fit_report(a.fit, a.law);

  // The column of the fan chart and of the probability: given, or the joint set's shear
  // displacement when it is recorded, or the first measurement point's displacement.
  std::string column = a.column;
  if (column.empty()) {
    if (js->record) column = a.joint_set + ".shear_displacement_magnitude";
    else if (!s.measurement_points.empty()) column = s.measurement_points.front().name + ".displacement";
    else throw std::invalid_argument("--column: the scene records no joint set and has no measurement point; give a history column");
  }
  // The threshold in the column's units: a displacement's in the scene's length unit, or
  // with its own ("50 mm"); a column of another kind takes a bare number.
  std::optional<double> threshold;
  if (!a.threshold_text.empty())
    threshold = option_quantity(
        "--threshold", a.threshold_text,
        scene::history_column_unit(column, s.units.length, s.units.force, s.units.time) == s.units.length ? "length" : "",
        s.units);

  // Units: the fit's parameters in the scene's units.
  const bool placeholder_units = fit.stress_unit == "stress" || fit.stress_unit.empty();
  std::vector<double> factor(fit.names.size(), 1.0);
  if (!placeholder_units)
    for (std::size_t i = 0; i < fit.names.size(); ++i)
      factor[i] = fc::unit_factor(fit.dimensions[i], fit, s.units.length, s.units.force, s.units.time);

  fc::Unidentified u;
  u.spread = a.unidentified_spread;
  const fc::Samples drawn = fc::draw_samples(fit, a.samples, a.seed, u);
  std::vector<laws::ParameterValues> scene_samples;
  for (const auto& v : drawn.accepted) {
    laws::ParameterValues c;
    for (std::size_t i = 0; i < fit.names.size(); ++i) c[fit.names[i]] = v.at(fit.names[i]) * factor[i];
    scene_samples.push_back(std::move(c));
  }

  const fs::path out = a.out.empty() ? fs::path("out") / (fs::path(a.scene).stem().string() + "-forecast") : fs::path(a.out);
  fs::create_directories(out);
  {  // samples.csv: each member's parameters in the scene's units
    std::ofstream f(out / "samples.csv", std::ios::binary);
    f << "case";
    for (std::size_t i = 0; i < fit.names.size(); ++i) f << "," << fit.names[i] << " [" << scene_unit(fit.dimensions[i], s.units) << "]";
    f << "\n";
    for (std::size_t k = 0; k < scene_samples.size(); ++k) {
      f << study::drawn_case_name(k, scene_samples.size());
      for (const auto& n : fit.names) f << "," << fmt::format("{}", scene_samples[k].at(n));
      f << "\n";
    }
  }
  const fs::path study_file = out / "ensemble.yaml";
  // The study's own output: the column at --by (its study.csv); the bands come from the histories.
  std::ofstream(study_file, std::ios::binary) << ensemble_text(a, s, fit, scene_samples, column, by);
  const study::StudyDescription st = study::load_study(study_file.string());
  const auto stop_if_asked = [&] {  // SIGINT or SIGTERM: stop between the phases (and the cases)
    if (!g_forecast_stop) return;
    fmt::print("forecast stopped; resume with: rheodda forecast ... -o {} --resume (same arguments)\n", out.string());
    throw CLI::RuntimeError(128 + static_cast<int>(g_forecast_stop));
  };
  stop_if_asked();

  fmt::print(stderr, "rheodda forecast: {} of {} draws of {} accepted ({} rejected){}{}; running {} members\n",
             drawn.accepted.size(), drawn.drawn, fit.law, drawn.drawn - drawn.accepted.size(),
             drawn.held.empty() ? "" : fmt::format("; not identified, held at the fit: {}", fmt::join(drawn.held, ", ")),
             drawn.spread.empty() ? "" : fmt::format("; not identified, drawn within a factor {:g}: {}", u.spread, fmt::join(drawn.spread, ", ")),
             scene_samples.size());

  // What the band covers, and what not (coverage.cpp): said before the members run.
  const std::string coverage = fc::band_coverage(fit, drawn, u);
  fmt::print("{}", coverage);

  // --- The ensemble, as a study.
  study::StudyOptions opt;
  opt.out_dir = out.string();
  opt.jobs = a.jobs;
  opt.progress = !a.quiet;
  opt.plot = !a.no_plot;
  opt.resume = a.resume;
  opt.stop = &g_forecast_stop;
  opt.executor = executor;
  if (!a.case_program.empty()) opt.rheodda_binary = fs::absolute(a.case_program).string();
  std::vector<study::CaseResult> results;
  try {
    results = study::run_study(st, opt);
  } catch (const scene::SceneError&) {
    throw;
  } catch (const std::exception& e) {
    fmt::print(stderr, "rheodda: error: {}\n", e.what());
    throw CLI::RuntimeError(kExitFailure);
  }
  stop_if_asked();

  // --- Bands: every history column (and POINT.displacement) at the output times (bands.hpp).
  scene::Progress display(a.quiet ? nullptr : stderr);  // docs/reference/cli.md, "Progress"
  std::optional<scene::ProgressPhase> phase(std::in_place, display, "rheodda forecast: reading the members' histories");
  std::vector<fc::History> members;
  std::vector<std::string> failed;
  for (const auto& r : results) {
    if (r.status != "completed") {
      failed.push_back(r.name + ": " + r.message);
      continue;
    }
    members.push_back(fc::read_history((out / "cases" / r.name / "history.csv").string()));
  }
  if (members.empty()) {
    fmt::print(stderr, "rheodda: error: no member of the ensemble completed; see {}/study.csv\n", out.string());
    throw CLI::RuntimeError(kExitFailure);
  }
  for (auto& h : members) fc::add_point_displacements(h);
  const fc::History& first = members.front();
  if (!fc::column_index(first, column))
    throw std::invalid_argument(fmt::format("--column {}: history.csv has no such column; it has: {}", column,
                                            fmt::join(first.columns, ", ")));
  std::vector<std::string> band_columns;
  for (const auto& c : first.columns)
    if (!bookkeeping(c)) band_columns.push_back(c);
  // At the members' output times (those of the scene and --by, ensemble_text's study
  // `times`): every member has a row at each (docs/guide/forecast.md, "Outputs").
  std::vector<double> band_times = scene::run_output_times(s.analysis);
  if (std::none_of(band_times.begin(), band_times.end(), [&](double t) { return std::abs(t - by) <= 1e-9 * s.analysis.duration; }))
    band_times.insert(std::upper_bound(band_times.begin(), band_times.end(), by), by);
  phase.emplace(display, "rheodda forecast: writing bands.csv");
  fc::write_bands((out / "bands.csv").string(), members, band_columns, a.percentiles, band_times);
  phase.reset();

  // --- The probability that the column exceeds the threshold by time `by` (its largest value up to then).
  nlohmann::json exceed = nullptr;
  if (threshold) {
    const fc::Exceedance e = fc::exceedance(members, column, *threshold, by);
    exceed = {{"column", column}, {"threshold", *threshold}, {"by", by}, {"members", e.members},
              {"exceeding", e.exceeding}, {"probability", e.probability}, {"std_error", e.std_error}};
    fmt::print("P({} > {:g} by t = {:g} {}) = {:.3f} +- {:.3f} ({} of {} members)\n", column, *threshold, by,
               s.units.time, e.probability, e.std_error, e.exceeding, e.members);
  }

  // --- forecast.json
  {
    nlohmann::json params = nlohmann::json::array();
    for (std::size_t i = 0; i < fit.names.size(); ++i)
      params.push_back({{"name", fit.names[i]}, {"fitted", fit.values[i]}, {"fit_unit", fit.units[i]},
                        {"factor_to_scene", factor[i]}, {"log_std", fit.identifiable[i] ? nlohmann::json(fit.log_std[i]) : nlohmann::json(nullptr)},
                        {"identifiable", static_cast<bool>(fit.identifiable[i])},
                        {"sampled", fit.identifiable[i] ? "normal in ln" : (u.spread > 1 ? "log-uniform within the spread" : "held at the fitted value")}});
    nlohmann::json rejected = nlohmann::json::object();
    for (const auto& [why, n] : drawn.rejected) rejected[why] = n;
    const nlohmann::json j{{"scene", a.scene}, {"fit", a.fit}, {"law", fit.law}, {"joint_set", a.joint_set},
                           {"seed", a.seed}, {"samples_requested", a.samples}, {"draws", drawn.drawn},
                           {"accepted", drawn.accepted.size()}, {"rejected", rejected},
                           {"unidentified_spread", u.spread}, {"parameters", params},
                           {"members_completed", members.size()}, {"members_failed", failed},
                           {"percentiles", a.percentiles}, {"column", column}, {"exceedance", exceed},
                           {"units_converted", !placeholder_units},
                           {"law_form_sampled", false}, {"band_coverage", coverage}};
    std::ofstream(out / "forecast.json", std::ios::binary) << j.dump(2) << "\n";
  }

  // --- The fan chart of the column: the outer band, the inner ones, the median (fan_chart.cpp).
  if (!a.no_plot) {
    const scene::ProgressPhase drawing(display, "rheodda forecast: drawing fan.png");
    try {
      fc::draw_fan_chart({.out_dir = out.string(), .band_columns = band_columns, .percentiles = a.percentiles,
                          .column = column, .units_line = !first.units_line.empty(),
                          .title = fmt::format("{}: {} members, law {} of {}", s.title, members.size(), fit.law,
                                               a.joint_set),
                          .time_unit = s.units.time, .length_unit = s.units.length, .threshold = threshold});
    } catch (const std::exception& e) {
      fmt::print(stderr, "rheodda: error: {}\n", e.what());
      throw CLI::RuntimeError(kExitFailure);
    }
  }
  fmt::print("forecast of {}: {} members completed{}; bands of {} columns in {}/bands.csv{}, members in {}/cases/\n",
             s.title, members.size(), failed.empty() ? "" : fmt::format(", {} failed", failed.size()),
             band_columns.size(), out.string(), a.no_plot ? "" : ", fan chart fan.png", out.string());
  for (const auto& f : failed) fmt::print("  failed {}\n", f);
  if (!failed.empty()) throw CLI::RuntimeError(kExitFailure);
}

}  // namespace

void add_forecast_command(CLI::App& app) {
  auto a = std::make_shared<ForecastArgs>();
  auto* cmd = app.add_subcommand(
      "forecast", "Run a scene with the uncertainty of a fitted law: percentile bands, fan chart, exceedance (docs/guide/forecast.md)");
  cmd->add_option("SCENE", a->scene, "Scene file (YAML)")->required();
  cmd->add_option("--fit", a->fit, "Report of `rheodda fit --json` (parameters, standard errors, correlation)")
      ->required()->type_name("FIT.json");
  cmd->add_option("--joint-set", a->joint_set, "Joint set whose law is sampled")->required()->type_name("NAME");
  cmd->add_option("--law", a->law, "Law of the report to sample (default: its best)");
  cmd->add_option("--samples", a->samples, "Members of the ensemble (accepted draws)")
      ->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", a->seed, "Seed of the draws (the same seed gives the same members)")->capture_default_str();
  cmd->add_option("--percentiles", a->percentiles, "Percentiles of the bands [%]")->delimiter(',')->capture_default_str();
  cmd->add_option("--unidentified-spread", a->unidentified_spread,
                  "Parameters the fit could not identify: 0 holds them at the fitted value, F > 1 draws them "
                  "log-uniformly within a factor F")->capture_default_str();
  cmd->add_option("--column", a->column,
                  "History column of the fan chart and of --threshold (default: JOINT_SET.shear_displacement_magnitude "
                  "when the joint set is recorded, else the first measurement point's displacement)");
  cmd->add_option("--threshold", a->threshold_text,
                  "Probability that --column (a displacement) exceeds this value (the scene's length unit, or with a "
                  "unit: \"50 mm\")")
      ->type_name("VALUE");
  cmd->add_option("--by", a->by, "... by this time (the scene's time unit, or with a unit: \"100 d\"; default: the end of the run)")->type_name("TIME");
  cmd->add_option("-o,--out", a->out, "Output directory (default out/<scene name>-forecast)")->type_name("OUTDIR");
  cmd->add_option("-j,--jobs", a->jobs, "Members run at once; 0 (the default): the machine's hardware threads")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-plot", a->no_plot, "Draw neither fan.png nor the study pictures");
  cmd->add_flag("--resume", a->resume, "Continue a stopped forecast in OUTDIR (same arguments): completed members are kept");
  cmd->add_option("--case-program", a->case_program, "Program run per member (as for rheodda study)")->type_name("PROGRAM");
  add_quiet_flag(*cmd, a->quiet);
  cmd->callback([a] {
    on_stop_signals(on_forecast_stop);
#ifdef RHEODDA_WITH_MPI
    if (study::mpi::launched_by_mpi()) {
      if (a->jobs != 0)
        throw std::invalid_argument("-j: under MPI each worker rank runs one member at a time; start one rank per core");
      const std::string binary = a->case_program.empty() ? fs::read_symlink("/proc/self/exe").string()
                                                         : fs::absolute(a->case_program).string();
      study::mpi::run_over_ranks(binary, &g_forecast_stop, [&](study::CaseExecutor* ranks) {
        if (ranks != nullptr)
          fmt::print(stderr, "rheodda forecast: members over {} MPI worker ranks (rank 0 dispatches)\n", ranks->capacity());
        forecast_command(*a, ranks);
      });
      return;
    }
#endif
    forecast_command(*a, nullptr);
  });
}

}  // namespace rheodda::apps
