// `rheodda law list` and `rheodda law curve`: the law library on its own.
#include <fmt/format.h>

#include <algorithm>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rheodda/laws/accurate_curve.hpp"
#include "rheodda/laws/registry.hpp"

namespace rheodda::apps {
namespace {

using namespace rheodda::laws;

void print_law_list() {
  for (const auto& law : LawRegistry::builtin().laws()) {
    fmt::print("{}: {}\n  {}\n", law.name, law.summary, law.equation);
    for (const auto& p : law.parameters)
      fmt::print("  {:<6} {:<20} {:<14} {}{}\n", p.name, p.unit, p.range_text(), p.meaning,
                 p.default_value ? fmt::format(" (default {:g})", *p.default_value) : "");
  }
  fmt::print(
      "\nUnits are per unit joint area: with stress in MPa, length in mm and time in h,\n"
      "stress/length is MPa/mm and stress*time/length is MPa*h/mm.\n");
}

struct CurveOptions {
  std::string law;
  std::vector<std::string> params;
  std::string force, displacement;
  double t_end = 0.0, dt = 0.0;
  std::string scheme = "exponential-linear";
  double tolerance = CurveAccuracy{}.tolerance;
};

ParameterValues parse_params(const std::vector<std::string>& items) {
  ParameterValues values;
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw LawError(item, fmt::format("--param '{}' is not of the form NAME=VALUE", item));
    const std::string name = item.substr(0, eq);
    const std::string text = item.substr(eq + 1);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size())
      throw LawError(name, fmt::format("--param {}: '{}' is not a number", name, text));
    if (!values.emplace(name, v).second)
      throw LawError(name, fmt::format("--param {} is given twice", name));
  }
  return values;
}

int run_curve(const CurveOptions& o) {
  const auto law = LawRegistry::builtin().create(o.law, parse_params(o.params));
  const Scheme scheme = parse_scheme(o.scheme);
  const bool by_force = !o.force.empty();
  const char* what = by_force ? "--force" : "--displacement";
  const StagedHistory history = StagedHistory::parse(by_force ? o.force : o.displacement, what);
  // A stage that starts after the end would be silently dropped: refuse it.
  for (const auto& stage : history.stages())
    if (stage.t > o.t_end)
      throw LawError(what, fmt::format("{}: stage at time {:g} starts after --t-end {:g}", what,
                                       stage.t, o.t_end));
  // Each output step in substeps of the scheme until step doubling says the curve
  // holds --tolerance (laws/accurate_curve.hpp); what cannot is refused (exit 1).
  AccurateCurve curve;
  try {
    curve = integrate_curve_accurate(*law, by_force ? Control::force : Control::displacement, history, o.t_end,
                                     o.dt, scheme, {o.tolerance});
  } catch (const CurveError& e) {
    fmt::print(stderr, "rheodda: error: law curve {}: {}\n", o.law, e.what());
    throw CLI::RuntimeError(kExitFailure);
  }
  const auto& samples = curve.samples;
  bool any_exact = false, any_damage = false;
  for (const auto& s : samples) {
    any_exact = any_exact || s.exact.has_value();
    any_damage = any_damage || s.damage > 0.0;
  }
  any_damage = any_damage || curve.failure_time.has_value();
  // A damage law (damage-burgers, docs/reference/laws.md) adds its damage D [-] per sample.
  std::string out = std::string("t,force,displacement") + (any_exact ? ",exact" : "") +
                    (any_damage ? ",damage" : "") + "\n";
  for (const auto& s : samples) {
    out += fmt::format("{:.10g},{:.10g},{:.10g}", s.t, s.force, s.displacement);
    if (any_exact) out += s.exact ? fmt::format(",{:.10g}", *s.exact) : ",";
    if (any_damage) out += fmt::format(",{:.10g}", s.damage);
    out += '\n';
  }
  std::fputs(out.c_str(), stdout);
  // What the substeps took, when the output step alone was not accurate enough.
  const auto output_steps = static_cast<long long>(samples.size()) - 1;
  if (curve.steps > output_steps)
    fmt::print(stderr, "law curve: {} substeps of the {} scheme (smallest {:.3g}) held each substep's error within "
                       "--tolerance {:g}\n",
               curve.steps, o.scheme, curve.smallest_step, o.tolerance);
  // The failure, on stderr (the CSV stays a table): when the damage reached 1, and
  // under a constant force the law's closed-form failure time t_f.
  if (any_damage) {
    std::string closed;
    if (by_force && history.stages().size() == 1)
      if (const auto tf = law->failure_time(history.stages().front().value))
        closed = fmt::format(" (closed form under the constant force {:g}: t_f = {:.10g})",
                             history.stages().front().value, history.stages().front().t + *tf);
    if (curve.ends_at_failure)
      fmt::print(stderr, "law curve: {} fails at t = {:.10g}{}, where its creep is infinite (n >= r + 1): the "
                         "curve ends at t = {:.10g}, the last output time before it\n",
                 o.law, *curve.failure_time, closed, samples.back().t);
    else if (curve.failure_time)
      fmt::print(stderr, "law curve: {} failed (damage 1) at t = {:.10g}{}; its creep stays at its value at "
                         "failure from then on\n",
                 o.law, *curve.failure_time, closed);
    else
      fmt::print(stderr, "law curve: {} did not fail by t = {:g}{}\n", o.law, o.t_end, closed);
  }
  return 0;
}

}  // namespace

void add_law_commands(CLI::App& app) {
  auto* law = app.add_subcommand("law", "The rheology law library: list laws, print creep curves");
  law->require_subcommand(1);

  auto* list = law->add_subcommand("list", "Print every law with its parameters and units");
  list->callback([] { print_law_list(); });

  auto opts = std::make_shared<CurveOptions>();
  auto* curve = law->add_subcommand(
      "curve", "Integrate one law under a staged force or displacement history; CSV to stdout");
  curve->add_option("LAW", opts->law, "Law name (see `rheodda law list`)")->required();
  curve->add_option("--param", opts->params, "Law parameter NAME=VALUE (repeat)")
      ->type_name("NAME=VALUE");
  auto* f = curve->add_option("--force", opts->force,
                              "Staged force T:F[,T:F...]: F [stress, e.g. MPa] holds from time T on")
                ->type_name("T:F,...");
  auto* d = curve->add_option("--displacement", opts->displacement,
                              "Staged total displacement T:D[,T:D...] [length, e.g. mm] (relaxation)")
                ->type_name("T:D,...");
  f->excludes(d);
  curve->add_option("--t-end", opts->t_end, "End time [time, e.g. h]")->required();
  curve->add_option("--dt", opts->dt, "Time step [time]; stage starts are added as step ends")
      ->required();
  curve->add_option("--scheme", opts->scheme, "Integration scheme (docs/reference/laws.md, \"Schemes\")")
      ->check(CLI::IsMember({"lagged", "implicit", "exponential-linear"}))
      ->capture_default_str();
  curve->add_option("--tolerance", opts->tolerance,
                    "Largest error of a substep relative to the curve's scale: each --dt is crossed in substeps "
                    "of the scheme until one step and two half steps agree to this (docs/reference/laws.md)")
      ->check(CLI::Range(1e-12, 1e-2))
      ->capture_default_str();
  curve->callback([opts, curve] {
    if (opts->force.empty() && opts->displacement.empty())
      throw CLI::ValidationError("law curve", "one of --force or --displacement is required");
    (void)curve;
    run_curve(*opts);
  });
}

}  // namespace rheodda::apps
