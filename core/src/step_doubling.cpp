// Step doubling with local (Richardson) extrapolation (docs/guide/choosing-step-controls.md,
// "Step doubling"): the adaptive control of Settings::step_tolerance.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "engine_impl.hpp"

namespace rheodda::core {

StepReport Engine::Impl::doubling_step(double dt_cap) {
  // Step doubling with local extrapolation (docs/reference/step-controls.md, "Step
  // doubling"). The step y_c of dt and two steps y_f of dt/2 from the same
  // state: the DDA step is first order, y_c - y = C dt^2 + O(dt^3) and
  // y_f - y = C dt^2/2 + O(dt^3), so err = max |y_f - y_c| over the block
  // vertices estimates the local error of y_f, and 2 y_f - y_c (Richardson)
  // is the state with local error O(dt^3): a second-order step.
  const Settings& s = model.settings;
  StepReport rep;
  rep.step = st.step;
  const double load_break = next_load_break();
  const double proposed = st.next_dt;
  const double caller_cap = dt_cap;  // the caller's end time shortens the step (landed_next_dt)
  dt_cap = std::min(dt_cap, load_break - st.time);
  double dt = std::min(st.next_dt, dt_cap);
  const std::vector<BlockState> start_blocks = st.blocks;
  const int start_step = st.step;
  const double start_time = st.time;
  const std::size_t start_samples =
      st.measurements.empty() ? 0 : st.measurements.front().size();
  const std::unique_ptr<ContactSnapshot> start_contacts = contacts->snapshot();
  const EnergyBalance start_energy = st.energy;
  const std::vector<BoltState> start_bolts = st.bolts;  // the bolts' states (bolt_doubling.cpp)
  if (!start_contacts)
    throw std::runtime_error(
        "settings.step_tolerance: the contact model cannot copy its state (step doubling needs "
        "ContactModel::snapshot)");
  auto restart = [&] {
    st.blocks = start_blocks;
    st.step = start_step;
    st.time = start_time;
    for (auto& m : st.measurements) m.resize(start_samples);
    refresh_geometry();
    contacts->restore(*start_contacts);
    st.energy = start_energy;
    st.bolts = start_bolts;
  };
  std::vector<BlockState> coarse;
  std::vector<BoltState> coarse_bolts;
  EnergyFlows coarse_energy;
  try {
    for (;;) {
      Trial trial;
      bool ok = take(dt, rep, trial);
      double coarse_disp = trial.max_disp;
      int iterations = trial.iterations;
      std::unique_ptr<ContactSnapshot> coarse_contacts;
      if (ok) {
        coarse = st.blocks;
        coarse_bolts = st.bolts;
        coarse_energy = st.energy.step;
        coarse_contacts = contacts->snapshot();
        restart();
        ok = take(0.5 * dt, rep, trial);
        iterations += trial.iterations;
        if (ok) {
          ok = take(0.5 * dt, rep, trial);
          iterations += trial.iterations;
        }
      }
      if (!ok) {
        restart();
        cut(dt, trial, rep);
        continue;
      }
      double err = 0.0;
      for (std::size_t k = 0; k < st.blocks.size(); ++k)
        for (std::size_t i = 0; i < st.blocks[k].vertices.size(); ++i)
          err = std::max(err, (st.blocks[k].vertices[i] - coarse[k].vertices[i]).squaredNorm());
      err = std::sqrt(err);
      // A bolt's creep moves no vertex where its length is held: the difference
      // of its creep elongation counts as well [length].
      if (!model.bolts.empty()) err = std::max(err, BoltSet::creep_difference(st.bolts, coarse_bolts));
      // Reject and redo a step whose estimate exceeds the tolerance by more than
      // kRejectFactor, as the creep control does (not below dt, at most max_cuts
      // times in one step).
      if (err > kRejectFactor * s.step_tolerance && dt > s.dt &&
          rep.rejections + rep.cuts < s.max_cuts) {
        restart();
        dt = std::max(dt * std::max(s.dt_cut, 0.9 * std::sqrt(s.step_tolerance / err)), s.dt);
        ++rep.rejections;
        continue;
      }
      // Richardson: 2 y_f - y_c for the blocks and, through the contact model,
      // for every contact quantity; only when both runs end with the same
      // contacts in the same states (else y_f stands, first order).
      rep.extrapolated = s.step_extrapolation && BoltSet::same_modes(st.bolts, coarse_bolts) &&
                         contacts->extrapolate(*coarse_contacts);
      if (rep.extrapolated) {
        for (std::size_t k = 0; k < st.blocks.size(); ++k) {
          BlockState& b = st.blocks[k];
          const BlockState& c = coarse[k];
          for (std::size_t i = 0; i < b.vertices.size(); ++i)
            b.vertices[i] = 2.0 * b.vertices[i] - c.vertices[i];
          b.map_A = 2.0 * b.map_A - c.map_A;
          b.map_b = 2.0 * b.map_b - c.map_b;
          b.stress = 2.0 * b.stress - c.stress;
          b.velocity = 2.0 * b.velocity - c.velocity;
          b.acceleration = 2.0 * b.acceleration - c.acceleration;
        }
        refresh_geometry();
        if (!model.bolts.empty()) BoltSet::extrapolate(model, st.blocks, st.bolts, coarse_bolts);
      }
      EnergyAccount::finish_doubling(energy_inputs(), start_energy, coarse_energy, rep.extrapolated,
                                     contacts->energy(), st.energy, BoltSet::stored_energy(model, st.bolts));
      // One step of dt for the outside: one report, one measurement sample.
      st.step = start_step + 1;
      st.time = start_time + dt;
      for (auto& m : st.measurements) m.resize(start_samples);
      record_measurements(start_step);
      rep.dt = dt;
      rep.time = st.time;
      rep.iterations = iterations;
      rep.max_displacement = coarse_disp;
      rep.max_penetration = trial.check.max_penetration;
      rep.step_error = err;
      // Not below dt (the first step): where the estimate does not fall with the
      // step - e.g. the quasi-static settling of a static analysis under gravity
      // applied at once, whose per-step motion is g dt^2 whatever the creep - the
      // control would follow that path in ever smaller steps.
      double next = next_adaptive_dt(dt, s.step_tolerance, err, load_break);
      if (dt == caller_cap && dt < proposed) next = landed_next_dt(next, proposed, rep, load_break);
      st.next_dt = std::max(next, s.dt);
      return rep;
    }
  } catch (const StepInterrupted&) {
    restart();  // a half step may have been accepted: back to the step's start, contacts too
    throw;
  }
}

}  // namespace rheodda::core
