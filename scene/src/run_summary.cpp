// What a run reports (docs/reference/outputs.md, "summary.json"): RunResult's totals,
// summary.json (rewritten at every frame and when the run ends), events.csv of
// a run with a settling stage, the warnings of a completed run, and the
// message of a failed one.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <new>
#include <nlohmann/json.hpp>

#include "rheodda/core/solver.hpp"
#include "rheodda/version.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

void collect_totals(Run& run) {
  const SceneDescription& s = run.s;
  const core::Engine& engine = run.engine;
  const RunTotals& run_totals = run.run_totals;
  RunResult& result = run.result;
  result.creep.clear();
  for (std::size_t j = 0; j < s.joint_sets.size(); ++j)
    if (run.contacts.joint_sets()[j].law) {
      const contact::CreepCounters& k = run.contacts.creep_counters()[j];
      result.creep.push_back(
          {s.joint_sets[j].name, k.contacts, k.contact_time, k.failures, run_totals.first_failure[j]});
    }
  result.steps = engine.step_count();
  result.time = engine.time();
  result.cuts = run_totals.cuts;
  result.redone = run_totals.redone;
  result.extrapolated = run_totals.extrapolated;
  result.max_penetration = run_totals.max_penetration;
  result.mechanism = run_totals.mechanism;
  if (result.mechanism.static_analysis)
    result.mechanism.inertia_share = core::inertia_share(engine.energy().total);
  result.frames = run.a.frames ? run.frames_done : 0;  // analysis.frames: false writes none
  result.wall_seconds = run.earlier_wall + std::chrono::duration<double>(Clock::now() - run.wall_start).count();
}

