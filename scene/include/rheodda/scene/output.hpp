// Output files of a run (docs/reference/outputs.md). Every file is either written whole
// (temporary file + rename, so a reader never sees half a file) or appended to
// line by line, each line complete and flushed before the next step, so an
// interrupted run leaves every file consistent.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/core/energy.hpp"
#include "rheodda/scene/scene.hpp"

namespace rheodda::scene {

/// The energy-balance columns that end every history.csv row, in order (docs/reference/outputs.md;
/// docs/reference/engine.md, "Energy balance"): stored energies now, flows since t = 0, the
/// residual and the step's inertia share.
inline constexpr std::array<const char*, 19> kHistoryEnergyColumns{
    "energy_kinetic",          "energy_strain",           "energy_fixed",
    "energy_contact_normal",   "energy_contact_shear",    "work_gravity",
    "work_loads",              "work_contact_restart",    "dissipation_friction",
    "dissipation_creep",       "dissipation_integration", "dissipation_contact_damping",
    "dissipation_block_damping", "dissipation_contact_closing", "dissipation_contact_release",
    "dissipation_edits",       "energy_residual",         "energy_residual_relative",
    "inertia_share"};

/// The values of kHistoryEnergyColumns, in that order, of a run's balance now.
inline std::array<double, kHistoryEnergyColumns.size()> history_energy_values(const core::EnergyBalance& en) {
  const core::StoredEnergy& st = en.stored;
  const core::EnergyFlows& fl = en.total;
  return {st.kinetic, st.strain, st.fixed, st.contact_normal, st.contact_shear,
          fl.work_gravity, fl.work_loads, fl.work_contact_restart,
          fl.dissipation_friction, fl.dissipation_creep, fl.dissipation_integration,
          fl.dissipation_contact_damping, fl.dissipation_block_damping, fl.dissipation_contact_closing,
          fl.dissipation_contact_release, fl.dissipation_edits, fl.residual, en.relative_residual(),
          core::inertia_share(en.step)};
}

/// The columns of a run's history.csv, in order (docs/reference/outputs.md): the one
/// list the run writes (run_writer.cpp) and a study checks its outputs against.
std::vector<std::string> history_columns(const SceneDescription& s);

/// A run's output times, increasing (docs/reference/outputs.md): 0, k × output_interval,
/// the `output_times` and the duration, times within 1e-9 × duration of each other
/// counted once [time]. A step ends on each; each has a frame and a history.csv row.
std::vector<double> run_output_times(const Analysis& a);

/// Writes `content` to `path` through `path + ".tmp"` and a rename, so that a reader
/// (or a run killed at any moment) sees either the old or the new content. With
/// `durable`, the file is also flushed to disk (fsync) before the rename and the rename
/// after it (fsync of the folder), so that this holds across a power loss as well
/// (the checkpoint; ~4 ms per call here, too slow for every frame). On failure the
/// `.tmp` file is removed and std::runtime_error names the file and the system's
/// reason (e.g. "No space left on device").
void write_file_atomic(const std::string& path, const std::string& content, bool durable = false);

/// Flushes a folder's entries (renames, removals) to disk; best effort.
void sync_directory(const std::string& path);

/// "cannot write PATH: REASON" from errno, with the advice a full disk needs.
std::string write_error(const std::string& path, int error_number);

/// Reads a whole file; throws std::runtime_error.
std::string read_file(const std::string& path);

/// Removes from `dir` what an earlier run and `rheodda plot` wrote there: the files of
/// docs/reference/outputs.md's table (history.csv, contacts.csv, bolts.csv, events.csv,
/// the .pvd collections, summary.json, checkpoint.json and its state files, and a `.tmp`
/// of any of them), the frames in frames/ (*.vtp) and the pictures in plots/ (*.png,
/// *.svg and their *.gp scripts and *.dat data), and plots/ when that empties it. Nothing else: files of the user's own stay. A run that starts without
/// --resume calls it, so a folder holds one run's outputs. Throws std::runtime_error
/// naming a file that cannot be removed.
void remove_run_outputs(const std::string& dir);

/// Exclusive use of an output folder by one run: an advisory lock (flock) on
/// DIR/.rheodda.lock holding the owner's process id. The object's destruction (the
/// run's end, however it ends short of the process being killed) removes the file;
/// the flock goes with the process too (also on kill -9), so a lock file a killed
/// run left does not block the next one (nor, on a file system without flock, one
/// whose process no longer runs). Throws std::runtime_error naming the folder and
/// the process that holds it.
class FolderLock {
 public:
  explicit FolderLock(const std::string& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

/// A CSV file appended line by line; each line is flushed whole. It keeps the
/// FNV-1a hash of everything it holds, so that a checkpoint can record what a
/// resume must find.
class CsvAppender {
 public:
  CsvAppender() = default;
  /// Creates `path` empty.
  void create(const std::string& path);
  /// Continues `path` from a checkpoint: the file must hold at least `keep_bytes`
  /// bytes whose hash is `keep_hash`; what follows them is dropped (the run writes
  /// it again identically). Throws std::invalid_argument naming the file and what
  /// differs when it is shorter or its kept bytes differ: nothing is changed then.
  void resume(const std::string& path, std::uint64_t keep_bytes, std::uint64_t keep_hash);
  ~CsvAppender();
  CsvAppender(const CsvAppender&) = delete;
  CsvAppender& operator=(const CsvAppender&) = delete;
  /// Appends `line` (which must end in '\n') and flushes it to the system.
  void append(const std::string& line);
  /// Flushes the file to disk (fsync): before a checkpoint that counts its bytes.
  void sync();
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t hash() const { return hash_; }

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::uint64_t bytes_ = 0;
  std::uint64_t hash_ = 1469598103934665603ull;  ///< FNV-1a of the bytes_ bytes held
};

/// One polygon of a VTK frame with its fields.
struct FrameBlock {
  std::vector<std::array<double, 2>> vertices;      ///< current [length]
  std::vector<std::array<double, 2>> displacement;  ///< per vertex, current - initial [length]
  std::array<double, 3> stress{};                   ///< (sigma_x, sigma_y, tau_xy) [stress]
  std::array<double, 3> velocity{};                 ///< (vx, vy [length/time], omega [1/time])
  int material = 0;
  bool fixed = false;
  /// Removed by a stage (docs/reference/stages.md); set for every block of a scene with
  /// stages (the frames then have a `removed` array), unset otherwise.
  std::optional<bool> removed;
};

/// A VTK XML PolyData file (.vtp, ASCII) of the blocks at one time.
std::string vtk_polydata(const std::vector<FrameBlock>& blocks);

/// One contact of a VTK contact frame: a point at the contact vertex with the
/// fields of contacts.csv (docs/reference/outputs.md, "VTK frames").
struct FrameContact {
  std::array<double, 2> point{};  ///< the contact vertex, current [length]
  int id = 0;                     ///< as contacts.csv's id
  int joint_set = 0;              ///< index of the joint set in the scene's order
  int state = 0;                  ///< 0 open, 1 sliding, 2 locked
  int kind = 0;                   ///< 0 vertex-edge, 1 vertex-vertex, 2 edge-edge
  double normal_force = 0.0;       ///< [force] (per unit thickness)
  double shear_force = 0.0;        ///< [force]
  double shear_strength = 0.0;     ///< Mohr-Coulomb strength N tan(phi) + c l, residual once not intact [force]
  double shear_displacement = 0.0; ///< accumulated, signed along the entrance edge [length]
  double creep_displacement = 0.0; ///< accumulated by the joint set's law [length]
  double penetration = 0.0;        ///< [length]
  double length = 0.0;             ///< contact length (0 for a point contact) [length]
  double tributary_length = 0.0;   ///< the joint length the contact stands for [length]
  std::optional<double> water_pressure;  ///< at the point, scenes with water only [stress] (docs/reference/water.md)
};

/// A VTK XML PolyData file (.vtp, ASCII) of the contacts at one time: one vertex
/// cell per contact, its fields as point data.
std::string vtk_contacts(const std::vector<FrameContact>& contacts);

/// A ParaView collection (.pvd) listing (time, file) frames.
std::string vtk_collection(const std::vector<std::pair<double, std::string>>& frames);

/// Reads the polygons back from a .vtp written by vtk_polydata (for `rheodda plot`):
/// per block, its current vertices and per-vertex displacement.
std::vector<FrameBlock> read_vtk_polydata(const std::string& path);

/// 64-bit FNV-1a hash of bytes (scene identity in checkpoints).
std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h = 1469598103934665603ull);

}  // namespace rheodda::scene
