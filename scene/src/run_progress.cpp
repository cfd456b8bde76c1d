// The progress display of `rheodda run` (run_progress.hpp; docs/reference/cli.md, "Progress").
//
// The time left is that of the simulated time still to run at the simulated-time
// rate of the last minute of the current stage. A dynamic stage of a static
// analysis (the settling stage, a mechanism stage) takes small steps until it
// ends at rest, at a time nobody knows beforehand, and the steps after it are of
// another size: no rate measured in it says anything of the rest of the run, so
// the display names the stage and gives no time left (nor a share of the
// simulated time, which stands near 0 % while settling takes most of the wall time).
#include "run_progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "run_internal.hpp"

namespace rheodda::scene {
namespace {

/// The window of the rate of simulated time [s].
constexpr double kRateWindow = 60.0;

}  // namespace

void RunProgress::follow(const Run& run, const core::StepReport* r) {
  const core::Engine& e = run.engine;
  const bool in = e.in_stage();
  const std::size_t ended = e.events().size();
  if (in && !r) {  // at the start (of a resumed run, perhaps within a mechanism stage): the saved stage, once
    const core::StageState stage = e.save().stage;
    kind_ = stage.event.kind;
    phase_start_ = stage.event.start_time;
  } else if (in && r && r->collapse_stage) {  // the step opened a mechanism stage (SettleStage::collapse_dt)
    kind_ = core::StageKind::mechanism;
    phase_start_ = e.time() - r->dt;
  } else if (in && (!in_dynamic_ || ended != events_)) {  // opened by a scene's stage (`settle: true`)
    kind_ = core::StageKind::settling;
    phase_start_ = e.time() - r->dt;
  }
  in_dynamic_ = in;
  events_ = ended;
  std::string phase = in ? core::stage_kind_name(kind_)
                         : e.model().settings.dynamic_ratio > 0.0 ? "dynamic"
                         : creep_                                 ? "creep"
                                                                  : "static";
  if (!run.stage_run.current.empty()) phase = fmt::format("stage '{}': {}", run.stage_run.current, phase);
  if (phase != phase_) {
    phase_ = std::move(phase);
    rate_.reset();  // a new stage, a new rate
  }
  rate_.add(display_.elapsed(), e.time());
}

std::string RunProgress::text(const Run& run, const char* how) {
  const core::Engine& e = run.engine;
  const std::string& u = run.s.units.time;
  const bool term = display_.terminal();
  const std::string sep = term ? "  " : ", ";
  std::string t = term ? "" : "rheodda run: ";
  if (how) t += std::string(how) + sep;
  t += phase_;
  t += fmt::format("{}t = {:.6g} of {:g} {}", sep, e.time(), run.a.duration, u);
  if (!in_dynamic_) t += fmt::format(" ({:.1f} %)", 100.0 * e.time() / run.a.duration);
  t += fmt::format("{}step {}", sep, e.step_count());
  if (!e.reports().empty()) t += fmt::format("{}dt {:.4g} {}", sep, e.reports().back().dt, u);
  t += fmt::format("{}cuts {}", sep, run.run_totals.cuts);
  t += fmt::format("{}wall {}", sep, duration_text(display_.elapsed()));
  if (how) return t;
  if (in_dynamic_) {
    const double latest = phase_start_ + e.model().settings.settle.until;
    return t + fmt::format(fmt::runtime(term ? "{}time left: after {} (at rest, by t = {:g} {})"
                                : "{}time left: known once the {} stage ends (at rest, or at t = {:g} {} at the latest)"),
                           sep, core::stage_kind_name(kind_), latest, u);
  }
  // Mechanism stages come back (the Goodman slope has 21 in its first 24 days), but when is not known.
  const bool mechanisms = std::any_of(e.events().begin(), e.events().end(),
                                      [](const core::StageEvent& v) { return v.kind == core::StageKind::mechanism; });
  if (const auto left = rate_.seconds_left(e.time(), run.a.duration))
    return t + fmt::format(fmt::runtime(term ? "{}~{} left (rate of the last {:.0f} s{})"
                                : "{}time left about {} (at the simulated-time rate of the last {:.0f} s of this stage{})"),
                           sep, duration_text(*left), std::min(kRateWindow, rate_.span()),
                           !mechanisms ? "" : term ? ", + mechanism stages" : "; mechanism stages to come add to it");
  return t + sep + (term ? "time left: measuring" : "time left: measuring the rate of this stage");
}

void RunProgress::start(const Run& run) {
  if (!display_.on()) return;
  rate_ = RateEstimate(kRateWindow);
  for (const auto& j : run.s.joint_sets) creep_ = creep_ || j.law.has_value();
  follow(run, nullptr);
  display_.show(text(run, run.engine.step_count() > 0 ? "resumed" : "start"), true);
}

void RunProgress::step(const Run& run, const core::StepReport& r) {
  if (!display_.on()) return;
  follow(run, &r);
  if (display_.due()) display_.show(text(run, nullptr));
}

void RunProgress::end(const Run& run, const char* how) {
  if (!display_.on()) return;
  display_.show(text(run, how), true);
  display_.finish();
}

}  // namespace rheodda::scene
