// What a run writes of its bolts (docs/reference/outputs.md, "bolts.csv"; docs/reference/bolts.md),
// only when the scene has bolts: a row per bolt in place (from the stage that
// installs it, for a stage's bolts) at every output time in
// bolts.csv, and a layer of lines frames/bolts_NNNNNN.vtp listed by bolts.pvd.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "run_internal.hpp"

namespace rheodda::scene {

namespace fs = std::filesystem;

namespace {

const std::string bolts_header =
    "time,step,bolt,state,force,elongation,plastic_elongation,creep_elongation,length,rupture_time\n";

/// The bolt layer file of the frame whose blocks file is `blocks_file`.
std::string bolts_file(const std::string& blocks_file) {
  std::string f = blocks_file;
  const std::size_t at = f.rfind("blocks_");
  if (at != std::string::npos) f.replace(at, 7, "bolts_");
  return f;
}

/// The two ends of bolt k now [length] (the engine's bolt: material points, bolt.hpp).
std::pair<core::Vec2, core::Vec2> bolt_ends(const Run& run, std::size_t k) {
  const core::Bolt& b = run.engine.model().bolts[k];
  const core::Vec2 a = run.engine.point_position(b.block_a, b.point_a);
  return {a, b.block_b < 0 ? b.point_b : run.engine.point_position(b.block_b, b.point_b)};
}

/// The bolts as VTK PolyData lines, with their force, elongation and state as cell data.
std::string vtk_bolts(const Run& run) {
  const std::vector<core::BoltState>& st = run.engine.bolts();
  const std::size_t n = st.size();
  std::string s;
  s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  s += fmt::format("<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfLines=\"{}\">\n", 2 * n, n);
  s += "<Points>\n<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < n; ++k) {
    const auto [a, b] = bolt_ends(run, k);
    s += fmt::format("{:.17g} {:.17g} 0\n{:.17g} {:.17g} 0\n", a.x(), a.y(), b.x(), b.y());
  }
  s += "</DataArray>\n</Points>\n<CellData Scalars=\"force\">\n";
  auto reals = [&](const char* name, auto field) {
    s += fmt::format("<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
    for (const auto& b : st) s += fmt::format("{:.17g}\n", field(b));
    s += "</DataArray>\n";
  };
  reals("force", [](const core::BoltState& b) { return b.force; });
  reals("elongation", [](const core::BoltState& b) { return b.elongation; });
  reals("plastic_elongation", [](const core::BoltState& b) { return b.plastic_elongation; });
  reals("creep_elongation", [](const core::BoltState& b) { return b.creep_elongation(); });
  s += "<DataArray type=\"Int32\" Name=\"bolt\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < n; ++k) s += fmt::format("{}\n", k);
  s += "</DataArray>\n<DataArray type=\"Int32\" Name=\"state\" format=\"ascii\">\n";
  for (const auto& b : st) s += fmt::format("{}\n", static_cast<int>(b.state));
  s += "</DataArray>\n</CellData>\n<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < n; ++k) s += fmt::format("{} {}\n", 2 * k, 2 * k + 1);
  s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < n; ++k) s += fmt::format("{}\n", 2 * k + 2);
  s += "</DataArray>\n</Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return s;
}

}  // namespace

void refuse_resume_with_bolts(const SceneDescription& s, const RunOptions& o) {
  if (o.resume && has_bolts(s))
    throw std::invalid_argument(fmt::format(
        "--resume: {} has bolts, whose states a checkpoint does not hold yet (docs/reference/bolts.md, \"Limits\"); "
        "nothing was changed: run again without --resume",
        s.file));
}

void create_bolts_csv(Run& run) {
  const Units& u = run.s.units;
  run.bolts_csv.create((fs::path(run.out) / "bolts.csv").string());
  run.bolts_csv.append(fmt::format("# units: length={} force={} time={} stress={}\n", u.length, u.force, u.time,
                                   u.stress()) +
                       bolts_header);
}

void write_bolts_frame(Run& run, const std::string& blocks_file) {
  const core::Engine& e = run.engine;
  const std::vector<const BoltDescription*> bolts = all_bolts(run.s);  // the engine's order (bolts_text.hpp)
  std::string rows;
  for (std::size_t k = 0; k < e.bolts().size(); ++k) {
    const core::BoltState& b = e.bolts()[k];
    for (const auto& [name, v] : {std::pair<const char*, double>{"force", b.force},
                                  {"elongation", b.elongation},
                                  {"plastic_elongation", b.plastic_elongation},
                                  {"creep_elongation", b.creep_elongation()},
                                  {"length", b.length}})
      if (!std::isfinite(v))
        throw NonFinite(fmt::format("bolts.csv column '{}' of bolt '{}' is not finite at step {} (t = {:g} {})",
                                    name, bolts[k]->name, e.step_count(), e.time(), run.s.units.time));
    rows += fmt::format("{:.10g},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{}\n", e.time(), e.step_count(),
                        bolts[k]->name, core::bolt_mode_name(b.state), b.force, b.elongation,
                        b.plastic_elongation, b.creep_elongation(), b.length,
                        b.state == core::BoltMode::ruptured ? fmt::format("{:.10g}", b.rupture_time) : "");
  }
  run.bolts_csv.append(rows);
  const std::string file = bolts_file(blocks_file), text = vtk_bolts(run);
  write_file_atomic((fs::path(run.out) / file).string(), text);
  run.frames_bytes += text.size();
  run.bolt_frames.emplace_back(e.time(), file);
  write_file_atomic((fs::path(run.out) / "bolts.pvd").string(), vtk_collection(run.bolt_frames));
}

}  // namespace rheodda::scene