void write_summary(Run& run, const std::string& status, const std::string& error) {
  const SceneDescription& s = run.s;
  const Analysis& a = run.a;
  const core::Engine& engine = run.engine;
  const RunResult& result = run.result;
  collect_totals(run);
  json j;
  j["program"] = kProgramVersion;
  j["status"] = status;
  if (!error.empty()) j["error"] = error;
  j["units"] = {{"length", s.units.length}, {"force", s.units.force}, {"time", s.units.time},
                {"stress", s.units.stress()}};
  j["time"] = result.time;
  j["duration"] = a.duration;
  j["steps"] = result.steps;
  j["cuts"] = result.cuts;
  j["redone"] = result.redone;
  j["extrapolated_steps"] = result.extrapolated;
  j["max_penetration"] = result.max_penetration;
  {
    // What the open-close checks changed over the run, by kind (every iterate
    // of every attempt, cut ones included): where the iterations went.
    const core::ContactChanges& c = run.run_totals.contact_changes;
    j["contact_changes"] = {{"closed", c.closed},   {"opened", c.opened},
                            {"slipped", c.slipped}, {"stuck", c.stuck},
                            {"refinements", c.refinements}};
  }
  {
    // The energy balance since t = 0 (docs/reference/engine.md, "Energy balance").
    const core::EnergyBalance& en = engine.energy();
    auto stored = [](const core::StoredEnergy& e) {
      return json{{"kinetic", e.kinetic},       {"strain", e.strain},
                  {"fixed", e.fixed},           {"contact_normal", e.contact_normal},
                  {"contact_shear", e.contact_shear}, {"total", e.total()}};
    };
    const core::EnergyFlows& t = en.total;
    j["energy"] = {{"initial", stored(en.initial)},
                   {"final", stored(en.stored)},
                   {"work_gravity", t.work_gravity},
                   {"work_loads", t.work_loads},
                   {"work_contact_restart", t.work_contact_restart},
                   {"dissipation_friction", t.dissipation_friction},
                   {"dissipation_creep", t.dissipation_creep},
                   {"dissipation_integration", t.dissipation_integration},
                   {"integration_inertia", t.integration_inertia},
                   {"dissipation_contact_damping", t.dissipation_contact_damping},
                   {"dissipation_block_damping", t.dissipation_block_damping},
                   {"dissipation_contact_closing", t.dissipation_contact_closing},
                   {"dissipation_contact_release", t.dissipation_contact_release},
                   {"dissipation_edits", t.dissipation_edits},
                   {"residual", t.residual},
                   {"scale", en.initial.total() + t.scale},
                   {"relative_residual", en.relative_residual()},
                   {"max_relative_residual", en.max_relative_residual}};
  }
  if (result.mechanism.static_analysis) {
    // Mechanism motion of a static analysis (docs/reference/engine.md, "Mechanisms in static analysis").
    const auto& m = result.mechanism;
    auto time_or_null = [](double t) { return std::isnan(t) ? json(nullptr) : json(t); };
    j["static_mechanism"] = {{"inertia_share", m.inertia_share},
                             {"steps", m.steps},
                             {"first_time", time_or_null(m.first_time)},
                             {"last_time", time_or_null(m.last_time)},
                             {"collapse_stages", m.collapse_stages}};
  } else {
    j["static_mechanism"] = nullptr;
  }
  if (a.has_settle()) {
    // Dynamic stages (docs/reference/engine.md, "Dynamic stages"): summary.json's
    // "events" and the events table events.csv, rewritten whole each time.
    j["events"] = json::array();
    std::string csv =
        "kind,start_time,end_time,start_step,steps,at_rest,blocks_involved,largest_displacement,"
        "kinetic_energy_peak,kinetic_energy_end,work,energy_dissipated\n";
    for (const core::StageEvent& e : engine.events()) {
      j["events"].push_back({{"kind", core::stage_kind_name(e.kind)},
                             {"start_time", e.start_time},
                             {"end_time", e.end_time},
                             {"start_step", e.start_step},
                             {"steps", e.steps},
                             {"at_rest", e.at_rest},
                             {"blocks_involved", e.blocks_involved},
                             {"largest_displacement", e.largest_displacement},
                             {"kinetic_energy_peak", e.kinetic_energy_peak},
                             {"kinetic_energy_end", e.kinetic_energy_end},
                             {"work", e.work},
                             {"energy_dissipated", e.energy_dissipated}});
      csv += fmt::format("{},{:.10g},{:.10g},{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n",
                         core::stage_kind_name(e.kind), e.start_time, e.end_time, e.start_step, e.steps,
                         e.at_rest ? 1 : 0, e.blocks_involved, e.largest_displacement, e.kinetic_energy_peak,
                         e.kinetic_energy_end, e.work, e.energy_dissipated);
    }
    write_file_atomic((fs::path(run.out) / "events.csv").string(), csv);
    run.result.events = engine.events();
  }
  if (!s.stages.empty()) {  // docs/reference/stages.md: the stages that have begun
    j["stages"] = json::array();
    for (const AppliedStage& st : run.stage_run.applied)
      j["stages"].push_back({{"name", st.name}, {"time", st.time}, {"step", st.step}, {"actions", st.actions}});
  }
  j["frames"] = result.frames;
  j["wall_seconds"] = result.wall_seconds;
  j["resumed_from_step"] = result.resumed_from_step;
  j["steps_computed"] = result.steps_computed;
  j["warnings"] = result.warnings;
  // Where each joint set's law acted (docs/reference/outputs.md, "summary.json").
  j["creep"] = json::object();
  for (const auto& c : result.creep)
    j["creep"][c.joint_set] = {{"contacts", c.contacts},
                               {"contact_time", c.contact_time},
                               {"failures", c.failures},
                               {"first_failure_time", std::isnan(c.first_failure_time)
                                                          ? json(nullptr)
                                                          : json(c.first_failure_time)}};
  {
    // The linear solver actually used (automatic resolved) and its work since
    // this process started (a resumed run counts from the resume).
    const auto& ss = engine.solver_stats();
    const core::SolverKind used =
        ss.amg_fallback_solve >= 0
            ? core::SolverKind::cholmod
            : core::LinearSolver::resolve(engine.model().settings.solver, engine.block_count());
    j["solver"] = {{"used", std::string(core::linear_solver_entry(used).word)},
                   {"solves", ss.solves},
                   {"cg_iterations", ss.pcg_iterations},
                   {"analyses", ss.analyses},
                   {"amg_fallback_solve", ss.amg_fallback_solve}};
  }
  j["measurement_points"] = json::array();
  for (const auto& mp : s.measurement_points) j["measurement_points"].push_back(mp.name);
  j["recorded_joint_sets"] = json::array();
  for (int k : run.recorded) j["recorded_joint_sets"].push_back(s.joint_sets[k].name);
  j["block_names"] = json::array();
  for (const auto& b : s.blocks) j["block_names"].push_back(b.name);
  // The inputs are the same at every frame: serialised once, spliced in.
  std::string text = j.dump(2);
  text.pop_back();  // the closing brace
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  text += ",\n  \"inputs\": " + run.inputs_text + ",\n  \"scene_text\": " + run.scene_text_json + "\n}\n";
  write_file_atomic((fs::path(run.out) / "summary.json").string(), text);
}

