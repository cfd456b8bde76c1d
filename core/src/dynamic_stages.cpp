// Dynamic stages of a static analysis (docs/reference/engine.md, "Dynamic stages"): the
// settling stage at the start (SettleStage::until) and the stages that take
// a collapse dynamically (SettleStage::collapse_dt). A stage carries velocity with
// settle.dt and settle.max_displacement_ratio; it ends at rest - after a step whose kinetic
// energy is below SettleStage::rest_tolerance of the work gravity and the
// loads did over the stage (with the explicit step and SettleStage::force_ratio: after a
// step whose unbalanced-force ratio is below it) - or at its longest, settle.until from its start.
// Each stage is recorded as a StageEvent when it ends.
#include <algorithm>
#include <cmath>

#include "engine_impl.hpp"

namespace rheodda::core {

namespace {

/// A stage ends at rest no sooner than after this many steps: the step that
/// opens a collapse stage starts at rest, with no kinetic energy and no work
/// done yet [-].
constexpr int kMinStageSteps = 2;

}  // namespace

const char* stage_kind_name(StageKind k) {
  switch (k) {
    case StageKind::settling: return "settling";
    case StageKind::mechanism: return "mechanism";
  }
  return "?";
}

void Engine::Impl::start_stage(StageKind kind, double length, double shortest) {
  StageState& g = st.stage;
  g.until = st.time + length;
  g.not_before = st.time + shortest;
  g.open = true;
  g.motion_kinetic = 0.0;
  g.event = StageEvent{};
  g.event.kind = kind;
  g.event.start_time = st.time;
  g.event.start_step = st.step;
  g.start_vertices.resize(st.blocks.size());
  for (std::size_t k = 0; k < st.blocks.size(); ++k) g.start_vertices[k] = st.blocks[k].vertices;
}

void Engine::Impl::update_stage(const StepReport& rep) {
  StageState& g = st.stage;
  if (!g.open) return;
  const Settings& s = model.settings;
  StageEvent& e = g.event;
  const EnergyFlows& f = st.energy.step;
  ++e.steps;
  e.end_time = rep.time;
  e.work += f.work_gravity + f.work_loads;
  e.energy_dissipated += f.dissipation_friction + f.dissipation_creep + f.dissipation_integration +
                         f.dissipation_contact_damping + f.dissipation_block_damping +
                         f.dissipation_contact_closing + f.dissipation_contact_release;
  const double kinetic = st.energy.stored.kinetic;
  e.kinetic_energy_peak = std::max(e.kinetic_energy_peak, kinetic);
  e.kinetic_energy_end = kinetic;
  // At rest: not before the gravity ramp has ended (a slow load keeps the
  // kinetic energy small while it rises), nor before the end of the static step
  // that found the mechanism (the stage starts at rest, before the cause of
  // the motion may have come), and relative to the energy the stage had to store or
  // dissipate: the largest of the work gravity and the loads did over it, the energy it
  // dissipated and its kinetic energy's peak. The work alone is that energy in a settling
  // stage; a stage that releases stored energy (a model edit that excavates, a mechanism
  // whose failing contacts let their springs go) can move while gravity does little or
  // negative work, and would never be at rest against it.
  const double ramp_end = s.settle.gravity_ramp;
  const double not_before = std::max(ramp_end, g.not_before);
  const bool late_enough = st.time >= not_before - 1e-12 * std::max(1.0, std::abs(not_before));
  const double reference = std::max({e.work, e.energy_dissipated, e.kinetic_energy_peak});
  // An explicit step with settle.force_ratio is at rest by its unbalanced-force ratio
  // (explicit_step.cpp (8)), UDEC's test: the kinetic energy of density-scaled masses, or of
  // a part that creeps along at its friction limit, says little of the forces' balance.
  const bool by_force = s.settle.force_ratio > 0.0 && rep.cycles > 0;
  // The kinetic energy read is the step's motion's, (D/dt)^T M (D/dt) / 2 (engine.cpp), not
  // the end velocity's: in Shi's scheme (v' = 2 D/dt - v) a stiff mode the step does not
  // resolve (omega dt >> 1) is held by its spring, D ~ 0, while its velocity changes sign
  // from step to step with no loss (v' = -v): kinetic energy that moves nothing and that
  // the stage's damping cannot reach. Where the step resolves the motion the two agree.
  // And not rising: a stage released from rest speeds up over its first steps, and its
  // kinetic energy is small then only because the motion has not yet come.
  const bool rests = by_force ? cycle_force_ratio <= s.settle.force_ratio
                              : reference > 0.0 && step_motion_kinetic <= s.settle.rest_tolerance * reference &&
                                    step_motion_kinetic <= g.motion_kinetic;
  g.motion_kinetic = step_motion_kinetic;
  if (settling() && s.settle.rest_tolerance > 0.0 && e.steps >= kMinStageSteps && late_enough && rests) {
    e.at_rest = true;
    g.until = st.time;  // the stage is over: the next step is static
  }
  if (settling()) return;
  // The stage has ended (at rest or at its longest): its event.
  const double reach = s.settle.max_displacement_ratio * w0;  // the stage's step limit [length]
  for (std::size_t k = 0; k < st.blocks.size(); ++k) {
    double moved = 0.0;
    const auto& v = st.blocks[k].vertices;
    const auto& v0 = g.start_vertices[k];
    for (std::size_t i = 0; i < v.size() && i < v0.size(); ++i) moved = std::max(moved, (v[i] - v0[i]).norm());
    e.largest_displacement = std::max(e.largest_displacement, moved);
    if (moved > reach) ++e.blocks_involved;
  }
  st.events.push_back(e);
  g.open = false;
  g.start_vertices.clear();
}

}  // namespace rheodda::core
