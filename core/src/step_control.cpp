// Step control (docs/reference/engine.md, "A step"; docs/reference/step-controls.md): the size
// of each step, cuts after a failed attempt, adaptive creep stepping with its
// rejections, steps onto a damage law's failure, the settling stage and the
// collapse stages of a static analysis.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "engine_impl.hpp"

namespace rheodda::core {

namespace {

/// " (the last of its iterates still changed 2: 1 slipped, 1 stuck)": why an
/// open-close iteration was cut, for the error message (empty when the contact
/// model does not tell the kinds apart).
std::string last_changes(const ContactCheck& c) {
  const ContactChanges& k = c.changes;
  if (k.total() == 0) return {};
  std::string s = " (the last of its iterates still changed " + std::to_string(k.total()) + ":";
  const std::pair<int, const char*> kinds[] = {{k.closed, "closed"},
                                               {k.opened, "opened"},
                                               {k.slipped, "slipped"},
                                               {k.stuck, "stuck"},
                                               {k.refinements, "friction refinements"}};
  const char* sep = " ";
  for (const auto& [n, word] : kinds)
    if (n > 0) s += sep + std::to_string(n) + " " + word, sep = ", ";
  return s + ")";
}

}  // namespace

StepReport Engine::Impl::step(double dt_cap) {
  StepStart start{search_disp, std::nullopt};
  try {
    return step_attempts(dt_cap, start);
  } catch (const StepInterrupted&) {
    // The contacts were abandoned where the attempt stopped (solve_trial; doubling_step
    // restores its snapshot): the engine as after the last accepted step.
    search_disp = start.search_disp;
    if (start.stage) st.stage = std::move(*start.stage);
    throw;
  }
}

StepReport Engine::Impl::step_attempts(double dt_cap, StepStart& start) {
  const Settings& s = model.settings;
  // Settling stage (docs/reference/engine.md, "Settling stage"): steps of at most
  // settle.dt with max_displacement_ratio = settle.max_displacement_ratio, ending on settle.until, no adaptive control.
  bool settle = settling();
  if (settle) dt_cap = std::min(dt_cap, stage_end() - st.time);
  if (s.step_tolerance > 0.0 && !settle) return doubling_step(dt_cap);
  StepReport rep;
  rep.step = st.step;
  // The step the control proposes, and whether the caller's end time shortens it
  // (run_until landing on an output time): see landed_next_dt.
  const double proposed = st.next_dt;
  const double caller_cap = dt_cap;
  bool adaptive = s.creep_tolerance > 0.0 && !settle;
  double load_break = std::numeric_limits<double>::infinity();
  double failure_step = std::numeric_limits<double>::infinity();  // step that reaches a failure
  if (adaptive) {
    load_break = next_load_break();
    dt_cap = std::min(dt_cap, load_break - st.time);
    // A damage law's failure ends a step (docs/reference/rheology-in-dda.md, "Failure"):
    // the time left before the first contact fails at its present stress, 1e-3
    // of it beyond, so that it fails in that step even when its stress moves
    // a little within it (a step right to the failure time can leave a sliver
    // of life, then a sliver of that, and so on: docs/notes/rheology-in-dda.md,
    // "Steps onto a failure").
    failure_step = contacts->time_to_failure() * (1.0 + 1e-3);
  }
  bool capped = dt_cap < st.next_dt;
  double dt = std::min(st.next_dt, dt_cap);
  // Step onto the failure rather than over it, and also when it is within
  // kFailureReach steps (the creep rate diverges there: the error control
  // would shrink the steps in proportion to the time left and never arrive),
  // but never beyond dt_max: a longer step would integrate the stress changes
  // before the failure over one step. The failing step keeps the creep up to
  // the failure (ContactSystem::fail_law).
  const bool within_dt_max = s.dt_max <= 0.0 || failure_step <= s.dt_max;
  if (failure_step < dt || (failure_step <= kFailureReach * dt && failure_step <= dt_cap && within_dt_max))
    dt = failure_step;
  double allowed = max_displacement_ratio_now() * w0;
  const bool watch = s.settle.collapse_dt > 0.0;  // collapse stages (docs/reference/engine.md, "Collapse stages")
  for (;;) {
    const Trial trial = solve_trial(dt, adaptive, rep);
    if (watch && !settle && trial.singular.empty() &&
        (!trial.converged || trial.max_disp > allowed || trial.short_of_rest || collapses(dt))) {
      // A static step that moves as a mechanism: its path would be set by dt
      // and max_displacement_ratio. Cut it down to collapse_dt (locating the onset); at collapse_dt,
      // take the collapse from the step's start in a dynamic stage. Beyond the
      // step limit max_displacement_ratio w0 counts as well: a part sliding at its friction limit
      // gives the inertia term only the unbalanced share of the work, yet
      // moves by that force times dt^2 / 2M; and so does an open-close
      // iteration that does not settle at collapse_dt, where the static steps
      // would otherwise go on cutting into a crawl of the mechanism
      // (docs/reference/engine.md, "Collapse stages"); and so does a static step
      // by cycles that ended short of rest at the step limit.
      contacts->abandon_step();
      if (!start.stage) start.stage = st.stage;  // set back if the step is interrupted
      if (open_collapse_stage(dt, rep)) {
        settle = true;
        adaptive = false;
        capped = true;
        allowed = max_displacement_ratio_now() * w0;
      }
      continue;
    }
    if (trial.converged && trial.max_disp <= allowed) {
      contacts->end_step(views, D);
      double err = 0.0;
      if (adaptive) {
        // Reject and redo a step whose creep error estimate exceeds the
        // tolerance by more than kRejectFactor (docs/reference/step-controls.md, "Adaptive
        // creep stepping"), with the step the estimate asks for: dt 0.9
        // sqrt(tol / err) (local error ~ dt^2), at least dt_cut dt. Never below
        // the first step dt (the control cannot stall on an estimate that does
        // not fall with the step, e.g. at a contact state change), nor more than
        // max_cuts times in one step.
        // The bolts' creep counts as the joints' does (bolt_creep_error.cpp); they
        // commit only when the step is accepted, and the null contact model has
        // nothing to retract.
        err = contacts->creep_error_estimate();
        if (!model.bolts.empty()) err = std::max(err, bolt_set.creep_error_estimate());
        if (err > kRejectFactor * s.creep_tolerance && dt > s.dt &&
            rep.rejections + rep.cuts < s.max_cuts &&
            (contacts->retract_step() || contacts == &null_contacts)) {
          dt = std::max(dt * std::max(s.dt_cut, 0.9 * std::sqrt(s.creep_tolerance / err)), s.dt);
          ++rep.rejections;
          continue;
        }
      }
      rep.dt = dt;
      rep.iterations = trial.iterations;
      rep.max_displacement = trial.max_disp;
      rep.max_penetration = trial.check.max_penetration;
      accept(D, dt, st.step, st.time + dt);
      rep.time = st.time;
      if (settle) update_stage(rep);
      if (adaptive) {
        // Step size from the creep error estimate err of this step.
        rep.creep_error = err;
        rep.creep_state_changes = contacts->creep_state_changes();
        double next = next_adaptive_dt(dt, s.creep_tolerance, err, load_break);
        if (dt == caller_cap && dt < proposed) next = landed_next_dt(next, proposed, rep, load_break);
        // A creeping contact that locked, slid or opened moved load onto its
        // neighbours at once, as a load change does: restart from dt.
        if (s.creep_restart_on_contact_change && rep.creep_state_changes > 0)
          next = std::min(next, s.dt);
        st.next_dt = next;
      } else if (rep.cuts > 0 || !capped) {
        st.next_dt = std::min(settle ? std::min(s.dt, s.settle.dt) : s.dt, dt * s.dt_growth);
      }
      if (settle && !settling()) st.next_dt = s.dt;  // the stage is over: the analysis's dt
      return rep;
    }
    contacts->abandon_step();
    cut(dt, trial, rep);
  }
}

bool Engine::Impl::open_collapse_stage(double& dt, StepReport& rep) {
  const Settings& s = model.settings;
  if (dt > s.settle.collapse_dt * (1.0 + 1e-9)) {  // locate the onset: retry smaller, not below collapse_dt
    if (rep.cuts >= s.max_cuts)
      throw std::runtime_error("step " + std::to_string(st.step) + " at time " + std::to_string(st.time) +
                               ": moves as a mechanism at dt = " + std::to_string(dt) + " after " +
                               std::to_string(rep.cuts) + " cuts, above collapse_dt = " +
                               std::to_string(s.settle.collapse_dt) + " (settings.max_cuts)");
    dt = std::max(dt * s.dt_cut, s.settle.collapse_dt);
    ++rep.cuts;
    return false;
  }
  // At most as long as the settling stage; at least over the failed step.
  start_stage(StageKind::mechanism, s.settle.until, dt);
  rep.collapse_stage = true;
  dt = std::min(s.settle.dt, stage_end() - st.time);
  return true;
}

double Engine::Impl::next_load_break() const {
  // Adaptive stepping (either control): steps end on the point-load sample
  // times (where the loads change their course), and the step after one
  // restarts from dt. Sample times closer than dt/1000 after the step start (a
  // load jump given as a steep ramp) fall inside the step.
  const double eps = std::max(1e-12 * std::max(1.0, std::abs(st.time)), 1e-3 * model.settings.dt);
  double t = std::numeric_limits<double>::infinity();
  for (const auto& pl : model.point_loads)
    for (const auto& ls : pl.history)
      if (ls.time > st.time + eps) t = std::min(t, ls.time);
  if (model.water.active()) t = std::min(t, next_water_break(model.water, st.time + eps));  // water.hpp
  return t;
}

double Engine::Impl::landed_next_dt(double next, double proposed, const StepReport& rep, double load_break) const {
  // A step shortened only to end on the caller's end time (an output time of
  // `rheodda run`, docs/reference/outputs.md "Output times") says little about the next:
  // its error estimate at the short step lets the control grow it by 2 at most. The
  // next step takes up the one the control had proposed, as Boost.Odeint's
  // integrate_times does after an observation point ("continue with the original step
  // size if dt was reduced due to observation"): max(proposed, what this step asks).
  // Not after a rejection or a cut (the proposal failed), nor at a load break (the
  // control restarts from dt there).
  if (rep.rejections > 0 || rep.cuts > 0) return next;
  if (st.time >= load_break - 1e-12 * std::max(1.0, std::abs(load_break))) return next;
  return std::max(next, proposed);
}

double Engine::Impl::next_adaptive_dt(double dt, double tolerance, double err,
                                      double load_break) const {
  // Local error ~ dt^2 for both first-order estimates (the creep estimate and
  // the step-doubling difference): dt' = dt min(2, max(dt_cut, 0.9 sqrt(tol /
  // err))), capped by dt_max; dt again after a load break.
  const Settings& s = model.settings;
  const double factor =
      err > 0.0 ? std::clamp(0.9 * std::sqrt(tolerance / err), s.dt_cut, 2.0) : 2.0;
  double next = dt * factor;
  if (s.dt_max > 0.0) next = std::min(next, s.dt_max);
  if (st.time >= load_break - 1e-12 * std::max(1.0, std::abs(load_break))) next = s.dt;
  return next;
}

bool Engine::Impl::take(double dt, StepReport& rep, Trial& trial) {
  trial = solve_trial(dt, false, rep);
  if (trial.converged && trial.max_disp <= max_displacement_ratio_now() * w0) {
    contacts->end_step(views, D);
    accept(D, dt, st.step, st.time + dt);
    return true;
  }
  contacts->abandon_step();
  return false;
}

void Engine::Impl::cut(double& dt, const Trial& trial, StepReport& rep) const {
  const Settings& s = model.settings;
  if (rep.cuts >= s.max_cuts && !trial.singular.empty())
    throw SingularSystemError("step " + std::to_string(st.step) + " at time " + std::to_string(st.time) + ": " +
                                  trial.singular + " after " + std::to_string(rep.cuts) +
                                  " cuts of dt (settings.max_cuts)",
                              trial.singular_block, trial.singular_unknown);
  if (rep.cuts >= s.max_cuts)
    throw std::runtime_error(
        "step " + std::to_string(st.step) + " at time " + std::to_string(st.time) + ": " +
        (trial.converged ? "displacement " + std::to_string(trial.max_disp) +
                               " exceeds max_displacement_ratio * w0 = " + std::to_string(max_displacement_ratio_now() * w0)
                         : !trial.unsettled.empty() ? trial.unsettled
                                                   : "open-close iteration did not converge" + last_changes(trial.check)) +
        " after " + std::to_string(rep.cuts) + " cuts of dt (settings.max_cuts)");
  dt *= s.dt_cut;
  ++rep.cuts;
}

Engine::Engine(Model model) : impl_(std::make_unique<Impl>()) {
  impl_->model = std::move(model);
  impl_->contacts = &impl_->null_contacts;
  impl_->validate();
  impl_->initialise();
}

Engine::Engine(Model model, ContactModel& contacts) : impl_(std::make_unique<Impl>()) {
  impl_->model = std::move(model);
  impl_->contacts = &contacts;
  impl_->validate();
  impl_->initialise();
}

Engine::~Engine() = default;

}  // namespace rheodda::core
