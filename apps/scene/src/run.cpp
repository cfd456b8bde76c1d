#include "rheodda/scene/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/solver.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/output.hpp"

namespace rheodda::scene {
namespace {

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

/// Thrown by the step observer to leave Engine::run_until between two steps.
struct StopAfterStep {};

/// Exact text of a double (C99 hex float), for bit-for-bit comparisons on resume.
std::string hex(double v) { return fmt::format("{:a}", v); }
double unhex(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

json scene_json(const SceneDescription& s) {
  json j;
  j["file"] = s.file;
  j["title"] = s.title;
  j["units"] = {{"length", s.units.length}, {"force", s.units.force}, {"time", s.units.time},
                {"stress", s.units.stress()}};
  const Analysis& a = s.analysis;
  j["analysis"] = {{"type", analysis_type_name(a.type)},
                   {"duration", a.duration},
                   {"dt", a.dt},
                   {"dt_growth", a.dt_growth},
                   {"dt_cut", a.dt_cut},
                   {"max_cuts", a.max_cuts},
                   {"creep_tolerance", a.creep_tolerance},
                   {"step_tolerance", a.step_tolerance},
                   {"step_extrapolation", a.step_extrapolation},
                   {"dt_max", a.dt_max},
                   {"creep_restart_on_contact_change", a.creep_restart_on_contact_change},
                   {"max_displacement_ratio", a.max_displacement_ratio},
                   {"dynamic_ratio", a.dynamic_ratio},
                   {"time_integration", time_integration_name(a.time_integration)},
                   {"scheme", scheme_text(a)},
                   {"penalty", a.penalty},
                   {"shear_normal_ratio", a.shear_normal_ratio},
                   {"search_factor", a.search_factor},
                   {"angle_tolerance", a.angle_tolerance},
                   {"penetration_ratio", a.penetration_ratio},
                   {"stick_keeps_force", a.stick_keeps_force},
                   {"friction_tolerance", a.friction_tolerance},
                   {"force_resolution", a.force_resolution},
                   {"max_flips", a.max_flips},
                   {"max_refinements", a.max_refinements},
                   {"penalty_raise", a.penalty_raise},
                   {"penalty_max_factor", a.penalty_max_factor},
                   {"open_close_limit", a.open_close_limit},
                   {"fixed_point_stiffness", a.fixed_point_stiffness},
                   {"solver", solver_name(a.solver)},
                   {"solver_tolerance", a.solver_tolerance},
                   {"solver_max_iterations", a.solver_max_iterations},
                   {"output_interval", a.output_interval},
                   {"gravity", a.gravity}};
  for (const auto& m : s.materials)
    j["materials"][m.name] = {{"density", m.density},
                              {"young_modulus", m.young_modulus},
                              {"poisson_ratio", m.poisson_ratio},
                              {"plane", plane_name(m.plane)}};
  for (const auto& js : s.joint_sets) {
    json o = {{"friction_angle", js.friction_angle},
              {"cohesion", js.cohesion},
              {"tensile_strength", js.tensile_strength}};
    o["normal_stiffness"] = js.normal_stiffness ? json(*js.normal_stiffness) : json(nullptr);
    o["shear_stiffness"] = js.shear_stiffness ? json(*js.shear_stiffness) : json(nullptr);
    if (js.law) {
      json law = {{"name", js.law->name}};
      for (const auto& [k, v] : js.law->parameters) law[k] = v;
      o["law"] = law;
    } else {
      o["law"] = nullptr;
    }
    o["record"] = js.record;
    j["joint_sets"][js.name] = o;
  }
  j["blocks"] = json::array();
  for (const auto& b : s.blocks) {
    json e = {{"name", b.name}, {"material", s.materials[b.material].name}, {"polygon", b.polygon}};
    json sets = json::array();
    for (int k : b.edge_joint_set) sets.push_back(s.joint_sets[k].name);
    e["edge_joint_sets"] = sets;
    e["fixed"] = b.fixed;
    e["initial_stress"] = b.initial_stress;
    e["initial_velocity"] = b.initial_velocity;
    j["blocks"].push_back(e);
  }
  j["fixed_points"] = json::array();
  for (const auto& f : s.fixed_points) j["fixed_points"].push_back({{"point", f.point}, {"block", s.blocks[f.block].name}});
  j["loads"] = json::array();
  for (const auto& l : s.loads)
    j["loads"].push_back({{"point", l.at.point}, {"block", s.blocks[l.at.block].name}, {"history", l.history}});
  j["measurement_points"] = json::array();
  for (const auto& m : s.measurement_points)
    j["measurement_points"].push_back({{"name", m.name}, {"point", m.at.point}, {"block", s.blocks[m.at.block].name}});
  return j;
}

/// Digest of everything the engine evolves (vertices, stresses, velocities, time).
std::uint64_t state_digest(const core::Engine& e) {
  std::uint64_t h = fnv1a(nullptr, 0);
  const double t = e.time();
  h = fnv1a(&t, sizeof t, h);
  for (int b = 0; b < e.block_count(); ++b) {
    const core::BlockState& s = e.block(b);
    for (const auto& v : s.vertices) h = fnv1a(v.data(), 2 * sizeof(double), h);
    h = fnv1a(s.stress.data(), 3 * sizeof(double), h);
    h = fnv1a(s.velocity.data(), 6 * sizeof(double), h);
  }
  return h;
}

std::string units_comment(const Units& u) {
  return fmt::format("# units: length={} force={} time={} stress={}\n", u.length, u.force, u.time, u.stress());
}

}  // namespace

RunResult run_scene(const SceneDescription& s, const std::string& scene_text, const RunOptions& opt) {
  namespace fs = std::filesystem;
  const auto wall_start = Clock::now();
  RunResult result;
  const Analysis& a = s.analysis;
  const std::string out = opt.out_dir;
  const std::string scene_hash = fmt::format("{:016x}", fnv1a(scene_text.data(), scene_text.size()));

  BuiltScene built = build_scene(s);
  result.warnings = built.warnings;
  std::unique_ptr<contact::ContactSystem> contacts_ptr;
  try {
    contacts_ptr = std::make_unique<contact::ContactSystem>(built.joint_sets, built.contact_settings);
  } catch (const std::invalid_argument& e) {
    // The contact layer names the joint set by index ("joint set 2 ..."): point at it in the scene.
    SourceLocation where = a.where;
    std::string key = "analysis";
    int index = -1;
    if (std::sscanf(e.what(), "joint set %d", &index) == 1 && index >= 0 &&
        index < static_cast<int>(s.joint_sets.size())) {
      where = s.joint_sets[index].where;
      key = "joint_sets." + s.joint_sets[index].name;
    }
    throw SceneError(s.file, where, key, e.what());
  }
  contact::ContactSystem& contacts = *contacts_ptr;
  core::ContactAdapter adapter(contacts);
  std::unique_ptr<core::Engine> engine_ptr;
  try {
    engine_ptr = std::make_unique<core::Engine>(built.model, adapter);
  } catch (const core::ModelError& e) {
    // The engine's key names a block ("blocks[3]...") or a setting: point at the scene's entry.
    SourceLocation where = a.where;
    int index = -1;
    if (std::sscanf(e.key().c_str(), "blocks[%d]", &index) == 1 && index >= 0 &&
        index < static_cast<int>(s.blocks.size()))
      where = s.blocks[index].where;
    throw SceneError(s.file, where, e.key(), e.what());
  }
  core::Engine& engine = *engine_ptr;
  // Only now that the model is accepted: a refused scene leaves nothing behind.
  fs::create_directories(fs::path(out) / "frames");

  // Initial vertex positions, for the displacement field of the frames.
  std::vector<std::vector<core::Vec2>> initial;
  for (int b = 0; b < engine.block_count(); ++b) {
    const auto v = engine.vertices(b);
    initial.emplace_back(v.begin(), v.end());
  }

  // Output frame times: k * output_interval, the last one landing on duration.
  std::vector<double> frame_times;
  const long long nframes = static_cast<long long>(std::ceil(a.duration / a.output_interval - 1e-9));
  for (long long k = 0; k <= nframes; ++k) frame_times.push_back(std::min(double(k) * a.output_interval, a.duration));

  // Per-step rows of history.csv.
  std::vector<int> recorded;
  for (std::size_t j = 0; j < s.joint_sets.size(); ++j)
    if (s.joint_sets[j].record) recorded.push_back(static_cast<int>(j));
  auto history_row = [&](const core::StepReport* r) {
    std::string row = fmt::format("{:.10g},{},{:.10g},{},{}", engine.time(), engine.step_count(),
                                  r ? r->dt : 0.0, r ? r->cuts : 0, r ? r->iterations : 0);
    for (const auto& mp : s.measurement_points) {
      const core::Vec2 d = engine.point_displacement(mp.at.block, {mp.at.point[0], mp.at.point[1]});
      row += fmt::format(",{:.10g},{:.10g}", d.x(), d.y());
    }
    for (int j : recorded) {
      int n = 0;
      double shear = 0.0, force = 0.0;
      for (const auto& c : contacts.contacts())
        if (c.joint_set == j && c.state != contact::ContactState::open) {
          ++n;
          shear += c.shear_displacement;
          force += c.shear_force;
        }
      row += n ? fmt::format(",{},{:.10g},{:.10g}", n, shear / n, force / n) : fmt::format(",0,,");
    }
    // Energy balance (docs/engine.md, "Energy balance"): stored energies now, flows since t = 0.
    const core::EnergyBalance& en = engine.energy();
    const core::StoredEnergy& st = en.stored;
    const core::EnergyFlows& fl = en.total;
    for (const double v : {st.kinetic, st.strain, st.fixed, st.contact_normal, st.contact_shear,
                           fl.work_gravity, fl.work_loads, fl.work_contact_restart,
                           fl.dissipation_friction, fl.dissipation_creep, fl.dissipation_integration,
                           fl.dissipation_contact_damping, fl.dissipation_contact_closing,
                           fl.dissipation_contact_release, fl.residual, en.relative_residual()})
      row += fmt::format(",{:.10g}", v);
    return row + '\n';
  };
  std::string history_header = "time,step,dt,cuts,iterations";
  for (const auto& mp : s.measurement_points) history_header += fmt::format(",{0}.u,{0}.v", mp.name);
  for (int j : recorded)
    history_header += fmt::format(",{0}.contacts,{0}.shear_displacement,{0}.shear_force", s.joint_sets[j].name);
  history_header +=
      ",energy_kinetic,energy_strain,energy_fixed,energy_contact_normal,energy_contact_shear,"
      "work_gravity,work_loads,work_contact_restart,dissipation_friction,dissipation_creep,"
      "dissipation_integration,dissipation_contact_damping,dissipation_contact_closing,"
      "dissipation_contact_release,energy_residual,energy_residual_relative\n";

  CsvAppender history, contacts_csv;
  std::vector<std::pair<double, std::string>> pvd;
  int frames_done = 0;
  double earlier_wall = 0.0;
  const std::string checkpoint_path = (fs::path(out) / "checkpoint.json").string();

  // Replay to the checkpoint (resume) without writing anything.
  enum class Mode { replay, record } mode = Mode::record;
  int replay_target = 0;
  Clock::time_point last_progress{};
  engine.add_observer([&](const core::Engine& e, const core::StepReport& r) {
    if (mode == Mode::replay) {
      if (e.step_count() >= replay_target) throw StopAfterStep{};
      return;
    }
    history.append(history_row(&r));
    if (opt.progress) {
      const auto now = Clock::now();
      if (now - last_progress > std::chrono::milliseconds(200)) {
        last_progress = now;
        std::fprintf(opt.progress_stream, "\r  t = %-12.6g of %g %s  step %-8d dt %-10.4g cuts %-3d %5.1f%%  ",
                     e.time(), a.duration, s.units.time.c_str(), e.step_count(), r.dt, r.cuts,
                     100.0 * e.time() / a.duration);
        std::fflush(opt.progress_stream);
      }
    }
    if ((opt.stop && *opt.stop) || (opt.stop_after_step >= 0 && e.step_count() >= opt.stop_after_step))
      throw StopAfterStep{};
  });

  if (opt.resume) {
    json ck;
    try {
      ck = json::parse(read_file(checkpoint_path));
    } catch (const std::exception& e) {
      throw std::invalid_argument(fmt::format("--resume: cannot read {}: {}", checkpoint_path, e.what()));
    }
    if (ck.value("scene_hash", "") != scene_hash)
      throw std::invalid_argument(fmt::format(
          "--resume: {} belongs to another scene text (the scene file changed since); run without --resume",
          checkpoint_path));
    frames_done = ck.at("frames").get<int>();
    const int step = ck.at("step").get<int>();
    earlier_wall = ck.at("wall_seconds").get<double>();
    for (const auto& f : ck.at("pvd")) pvd.emplace_back(unhex(f.at(0).get<std::string>()), f.at(1).get<std::string>());
    history.open((fs::path(out) / "history.csv").string(), ck.at("history_bytes").get<std::uint64_t>(), true);
    contacts_csv.open((fs::path(out) / "contacts.csv").string(), ck.at("contacts_bytes").get<std::uint64_t>(), true);
    mode = Mode::replay;
    replay_target = step;
    try {
      for (int k = 1; k <= frames_done && k < static_cast<int>(frame_times.size()) && engine.step_count() < step; ++k)
        engine.run_until(frame_times[k]);
    } catch (const StopAfterStep&) {
    }
    if (engine.step_count() != step || hex(engine.time()) != ck.at("time").get<std::string>() ||
        fmt::format("{:016x}", state_digest(engine)) != ck.at("digest").get<std::string>())
      throw std::runtime_error(fmt::format(
          "--resume: replaying {} steps did not reproduce the checkpoint (step {}, time {:g})", step,
          engine.step_count(), engine.time()));
    mode = Mode::record;
    result.resumed_from_step = step;
  } else {
    history.open((fs::path(out) / "history.csv").string(), 0, false);
    contacts_csv.open((fs::path(out) / "contacts.csv").string(), 0, false);
    history.append(units_comment(s.units) + history_header);
    contacts_csv.append(units_comment(s.units) +
                        "time,step,id,joint_set,state,kind,vertex_block,vertex,edge_block,edge,x,y,"
                        "normal_force,shear_force,shear_displacement,penetration,length\n");
    history.append(history_row(nullptr));
  }

  auto totals = [&] {
    result.steps = engine.step_count();
    result.time = engine.time();
    result.cuts = result.redone = result.extrapolated = 0;
    result.max_penetration = 0.0;
    for (const auto& r : engine.reports()) {
      result.cuts += r.cuts;
      result.redone += r.rejections;
      result.extrapolated += r.extrapolated ? 1 : 0;
      result.max_penetration = std::max(result.max_penetration, r.max_penetration);
    }
    result.frames = frames_done;
    result.wall_seconds = earlier_wall + std::chrono::duration<double>(Clock::now() - wall_start).count();
  };
  const std::string inputs_text = scene_json(s).dump();
  const std::string scene_text_json = json(scene_text).dump();
  auto write_summary = [&](const std::string& status, const std::string& error) {
    totals();
    json j;
    j["program"] = "rheodda 0.1.0";
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
      core::ContactChanges c;
      for (const auto& r : engine.reports()) c += r.changes;
      j["contact_changes"] = {{"closed", c.closed},   {"opened", c.opened},
                              {"slipped", c.slipped}, {"stuck", c.stuck},
                              {"refinements", c.refinements}};
    }
    {
      // The energy balance since t = 0 (docs/engine.md, "Energy balance").
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
                     {"dissipation_contact_closing", t.dissipation_contact_closing},
                     {"dissipation_contact_release", t.dissipation_contact_release},
                     {"residual", t.residual},
                     {"scale", en.initial.total() + t.scale},
                     {"relative_residual", en.relative_residual()},
                     {"max_relative_residual", en.max_relative_residual}};
    }
    j["frames"] = result.frames;
    j["wall_seconds"] = result.wall_seconds;
    j["resumed_from_step"] = result.resumed_from_step;
    j["warnings"] = result.warnings;
    {
      // The linear solver actually used (automatic resolved) and its work since
      // this process started (a resumed run counts from the resume).
      const core::SolverKind used =
          core::LinearSolver::resolve(engine.model().settings.solver, engine.block_count());
      const auto& ss = engine.solver_stats();
      j["solver"] = {{"used", used == core::SolverKind::amg       ? "amg"
                              : used == core::SolverKind::pcg     ? "pcg"
                                                                  : "cholmod"},
                     {"solves", ss.solves},
                     {"cg_iterations", ss.pcg_iterations},
                     {"analyses", ss.analyses}};
    }
    j["measurement_points"] = json::array();
    for (const auto& mp : s.measurement_points) j["measurement_points"].push_back(mp.name);
    j["recorded_joint_sets"] = json::array();
    for (int k : recorded) j["recorded_joint_sets"].push_back(s.joint_sets[k].name);
    j["block_names"] = json::array();
    for (const auto& b : s.blocks) j["block_names"].push_back(b.name);
    // The inputs are the same at every frame: serialised once, spliced in.
    std::string text = j.dump(2);
    text.pop_back();  // the closing brace
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    text += ",\n  \"inputs\": " + inputs_text + ",\n  \"scene_text\": " + scene_text_json + "\n}\n";
    write_file_atomic((fs::path(out) / "summary.json").string(), text);
  };
  auto write_checkpoint = [&] {
    json ck;
    ck["scene_hash"] = scene_hash;
    ck["step"] = engine.step_count();
    ck["time"] = hex(engine.time());
    ck["digest"] = fmt::format("{:016x}", state_digest(engine));
    ck["frames"] = frames_done;
    ck["history_bytes"] = history.bytes();
    ck["contacts_bytes"] = contacts_csv.bytes();
    ck["wall_seconds"] = earlier_wall + std::chrono::duration<double>(Clock::now() - wall_start).count();
    json frames = json::array();
    for (const auto& [t, f] : pvd) frames.push_back({hex(t), f});
    ck["pvd"] = frames;
    write_file_atomic(checkpoint_path, ck.dump(1) + "\n");
  };
  auto write_frame = [&] {
    const int k = frames_done;
    std::string rows;
    for (const auto& c : contacts.contacts()) {
      const core::Vec2 p = engine.vertices(c.key.vblock)[c.key.vertex];
      rows += fmt::format("{:.10g},{},{},{},{},{},{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n",
                          engine.time(), engine.step_count(), c.id, s.joint_sets[c.joint_set].name,
                          contact::contact_state_name(c.state), contact::contact_kind_name(c.kind),
                          s.blocks[c.key.vblock].name, c.key.vertex, s.blocks[c.key.eblock].name, c.key.edge,
                          p.x(), p.y(), c.normal_force, c.shear_force, c.shear_displacement, c.penetration,
                          c.length);
    }
    if (!rows.empty()) contacts_csv.append(rows);
    std::vector<FrameBlock> blocks;
    for (int b = 0; b < engine.block_count(); ++b) {
      const core::BlockState& st = engine.block(b);
      FrameBlock fb;
      for (std::size_t v = 0; v < st.vertices.size(); ++v) {
        fb.vertices.push_back({st.vertices[v].x(), st.vertices[v].y()});
        const core::Vec2 d = st.vertices[v] - initial[b][v];
        fb.displacement.push_back({d.x(), d.y()});
      }
      fb.stress = {st.stress[0], st.stress[1], st.stress[2]};
      fb.velocity = {st.velocity[0], st.velocity[1], st.velocity[2]};
      fb.material = st.material;
      fb.fixed = s.blocks[b].fixed;
      blocks.push_back(std::move(fb));
    }
    const std::string file = fmt::format("frames/blocks_{:06d}.vtp", k);
    write_file_atomic((fs::path(out) / file).string(), vtk_polydata(blocks));
    pvd.emplace_back(engine.time(), file);
    write_file_atomic((fs::path(out) / "blocks.pvd").string(), vtk_collection(pvd));
    ++frames_done;
    write_checkpoint();
    write_summary("running", "");
  };

  try {
    if (frames_done == 0) write_frame();
    for (int k = frames_done; k < static_cast<int>(frame_times.size()); ++k) {
      engine.run_until(frame_times[k]);
      write_frame();
    }
  } catch (const StopAfterStep&) {
    write_checkpoint();
    write_summary("interrupted", "");
    result.status = RunStatus::interrupted;
    return result;
  } catch (const std::exception& e) {
    write_checkpoint();
    write_summary("failed", e.what());
    throw std::runtime_error(fmt::format("run failed at t = {:g} {} (step {}): {}", engine.time(), s.units.time,
                                         engine.step_count(), e.what()));
  }
  if (opt.progress) std::fprintf(opt.progress_stream, "\n");
  write_summary("completed", "");
  return result;
}

}  // namespace rheodda::scene
