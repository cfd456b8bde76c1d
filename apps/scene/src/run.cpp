#include "rheodda/scene/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <nlohmann/json.hpp>

#include "checkpoint.hpp"
#include "checkpoint_state.hpp"
#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/core/solver.hpp"
#include "rheodda/scene/assemble.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/memory.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/version.hpp"
#include "run_totals.hpp"

namespace rheodda::scene {
namespace {

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

/// Thrown by the step observer to leave Engine::run_until between two steps.
struct StopAfterStep {};

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
                   {"settle", a.settle ? json{{"until", a.settle->until},
                                              {"dt", a.settle->dt},
                                              {"max_displacement_ratio", a.settle->max_displacement_ratio},
                                              {"type", a.settle->dynamic ? "dynamic" : "static"},
                                              {"collapse_dt", a.settle->collapse_dt},
                                              {"gravity_ramp", a.settle->gravity_ramp},
                                              {"rest_tolerance", a.settle->rest_tolerance},
                                              {"open_close_limit", a.settle->open_close_limit}}
                                       : json(nullptr)},
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
                   {"solver_iterate_tolerance", a.solver_iterate_tolerance},
                   {"contact_solver", a.contact_solver == ContactSolverKind::newton ? "newton" : "open-close"},
                   {"contact_residual_tolerance", a.contact_residual_tolerance},
                   {"output_interval", a.output_interval},
                   {"max_travel_ratio", a.max_travel_ratio},
                   {"max_output_size", a.max_output_size},
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

/// Thrown by the step observer when the state or an output row is no longer finite:
/// nothing of that step is written, and the last checkpoint stays the one to resume from.
struct NonFinite : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown by the step observer when a run guard (max_travel_ratio, max_output_size) trips.
struct GuardTripped : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The first non-finite quantity of the engine's state ("velocity of block 'b3'"), or "".
std::string nonfinite_state(const core::Engine& e, const SceneDescription& s) {
  auto finite = [](const auto& v) {
    for (int i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i])) return false;
    return true;
  };
  if (!std::isfinite(e.time())) return "the time";
  for (int b = 0; b < e.block_count(); ++b) {
    const core::BlockState& st = e.block(b);
    for (const auto& v : st.vertices)
      if (!finite(v)) return fmt::format("a vertex position of block '{}'", s.blocks[b].name);
    if (!finite(st.velocity)) return fmt::format("the velocity of block '{}'", s.blocks[b].name);
    if (!finite(st.stress)) return fmt::format("the stress of block '{}'", s.blocks[b].name);
  }
  return "";
}