void add_end_warnings(Run& run) {
  const SceneDescription& s = run.s;
  RunResult& result = run.result;
  for (const auto& c : result.creep)
    if (c.contacts == 0)
      result.warnings.push_back(fmt::format(
          "joint set '{}' has a creep law but none of its contacts crept (none stayed locked through a step)",
          c.joint_set));
  if (const auto& m = result.mechanism; m.static_analysis && m.steps > 0 &&
                                                 m.inertia_share > core::kMechanismRunShare)
    result.warnings.push_back(fmt::format(
        "static analysis: parts of the model moved as a mechanism in {} steps (t = {:g} to {:g} {}), held only by "
        "the steps' inertia ({:.1f} % of the work of gravity and loads): how far depends on dt and "
        "max_displacement_ratio. Check with both halved (`rheodda check {} --refine`) or run that phase dynamically "
        "(docs/reference/engine.md, \"Mechanisms in static analysis\"){}",
        m.steps, m.first_time, m.last_time, s.units.time, 100.0 * m.inertia_share,
        s.file.empty() ? std::string("SCENE") : s.file,
        // Settling under gravity applied at once: the usual case, with its remedy.
        m.first_step >= 0 && m.first_step < 10 && !s.analysis.has_settle()
            ? "; from the first steps: a settling stage (analysis.settle) starts every run settled"
            : ""));
}

std::string failure_text(const Run& run, const std::exception& e) {
  const SceneDescription& s = run.s;
  const core::Engine& engine = run.engine;
  std::string error = e.what();
  if (dynamic_cast<const std::bad_alloc*>(&e))
    error = fmt::format("out of memory (a model of {} blocks needs more memory than is available to this "
                        "process; docs/notes/performance.md gives the memory a run needs per block)",
                        engine.block_count());
  if (const auto* se = dynamic_cast<const core::SingularSystemError*>(&e);
      se && se->block >= 0 && se->block < static_cast<int>(s.blocks.size())) {
    // Say which block, and what held it: its contacts at the start of the failed step.
    int closed = 0, total = 0;
    for (const auto& c : run.contacts.contacts())
      if (c.key.vblock == se->block || c.key.eblock == se->block) {
        ++total;
        if (c.state != contact::ContactState::open) ++closed;
      }
    error += fmt::format(
        ". That is block '{}'{}: {} of its {} contacts were closed at the start of the step{}. The matrix "
        "stays positive definite while every block is held (a closed contact, a fixed point, or the inertia "
        "of the step): look at that block's support and contacts in the last frame (rheodda plot), or try a "
        "smaller dt",
        s.blocks[se->block].name,
        se->unknown >= 0 ? fmt::format(" (its unknown {})", core::unknown_name(se->unknown)) : std::string(),
        closed, total, s.blocks[se->block].fixed ? " (it is fixed)" : "");
  }
  return error;
}

}  // namespace rheodda::scene
