// What a run writes as it goes (docs/reference/outputs.md): the rows of history.csv
// (at the output times and the events of history_row_due, or after every step), and
// at each output time a frame: the contacts' rows of contacts.csv, the VTK files
// frames/blocks_NNNNNN.vtp and frames/contacts_NNNNNN.vtp, and the collections
// blocks.pvd and contacts.pvd that list them (unless analysis.frames is false).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "rheodda/contact/strength.hpp"
#include "rheodda/scene/history_columns.hpp"
#include "run_internal.hpp"

namespace rheodda::scene {
namespace {

namespace fs = std::filesystem;

std::string units_comment(const Units& u) {
  return fmt::format("# units: length={} force={} time={} stress={}\n", u.length, u.force, u.time, u.stress());
}

const std::string contacts_header =
    "time,step,id,joint_set,state,kind,vertex_block,vertex,edge_block,edge,x,y,"
    "normal_force,shear_force,shear_strength,shear_displacement,penetration,length,tributary_length,"
    "creep_displacement,creep_state\n";

/// The contact's Mohr-Coulomb strength [force/length]: the peak while it is intact, the
/// residual once it has slid or opened (contact/strength.hpp).
double strength(const Run& run, const contact::Contact& c) {
  return contact::mohr_coulomb_strength(run.contacts.joint_sets()[c.joint_set], c.normal_force, c.length, c.intact);
}

std::string contacts_collection(const Run& run) {
  std::vector<std::pair<double, std::string>> files;
  for (const auto& [t, f] : run.pvd) files.emplace_back(t, contacts_file(f));
  return vtk_collection(files);
}

}  // namespace

std::vector<std::string> history_columns(const SceneDescription& s) {
  // The declared columns (history_columns.hpp) of the scene's points, its recorded joint
  // sets (Run::recorded), its settling stage, bolts (docs/reference/bolts.md, "Energy") and
  // stages (docs/reference/stages.md).
  std::vector<std::string> points, recorded;
  for (const auto& mp : s.measurement_points) points.push_back(mp.name);
  for (const auto& j : s.joint_sets)
    if (j.record) recorded.push_back(j.name);
  return history_columns_of(points, s.analysis.has_settle(), recorded, has_bolts(s), !s.stages.empty());
}

std::string make_history_header(const SceneDescription& s) { return fmt::format("{}\n", fmt::join(history_columns(s), ",")); }

std::string history_row(const Run& run, const core::StepReport* r) {
  const SceneDescription& s = run.s;
  const core::Engine& engine = run.engine;
  std::string row = fmt::format("{:.10g},{},{:.10g},{},{}", engine.time(), engine.step_count(),
                                r ? r->dt : 0.0, r ? r->cuts : 0, r ? r->iterations : 0);
  const std::vector<double>& settled = run.run_totals.settled;
  for (std::size_t k = 0; k < s.measurement_points.size(); ++k) {
    const auto& mp = s.measurement_points[k];
    const core::Vec2 d = engine.point_displacement(mp.at.block, {mp.at.point[0], mp.at.point[1]});
    row += fmt::format(",{:.10g},{:.10g}", d.x(), d.y());
    if (!s.analysis.has_settle()) continue;
    // Empty until the settling stage has ended, then 0 at its end (docs/reference/outputs.md).
    if (settled.empty())
      row += ",,";
    else
      row += fmt::format(",{:.10g},{:.10g}", d.x() - settled[2 * k], d.y() - settled[2 * k + 1]);
  }
  for (int j : run.recorded) {
    int n = 0;
    double shear = 0.0, force = 0.0, magnitude = 0.0;
    for (const auto& c : run.contacts.contacts())
      if (c.joint_set == j && c.state != contact::ContactState::open) {
        ++n;
        shear += c.shear_displacement;
        force += c.shear_force;
        magnitude += std::abs(c.shear_displacement);
      }
    row += n ? fmt::format(",{},{:.10g},{:.10g},{:.10g}", n, shear / n, force / n, magnitude / n)
             : fmt::format(",0,,,");
  }
  // Energy balance (docs/reference/engine.md, "Energy balance"): stored energies now, flows since t = 0.
  for (const double v : history_energy_values(engine.energy())) row += fmt::format(",{:.10g}", v);
  if (has_bolts(s))
    row += fmt::format(",{:.10g},{:.10g}", engine.energy().stored.bolt, engine.energy().total.dissipation_bolt);
  if (!s.stages.empty()) row += "," + run.stage_run.current;  // the stage in force (docs/reference/stages.md)
  return row + '\n';
}

std::vector<double> run_output_times(const Analysis& a) {
  std::vector<double> t;
  const long long n = static_cast<long long>(std::ceil(a.duration / a.output_interval - 1e-9));
  for (long long k = 0; k <= n; ++k) t.push_back(std::min(double(k) * a.output_interval, a.duration));
  t.insert(t.end(), a.output_times.begin(), a.output_times.end());
  std::sort(t.begin(), t.end());
  // One time for those closer than 1e-9 of the run (a study's time of 5.787037e-5 d
  // among the output times 5 x 1.1574074e-5 d); the duration and the earlier of others stay.
  const double same = 1e-9 * a.duration;
  std::vector<double> out;
  for (const double x : t)
    if (out.empty() || x - out.back() > same) out.push_back(x);
    else if (x == a.duration) out.back() = x;
  return out;
}

bool history_row_due(Run& run, const core::StepReport& r) {
  const core::Engine& e = run.engine;
  bool due = run.a.history == HistoryRows::steps || r.collapse_stage;
  if (const std::size_t k = index_after(run.row_times, e.time()); k > run.rows_reached) {
    run.rows_reached = k;  // an output time or a stage's time
    due = true;
  }
  if (e.events().size() > run.events_seen) {  // a dynamic stage ended
    run.events_seen = e.events().size();
    due = true;
  }
  int failures = 0;
  for (const contact::CreepCounters& c : run.contacts.creep_counters()) failures += c.failures;
  if (failures > run.failures_seen) {  // a contact's damage law failed
    run.failures_seen = failures;
    due = true;
  }
  return due;
}

void note_settled(Run& run) {
  const SceneDescription& s = run.s;
  std::vector<double>& settled = run.run_totals.settled;
  if (!s.analysis.has_settle() || !settled.empty()) return;
  // The settling stage at the start is the first dynamic stage to end; a stage's own
  // settling (docs/reference/stages.md) comes later, a collapse stage only after it.
  const auto& events = run.engine.events();
  if (events.empty() || events.front().kind != core::StageKind::settling) return;
  for (const auto& mp : s.measurement_points) {
    const core::Vec2 d = run.engine.point_displacement(mp.at.block, {mp.at.point[0], mp.at.point[1]});
    settled.push_back(d.x());
    settled.push_back(d.y());
  }
  if (settled.empty()) settled.push_back(0.0);  // no point: the stage has ended all the same
}

void create_csv_files(Run& run) {
  run.history.create((fs::path(run.out) / "history.csv").string());
  run.history.append(units_comment(run.s.units) + run.history_header);
  run.history.append(history_row(run, nullptr));
  if (!run.a.frames) {
    // Only history.csv, events.csv and summary.json: what an earlier run into the
    // folder left of the others would be taken for this run's.
    std::error_code ec;
    for (const char* f : {"contacts.csv", "bolts.csv", "blocks.pvd", "contacts.pvd", "bolts.pvd"})
      fs::remove(fs::path(run.out) / f, ec);
    fs::remove_all(fs::path(run.out) / "frames", ec);
    return;
  }
  run.contacts_csv.create((fs::path(run.out) / "contacts.csv").string());
  // With water (docs/reference/water.md) a last column, water_pressure.
  run.contacts_csv.append(units_comment(run.s.units) +
                          (scene_has_water(run.s) ? contacts_header.substr(0, contacts_header.size() - 1) + ",water_pressure\n"
                                       : contacts_header));
  if (has_bolts(run.s)) create_bolts_csv(run);
}

std::string frame_text(const Run& run) {
  const core::Engine& engine = run.engine;
  std::vector<FrameBlock> blocks;
  for (int b = 0; b < engine.block_count(); ++b) {
    const core::BlockState& st = engine.block(b);
    FrameBlock fb;
    for (std::size_t v = 0; v < st.vertices.size(); ++v) {
      fb.vertices.push_back({st.vertices[v].x(), st.vertices[v].y()});
      const core::Vec2 d = st.vertices[v] - run.initial[b][v];
      fb.displacement.push_back({d.x(), d.y()});
    }
    fb.stress = {st.stress[0], st.stress[1], st.stress[2]};
    fb.velocity = {st.velocity[0], st.velocity[1], st.velocity[2]};
    fb.material = st.material;
    fb.fixed = run.s.blocks[b].fixed;
    if (!run.s.stages.empty()) fb.removed = engine.removed(b);  // docs/reference/stages.md
    blocks.push_back(std::move(fb));
  }
  return vtk_polydata(blocks);
}

std::string contacts_frame_text(const Run& run) {
  std::vector<FrameContact> layer;
  for (const auto& c : run.contacts.contacts()) {
    const core::Vec2 p = run.engine.vertices(c.key.vblock)[c.key.vertex];
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
    fc.tributary_length = c.tributary_length;
    fc.shear_strength = strength(run, c);
    if (scene_has_water(run.s)) fc.water_pressure = core::water_pressure(run.engine.model().water, p, run.engine.time());
    layer.push_back(fc);
  }
  return vtk_contacts(layer);
}

// A frame is two files, frames/blocks_NNNNNN.vtp and frames/contacts_NNNNNN.vtp;
// the checkpoint keeps one hash of both.
std::string contacts_file(const std::string& blocks_file) {
  std::string f = blocks_file;
  const std::size_t at = f.rfind("blocks_");
  if (at != std::string::npos) f.replace(at, 7, "contacts_");
  return f;
}

std::uint64_t frame_pair_hash(const std::string& blocks_text, const std::string& contacts_text) {
  return fnv1a(contacts_text.data(), contacts_text.size(), fnv1a(blocks_text.data(), blocks_text.size()));
}

void write_collections(const Run& run) {
  write_file_atomic((fs::path(run.out) / "blocks.pvd").string(), vtk_collection(run.pvd));
  write_file_atomic((fs::path(run.out) / "contacts.pvd").string(), contacts_collection(run));
}

void write_frame(Run& run) {
  const SceneDescription& s = run.s;
  const core::Engine& engine = run.engine;
  const std::string& out = run.out;
  run.frame_open = true;
  const int k = run.frames_done;
  if (!run.a.frames) {  // analysis.frames: false: the output time only (the loop, checkpoint and summary count it)
    run.pvd.emplace_back(engine.time(), std::string());
    run.frame_hash.push_back(0);
    ++run.frames_done;
    run.frame_open = false;
    if (run.frames_done == 1 || Clock::now() - run.last_checkpoint > std::chrono::seconds(1)) write_checkpoint(run);
    write_summary(run, "running", "");
    return;
  }
  std::string rows;
  for (const auto& c : run.contacts.contacts()) {
    const core::Vec2 p = engine.vertices(c.key.vblock)[c.key.vertex];
    rows += fmt::format("{:.10g},{},{},{},{},{},{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},"
                        "{:.10g},{:.10g},{:.10g},{}{}\n",
                        engine.time(), engine.step_count(), c.id, s.joint_sets[c.joint_set].name,
                        contact::contact_state_name(c.state), contact::contact_kind_name(c.kind),
                        s.blocks[c.key.vblock].name, c.key.vertex, s.blocks[c.key.eblock].name, c.key.edge,
                        p.x(), p.y(), c.normal_force, c.shear_force, strength(run, c), c.shear_displacement,
                        c.penetration, c.length, c.tributary_length, c.creep_displacement,
                        contact::creep_state_name(c.creep_state),
                        scene_has_water(s) ? water_pressure_cell(engine.model().water, p, engine.time()) : std::string());
  }
  for (const auto& c : run.contacts.contacts())
    for (const auto& [name, v] : {std::pair<const char*, double>{"normal_force", c.normal_force},
                                  {"shear_force", c.shear_force},
                                  {"shear_displacement", c.shear_displacement},
                                  {"penetration", c.penetration},
                                  {"length", c.length},
                                  {"creep_displacement", c.creep_displacement}})
      if (!std::isfinite(v))
        throw NonFinite(fmt::format("contacts.csv column '{}' of contact {} is not finite at step {} (t = {:g} {})",
                                    name, c.id, engine.step_count(), engine.time(), s.units.time));
  if (!rows.empty()) run.contacts_csv.append(rows);
  const std::string file = fmt::format("frames/blocks_{:06d}.vtp", k);
  const std::string text = frame_text(run), layer = contacts_frame_text(run);
  write_file_atomic((fs::path(out) / file).string(), text);
  write_file_atomic((fs::path(out) / contacts_file(file)).string(), layer);
  run.frames_bytes += text.size() + layer.size();
  if (has_bolts(s)) write_bolts_frame(run, file);
  run.pvd.emplace_back(engine.time(), file);
  run.frame_hash.push_back(frame_pair_hash(text, layer));
  write_collections(run);
  ++run.frames_done;
  run.frame_open = false;
  // A checkpoint costs a few fsyncs (~10 ms here) and the state file: at most one
  // per second of wall time at frames; always on a stop, a failure and at the end.
  // A resume after a crash continues from the last one (and writes the later
  // frames again).
  if (run.frames_done == 1 || Clock::now() - run.last_checkpoint > std::chrono::seconds(1)) write_checkpoint(run);
  write_summary(run, "running", "");
}

}  // namespace rheodda::scene