/// The name of the first column of a CSV row holding nan or inf, or "" (a number
/// written with {:g} contains neither 'n' nor 'i' unless it is not finite).
std::string nonfinite_column(const std::string& header, const std::string& row) {
  if (row.find_first_of("ni") == std::string::npos) return "";
  std::size_t h = 0, r = 0;
  while (r < row.size()) {
    const std::size_t re = std::min(row.find(',', r), row.find('\n', r));
    const std::size_t he = std::min(header.find(',', h), header.find('\n', h));
    const std::string cell = row.substr(r, re - r);
    if (cell.find_first_of("ni") != std::string::npos) return header.substr(h, he - h);
    if (re == std::string::npos || row[re] == '\n') break;
    r = re + 1;
    h = he == std::string::npos ? header.size() : he + 1;
  }
  return "a column";
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

  // Fail early when the run will not fit in memory (docs/performance.md, "Memory").
  if (const auto available = available_memory()) {
    const MemoryEstimate need = estimate_memory(s);
    if (need.bytes > *available)
      throw std::runtime_error(fmt::format(
          "{}: the run needs about {} of memory ({} blocks, solver {}) but this process may use only {} "
          "(MemAvailable, the control group's limit, ulimit -v); run it where more memory is free{}",
          s.file, format_bytes(need.bytes), s.blocks.size(), need.solver, format_bytes(*available),
          need.solver == "cholmod" ? ", or with `solver: amg` (less memory for large models)" : ""));
  }
  BuiltScene built = build_scene(s);
  result.warnings = built.warnings;
  const AssembledScene assembled = assemble_scene(s, built);
  contact::ContactSystem& contacts = *assembled.contacts;
  core::Engine& engine = *assembled.engine;
  const std::string checkpoint_path = (fs::path(out) / "checkpoint.json").string();
  if (opt.resume) {
    // Refuse before anything is created or changed.
    std::error_code ec;
    if (!fs::exists(checkpoint_path, ec))
      throw std::invalid_argument(fmt::format(
          "--resume: {} has no checkpoint.json{}: there is no run to continue; run without --resume", out,
          fs::exists(out, ec) ? "" : " (the folder does not exist)"));
  }
  // Only now that the model is accepted: a refused scene leaves nothing behind.
  {
    // An output folder that cannot be made is bad input (exit 2), as for `fit`.
    std::error_code ec;
    fs::create_directories(fs::path(out) / "frames", ec);
    if (ec) throw std::invalid_argument(write_error((fs::path(out) / "frames").string(), ec.value()));
  }
  // One run per folder at a time (held until this function returns).
  const FolderLock lock(out);
  if (!opt.resume) {
    // A new run invalidates an earlier run's checkpoint before it touches any
    // output: a later --resume must never continue files this run has emptied.
    std::error_code ec;
    if (fs::remove(checkpoint_path, ec)) sync_directory(out);
    if (ec) throw std::runtime_error(write_error(checkpoint_path, ec.value()));
    for (const char* f : kStateFiles) fs::remove(fs::path(out) / f, ec);  // its states, named by nothing now
  }

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
  // A frame is written at the end of the first step that reaches its output time:
  // steps are never shortened to land on output times (only on the end of the run),
  // so output_interval cannot change the steps taken (docs/outputs.md). The next
  // output time after t, the engine's round-off sliver counting as reached:
  auto next_output = [&](double t) {
    std::size_t k = 0;
    while (k < frame_times.size() && frame_times[k] <= t + 1e-12 * std::max(1.0, std::abs(frame_times[k]))) ++k;
    return k;
  };

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
      double shear = 0.0, force = 0.0, magnitude = 0.0;
      for (const auto& c : contacts.contacts())
        if (c.joint_set == j && c.state != contact::ContactState::open) {
          ++n;
          shear += c.shear_displacement;
          force += c.shear_force;
          magnitude += std::abs(c.shear_displacement);
        }
      row += n ? fmt::format(",{},{:.10g},{:.10g},{:.10g}", n, shear / n, force / n, magnitude / n)
               : fmt::format(",0,,,");
    }
    // Energy balance (docs/engine.md, "Energy balance"): stored energies now, flows since t = 0.
    for (const double v : history_energy_values(engine.energy())) row += fmt::format(",{:.10g}", v);
    return row + '\n';
  };
  std::string history_header = "time,step,dt,cuts,iterations";
  for (const auto& mp : s.measurement_points) history_header += fmt::format(",{0}.u,{0}.v", mp.name);
  for (int j : recorded)
    history_header += fmt::format(",{0}.contacts,{0}.shear_displacement,{0}.shear_force,{0}.shear_displacement_magnitude",
                                  s.joint_sets[j].name);
  for (const char* column : kHistoryEnergyColumns) history_header += fmt::format(",{}", column);
  history_header += '\n';

  const std::string contacts_header =
      "time,step,id,joint_set,state,kind,vertex_block,vertex,edge_block,edge,x,y,"
      "normal_force,shear_force,shear_displacement,penetration,length,creep_displacement,creep_state\n";

  CsvAppender history, contacts_csv;
  std::vector<std::pair<double, std::string>> pvd;
  std::vector<std::uint64_t> frame_hash;  ///< FNV-1a of each frame file, in pvd order
  std::uint64_t frames_bytes = 0;         ///< total size of the frames written by this process [byte]
  int frames_done = 0;
  double earlier_wall = 0.0;

  // Run guards (analysis.max_travel_ratio, max_output_size): unbounded motion
  // stops the run instead of filling the disk.
  double model_size = 0.0;
  {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& b : initial)
      for (const auto& v : b) {
        x0 = std::min(x0, v.x()), x1 = std::max(x1, v.x());
        y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
      }
    model_size = std::max(x1 - x0, y1 - y0);
  }
  auto check_guards = [&](const core::Engine& e) {
    if (a.max_travel_ratio > 0.0) {
      const double limit = a.max_travel_ratio * model_size;
      for (int b = 0; b < e.block_count(); ++b) {
        const auto v = e.vertices(b);
        for (std::size_t k = 0; k < v.size(); ++k) {
          const double d = (v[k] - initial[b][k]).norm();
          if (d > limit)
            throw GuardTripped(fmt::format(
                "block '{}' has moved {:g} {}, more than max_travel_ratio ({:g}) x the model size ({:g} {}): the "
                "motion looks unbounded (no friction, a near-zero viscosity, an unsupported block?); check the "
                "scene, or raise analysis.max_travel_ratio (0 = no limit) to let it go on",
                s.blocks[b].name, d, s.units.length, a.max_travel_ratio, model_size, s.units.length,
                s.units.length));
        }
      }
    }
    if (a.max_output_size > 0.0) {
      const double mb = double(history.bytes() + contacts_csv.bytes() + frames_bytes) / 1e6;
      if (mb > a.max_output_size)
        throw GuardTripped(fmt::format(
            "the outputs have grown to {:.0f} MB, more than max_output_size ({:g} MB); raise "
            "analysis.max_output_size (0 = no limit) or output_interval",
            mb, a.max_output_size));
    }
  };

  // Steps run again without writing (a resume writing a lost frame again), up to the checkpoint's.
  enum class Mode { replay, record } mode = Mode::record;
  int replay_target = 0;
  Clock::time_point last_progress{};
  RunTotals run_totals(s.joint_sets.size(), a.type == AnalysisType::static_analysis);
  int recorded_step = engine.step_count();  // the last step whose outputs are written [-]
  engine.add_observer([&](const core::Engine& e, const core::StepReport& r) {
    ++result.steps_computed;
    if (mode == Mode::replay) {
      if (e.step_count() >= replay_target) throw StopAfterStep{};
      return;
    }
    run_totals.add(r, contacts.creep_counters());
    if (const std::string what = nonfinite_state(e, s); !what.empty())
      throw NonFinite(fmt::format("{} is not finite after step {} (t = {:g} {})", what, e.step_count(), e.time(),
                                  s.units.time));
    const std::string row = history_row(&r);
    if (const std::string col = nonfinite_column(history_header, row); !col.empty())
      throw NonFinite(fmt::format("history.csv column '{}' is not finite after step {} (t = {:g} {})", col,
                                  e.step_count(), e.time(), s.units.time));
    history.append(row);
    recorded_step = e.step_count();
    check_guards(e);
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

  // A frame's file: the blocks at the engine's current state.
  auto frame_text = [&] {
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
    return vtk_polydata(blocks);
  };
  // The contact layer of a frame: each contact at its vertex with the fields of contacts.csv.
  auto contacts_frame_text = [&] {
    std::vector<FrameContact> layer;
    for (const auto& c : contacts.contacts()) {
      const core::Vec2 p = engine.vertices(c.key.vblock)[c.key.vertex];
      FrameContact fc;
      fc.point = {p.x(), p.y()};
      fc.id = static_cast<int>(c.id);
      fc.joint_set = c.joint_set;
      fc.state = static_cast<int>(c.state);
      fc.kind = static_cast<int>(c.kind);
      fc.normal_force = c.normal_force;
      fc.shear_force = c.shear_force;
      fc.shear_displacement = c.shear_displacement;
      fc.creep_displacement = c.creep_displacement;
      fc.penetration = c.penetration;
      fc.length = c.length;
      layer.push_back(fc);
    }
    return vtk_contacts(layer);
  };
  // A frame is two files, frames/blocks_NNNNNN.vtp and frames/contacts_NNNNNN.vtp;
  // the checkpoint keeps one hash of both.
  auto contacts_file = [](const std::string& blocks_file) {
    std::string f = blocks_file;
    const std::size_t at = f.rfind("blocks_");
    if (at != std::string::npos) f.replace(at, 7, "contacts_");
    return f;
  };
  auto frame_pair_hash = [](const std::string& blocks_text, const std::string& contacts_text) {
    return fnv1a(contacts_text.data(), contacts_text.size(), fnv1a(blocks_text.data(), blocks_text.size()));
  };
  auto contacts_collection = [&] {
    std::vector<std::pair<double, std::string>> files;
    for (const auto& [t, f] : pvd) files.emplace_back(t, contacts_file(f));
    return vtk_collection(files);
  };

  StateFile state_file;  // the state file the last checkpoint names
  if (opt.resume) {
    const Checkpoint ck = read_checkpoint(checkpoint_path, s.file, scene_hash, frame_times.size());
    SavedRun saved = read_state_file(out, ck.state, scene_hash);
    // Take the saved state up before any file is changed: one that does not fit
    // this scene's model is refused with the folder as it was.
    const core::EngineState start = engine.save();
    const contact::ContactSystem::State start_contacts = contacts.state();
    try {
      if (saved.engine.step != ck.step || saved.engine.time != ck.time)
        throw std::invalid_argument(
            fmt::format("it is of step {}, the checkpoint of step {}", saved.engine.step, ck.step));
      if (saved.totals.first_failure.size() != s.joint_sets.size())
        throw std::invalid_argument(fmt::format("its totals are of {} joint sets, the scene has {}",
                                                saved.totals.first_failure.size(), s.joint_sets.size()));
      engine.restore(saved.engine);
      contacts.restore(saved.contacts);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format(
          "--resume: {} does not fit this run ({}); nothing was changed: run without --resume to start again, or "
          "into a new folder",
          (fs::path(out) / ck.state.name).string(), e.what()));
    }
    state_file = ck.state;
    frames_done = static_cast<int>(ck.frames.size());
    pvd = ck.frames;
    frame_hash = ck.frame_hashes;
    earlier_wall = ck.wall_seconds;
    // Every file the run continues must be what the checkpoint recorded.
    history.resume((fs::path(out) / "history.csv").string(), ck.history_bytes, ck.history_hash);
    contacts_csv.resume((fs::path(out) / "contacts.csv").string(), ck.contacts_bytes, ck.contacts_hash);
    std::vector<bool> frame_ok;  // false: missing or changed
    int last_lost = -1;
    for (int k = 0; k < frames_done; ++k) {
      std::string text, layer;
      try {
        text = read_file((fs::path(out) / pvd[k].second).string());
        layer = read_file((fs::path(out) / contacts_file(pvd[k].second)).string());
      } catch (const std::exception&) {
      }
      frame_ok.push_back(!text.empty() && !layer.empty() && frame_pair_hash(text, layer) == frame_hash[k]);
      if (!frame_ok.back()) last_lost = k;
    }
    if (last_lost >= 0) {
      // A lost or changed frame can be written again only from the state of its
      // time: the steps up to it are run again from the start (the one case in
      // which a resume computes steps), then the saved state is taken up again.
      auto restore_frame = [&](int k) {
        if (frame_ok[k] || engine.time() != pvd[k].first) return;
        const std::string text = frame_text(), layer = contacts_frame_text();
        if (frame_pair_hash(text, layer) != frame_hash[k])
          throw std::runtime_error(
              fmt::format("--resume: running again did not reproduce frame {} ({})", k, pvd[k].second));
        write_file_atomic((fs::path(out) / pvd[k].second).string(), text);
        write_file_atomic((fs::path(out) / contacts_file(pvd[k].second)).string(), layer);
        frame_ok[k] = true;
      };
      engine.restore(start);
      contacts.restore(start_contacts);
      mode = Mode::replay;
      replay_target = ck.step;
      restore_frame(0);
      int f = 1;  // the frame the steps reach next
      try {
        for (std::size_t k = next_output(engine.time()); k < frame_times.size() && f <= last_lost;
             k = next_output(engine.time())) {
          engine.run_until(frame_times[k], a.duration);
          restore_frame(f++);
        }
      } catch (const StopAfterStep&) {  // at the checkpoint's step: its frame, if it is one
        if (f <= last_lost) restore_frame(f);
      }
      mode = Mode::record;
      for (int k = 0; k <= last_lost; ++k)
        if (!frame_ok[k])
          throw std::runtime_error(fmt::format("--resume: frame {} ({}) could not be written again", k, pvd[k].second));
      engine.restore(saved.engine);
      contacts.restore(saved.contacts);
    }
    write_file_atomic((fs::path(out) / "blocks.pvd").string(), vtk_collection(pvd));
    write_file_atomic((fs::path(out) / "contacts.pvd").string(), contacts_collection());
    run_totals = std::move(saved.totals);
    recorded_step = ck.step;
    result.resumed_from_step = ck.step;
  } else {
    history.create((fs::path(out) / "history.csv").string());
    contacts_csv.create((fs::path(out) / "contacts.csv").string());
    history.append(units_comment(s.units) + history_header);
    contacts_csv.append(units_comment(s.units) + contacts_header);
    history.append(history_row(nullptr));
  }

  auto totals = [&] {
    result.creep.clear();
    for (std::size_t j = 0; j < s.joint_sets.size(); ++j)
      if (contacts.joint_sets()[j].law) {
        const contact::CreepCounters& k = contacts.creep_counters()[j];
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
    result.frames = frames_done;
    result.wall_seconds = earlier_wall + std::chrono::duration<double>(Clock::now() - wall_start).count();
  };
  const std::string inputs_text = scene_json(s).dump();
  const std::string scene_text_json = json(scene_text).dump();
  auto write_summary = [&](const std::string& status, const std::string& error) {
    totals();
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
      const core::ContactChanges& c = run_totals.contact_changes;
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
                     {"dissipation_block_damping", t.dissipation_block_damping},
                     {"dissipation_contact_closing", t.dissipation_contact_closing},
                     {"dissipation_contact_release", t.dissipation_contact_release},
                     {"residual", t.residual},
                     {"scale", en.initial.total() + t.scale},
                     {"relative_residual", en.relative_residual()},
                     {"max_relative_residual", en.max_relative_residual}};
    }
    if (result.mechanism.static_analysis) {
      // Mechanism motion of a static analysis (docs/engine.md, "Mechanisms in static analysis").
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
    if (a.settle) {
      // Dynamic stages (docs/engine.md, "Dynamic stages"): summary.json's
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
      write_file_atomic((fs::path(out) / "events.csv").string(), csv);
      result.events = engine.events();
    }
    j["frames"] = result.frames;
    j["wall_seconds"] = result.wall_seconds;
    j["resumed_from_step"] = result.resumed_from_step;
    j["steps_computed"] = result.steps_computed;
    j["warnings"] = result.warnings;
    // Where each joint set's law acted (docs/outputs.md, "summary.json").
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
      j["solver"] = {{"used", used == core::SolverKind::amg       ? "amg"
                              : used == core::SolverKind::pcg     ? "pcg"
                                                                  : "cholmod"},
                     {"solves", ss.solves},
                     {"cg_iterations", ss.pcg_iterations},
                     {"analyses", ss.analyses},
                     {"amg_fallback_solve", ss.amg_fallback_solve}};
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
  Clock::time_point last_checkpoint{};
  auto write_checkpoint = [&] {
    // What the checkpoint counts must be on disk before the checkpoint is: the
    // CSVs and the state file it names (the frames and blocks.pvd need not:
    // resume writes them again when they are lost).
    history.sync();
    contacts_csv.sync();
    const StateFile previous = state_file;
    state_file = write_state_file(out, {engine.save(), contacts.state(), run_totals}, scene_hash, previous.name);
    Checkpoint ck;
    ck.scene_hash = scene_hash;
    ck.scene_file = s.file;
    ck.title = s.title;
    ck.step = engine.step_count();
    ck.time = engine.time();
    ck.wall_seconds = earlier_wall + std::chrono::duration<double>(Clock::now() - wall_start).count();
    ck.history_bytes = history.bytes();
    ck.history_hash = history.hash();
    ck.contacts_bytes = contacts_csv.bytes();
    ck.contacts_hash = contacts_csv.hash();
    ck.frames = pvd;
    ck.frame_hashes = frame_hash;
    ck.state = state_file;
    write_file_atomic(checkpoint_path, checkpoint_text(ck), true);
    std::error_code ec;  // the state the previous checkpoint named is needed no more
    if (!previous.name.empty() && previous.name != state_file.name) fs::remove(fs::path(out) / previous.name, ec);
    last_checkpoint = Clock::now();
  };
  bool frame_open = false;  // a frame is being written (its rows may be in contacts.csv already)
  auto write_frame = [&] {
    frame_open = true;
    const int k = frames_done;
    std::string rows;
    for (const auto& c : contacts.contacts()) {
      const core::Vec2 p = engine.vertices(c.key.vblock)[c.key.vertex];
      rows += fmt::format("{:.10g},{},{},{},{},{},{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},"
                          "{:.10g},{}\n",
                          engine.time(), engine.step_count(), c.id, s.joint_sets[c.joint_set].name,
                          contact::contact_state_name(c.state), contact::contact_kind_name(c.kind),
                          s.blocks[c.key.vblock].name, c.key.vertex, s.blocks[c.key.eblock].name, c.key.edge,
                          p.x(), p.y(), c.normal_force, c.shear_force, c.shear_displacement, c.penetration,
                          c.length, c.creep_displacement, contact::creep_state_name(c.creep_state));
    }
    for (const auto& c : contacts.contacts())
      for (const auto& [name, v] : {std::pair<const char*, double>{"normal_force", c.normal_force},
                                    {"shear_force", c.shear_force},
                                    {"shear_displacement", c.shear_displacement},
                                    {"penetration", c.penetration},
                                    {"length", c.length},
                                    {"creep_displacement", c.creep_displacement}})
        if (!std::isfinite(v))
          throw NonFinite(fmt::format("contacts.csv column '{}' of contact {} is not finite at step {} (t = {:g} {})",
                                      name, c.id, engine.step_count(), engine.time(), s.units.time));
    if (!rows.empty()) contacts_csv.append(rows);
    const std::string file = fmt::format("frames/blocks_{:06d}.vtp", k);
    const std::string text = frame_text(), layer = contacts_frame_text();
    write_file_atomic((fs::path(out) / file).string(), text);
    write_file_atomic((fs::path(out) / contacts_file(file)).string(), layer);
    frames_bytes += text.size() + layer.size();
    pvd.emplace_back(engine.time(), file);
    frame_hash.push_back(frame_pair_hash(text, layer));
    write_file_atomic((fs::path(out) / "blocks.pvd").string(), vtk_collection(pvd));
    write_file_atomic((fs::path(out) / "contacts.pvd").string(), contacts_collection());
    ++frames_done;
    frame_open = false;
    // A checkpoint costs a few fsyncs (~10 ms here) and the state file: at most one
    // per second of wall time at frames; always on a stop, a failure and at the end.
    // A resume after a crash continues from the last one (and writes the later
    // frames again).
    if (frames_done == 1 || Clock::now() - last_checkpoint > std::chrono::seconds(1)) write_checkpoint();
    write_summary("running", "");
  };

  try {
    if (frames_done == 0) write_frame();
    // The next output time after the last frame written: a run resumed at an output
    // time that its frame was not written for (stopped on that very step) writes it now.
    for (std::size_t k = next_output(pvd.back().first); k < frame_times.size(); k = next_output(pvd.back().first)) {
      engine.run_until(frame_times[k], a.duration);  // returns at once if the time is reached
      write_frame();
    }
  } catch (const StopAfterStep&) {
    write_checkpoint();
    write_summary("interrupted", "");
    result.status = RunStatus::interrupted;
    return result;
  } catch (const NonFinite& e) {
    // Nothing of the bad step was written; the last checkpoint (at the last frame)
    // stays the one to resume from.
    const std::string msg = fmt::format(
        "{}: the run stops with the outputs of the steps before it kept (a step, penalty or parameter at the "
        "limit of double precision? see docs/outputs.md, \"Runs that stop\")",
        e.what());
    try {
      write_summary("failed", msg);
    } catch (const std::exception&) {
    }
    throw std::runtime_error(msg);
  } catch (const std::exception& e) {
    // Keep what can be kept; a second failure (e.g. a full disk) must not hide the first.
    std::string error = e.what();
    if (dynamic_cast<const std::bad_alloc*>(&e))
      error = fmt::format("out of memory (a model of {} blocks needs more memory than is available to this "
                          "process; docs/performance.md gives the memory a run needs per block)",
                          engine.block_count());
    if (const auto* se = dynamic_cast<const core::SingularSystemError*>(&e);
        se && se->block >= 0 && se->block < static_cast<int>(s.blocks.size())) {
      // Say which block, and what held it: its contacts at the start of the failed step.
      int closed = 0, total = 0;
      for (const auto& c : contacts.contacts())
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
    try {
      // Only where the state is that of the outputs: not within a step (a
      // failure inside the engine can leave it there), nor within a frame.
      if (engine.step_count() == recorded_step && !frame_open) write_checkpoint();
    } catch (const std::exception&) {
    }
    try {
      write_summary("failed", error);
    } catch (const std::exception& e2) {
      error += fmt::format(" (summary.json could not be updated either: {})", e2.what());
    }
    throw std::runtime_error(fmt::format("run {} at t = {:g} {} (step {}): {}",
                                         dynamic_cast<const GuardTripped*>(&e) ? "stopped" : "failed",
                                         engine.time(), s.units.time, engine.step_count(), error));
  }
  if (opt.progress) std::fprintf(opt.progress_stream, "\n");
  write_checkpoint();
  totals();
  for (const auto& c : result.creep)
    if (c.contacts == 0)
      result.warnings.push_back(fmt::format(
          "joint set '{}' has a creep law but none of its contacts crept (none stayed locked through a step)",
          c.joint_set));
  if (const auto& m = result.mechanism; m.static_analysis && m.steps > 0 &&
                                                 m.inertia_share > core::kMechanismRunShare)
    result.warnings.push_back(fmt::format(
        "static analysis: parts of the model moved as a mechanism in {} steps (from t = {:g} to {:g} {}): "
        "the inertia term of the static steps took {:.1f} % of the work of gravity and loads. A static "
        "step starts at rest and holds a mechanism (or a part whose springs are soft on the step's scale) "
        "by its inertia term alone, so how far and how fast it moves there depends on dt and "
        "max_displacement_ratio: check the results with both halved (`rheodda check {} --refine` does it), or "
        "run that phase as a dynamic analysis (docs/engine.md, \"Mechanisms in static analysis\"){}",
        m.steps, m.first_time, m.last_time, s.units.time, 100.0 * m.inertia_share,
        s.file.empty() ? std::string("SCENE") : s.file,
        // Settling under gravity applied at once: the usual case, with its remedy.
        m.first_step >= 0 && m.first_step < 10 && !s.analysis.settle
            ? ". It began in the first steps: where that is the model settling as gravity comes on, a "
              "settling stage (analysis.settle, docs/engine.md \"Settling stage\") makes every run start "
              "from the same settled state"
            : ""));
  write_summary("completed", "");
  return result;
}

}  // namespace rheodda::scene
