// What the parts of `rheodda run` (run.cpp) share: the state of one run, and
// the steps run_scene takes over it, each in the file of its concern:
// scene_json.cpp (the scene as summary.json's "inputs"), run_guards.cpp (the
// memory check, non-finite values, max_travel_ratio and max_output_size),
// run_writer.cpp (history.csv rows, contacts.csv and the VTK frames),
// run_checkpoint.cpp (checkpoint.json and --resume), run_summary.cpp
// (summary.json, RunResult's totals, the end-of-run warnings), run_progress.cpp
// (the progress display).
#pragma once

#include "rheodda/scene/describe.hpp"

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bolts_text.hpp"
#include "checkpoint_state.hpp"
#include "rheodda/contact/contact_system.hpp"
#include "rheodda/core/engine.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/run.hpp"
#include "run_progress.hpp"
#include "run_stages.hpp"
#include "run_totals.hpp"

namespace rheodda::scene {

using Clock = std::chrono::steady_clock;

/// Thrown by the step observer to leave Engine::run_until between two steps.
struct StopAfterStep {};

/// Thrown by the step observer when the state or an output row is no longer finite:
/// nothing of that step is written, and the last checkpoint stays the one to resume from.
struct NonFinite : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown by the step observer when a run guard (max_travel_ratio, max_output_size) trips.
struct GuardTripped : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One run of a scene into its output folder: what the steps of run_scene read and change.
struct Run {
  Run(const SceneDescription& scene, const RunOptions& options, RunResult& result, contact::ContactSystem& contacts,
      core::Engine& engine, const std::string& scene_text, Clock::time_point wall_start);

  const SceneDescription& s;
  const Analysis& a;
  const RunOptions& opt;
  RunResult& result;
  contact::ContactSystem& contacts;
  core::Engine& engine;
  const std::string out;              ///< the output folder
  const std::string scene_hash;       ///< FNV-1a of the scene text (hex)
  const std::string checkpoint_path;  ///< out/checkpoint.json
  const Clock::time_point wall_start;

  /// Initial vertex positions, for the displacement field of the frames and max_travel_ratio.
  std::vector<std::vector<core::Vec2>> initial;
  /// Output times (output_times(a)): a step ends on each, and a frame is written there.
  std::vector<double> frame_times;
  /// The output times and the stages' `at` times: history.csv has a row of the step
  /// that ends on each (history_row_due).
  std::vector<double> row_times;
  std::size_t rows_reached = 0;   ///< the row_times up to the last step's time [-]
  std::size_t events_seen = 0;    ///< the engine's dynamic stages that had ended at the last step [-]
  int failures_seen = 0;          ///< contacts whose damage law had failed at the last step [-]
  std::vector<int> recorded;   ///< the joint sets with `record` (history.csv columns)
  std::string history_header;  ///< history.csv's column line
  double model_size = 0.0;     ///< the larger side of the initial bounding box [length]

  CsvAppender history, contacts_csv;
  CsvAppender bolts_csv;  ///< bolts.csv, with bolts only (run_bolts.cpp)
  std::vector<std::pair<double, std::string>> bolt_frames;  ///< (time, bolts layer file) of each frame, with bolts
  std::vector<std::pair<double, std::string>> pvd;  ///< (time, blocks file) of each frame written
  std::vector<std::uint64_t> frame_hash;  ///< FNV-1a of each frame file, in pvd order
  std::uint64_t frames_bytes = 0;         ///< total size of the frames written by this process [byte]
  int frames_done = 0;
  double earlier_wall = 0.0;  ///< wall time of earlier (resumed) sessions [s]

  /// Steps run again without writing (a resume writing a lost frame again), up to the checkpoint's.
  enum class Mode { replay, record } mode = Mode::record;
  int replay_target = 0;
  RunProgress progress;  ///< the progress display (run_progress.cpp)
  RunTotals run_totals;
  int recorded_step;     ///< the last step whose outputs are written [-]
  StateFile state_file;  ///< the state file the last checkpoint names
  Clock::time_point last_checkpoint{};
  bool frame_open = false;  ///< a frame is being written (its rows may be in contacts.csv already)
  std::string inputs_text;      ///< scene_json_text of the scene, spliced into summary.json
  std::string scene_text_json;  ///< the scene text as a JSON string
  StageRun stage_run;           ///< the scene's stages (run_stages.cpp); unused without stages
  /// The contacts' shear stresses compared with what the laws were fitted to (law_choice.cpp)
  /// once settled: false until done, true from the start when no law asks for it.
  bool law_stresses_done = false;

  /// The index of the first output time after t, the engine's round-off sliver counting as reached.
  std::size_t next_output(double t) const;
  /// Takes up rows_reached, events_seen and failures_seen from the engine's state now (a
  /// new run, a resume): what history_row_due compares the next step with.
  void note_rows_state();
};

/// The index of the first of the increasing `times` after t, the engine's round-off
/// sliver counting as reached.
std::size_t index_after(const std::vector<double>& times, double t);

// scene_json.cpp: scene_json_text (rheodda/scene/describe.hpp).

// run_guards.cpp
/// Fails early when the run will not fit in memory (docs/notes/performance.md, "Memory").
void check_memory(const SceneDescription& s);
/// The first non-finite quantity of the engine's state ("velocity of block 'b3'"), or "".
std::string nonfinite_state(const core::Engine& e, const SceneDescription& s);
/// The name of the first column of a CSV row holding nan or inf, or "".
std::string nonfinite_column(const std::string& header, const std::string& row);
/// The larger side of the bounding box of `vertices` [length].
double model_size(const std::vector<std::vector<core::Vec2>>& vertices);
/// Throws GuardTripped when analysis.max_travel_ratio or max_output_size is exceeded.
void check_guards(const Run& run, const core::Engine& e);

// run_writer.cpp
/// history.csv's column line for the scene's measurement points and recorded joint sets.
std::string make_history_header(const SceneDescription& s);
/// history.csv's row of the engine's state after the step `r` (nullptr: the initial state).
std::string history_row(const Run& run, const core::StepReport* r);
/// Whether history.csv gets the row of the step `r` just taken (analysis.history): every
/// step, or the step that ends on an output time or a stage's time, ends a dynamic
/// stage, opens a collapse stage, or brings a contact's damage law to failure. Notes the
/// step as seen.
bool history_row_due(Run& run, const core::StepReport& r);
/// After the step just taken: the measurement points' displacements at the end of the
/// settling stage (analysis.settle), once it has ended (RunTotals::settled).
void note_settled(Run& run);
/// A new run's history.csv and contacts.csv: units, headers and the initial row.
void create_csv_files(Run& run);
/// A frame's blocks file: the blocks at the engine's current state.
std::string frame_text(const Run& run);
/// A frame's contacts file: each contact at its vertex with the fields of contacts.csv.
std::string contacts_frame_text(const Run& run);
/// The contacts file of the frame whose blocks file is `blocks_file`.
std::string contacts_file(const std::string& blocks_file);
/// The hash a checkpoint keeps of a frame's two files.
std::uint64_t frame_pair_hash(const std::string& blocks_text, const std::string& contacts_text);
/// blocks.pvd and contacts.pvd, listing the frames of run.pvd.
void write_collections(const Run& run);
/// The next frame: contacts.csv rows, the two frame files, the collections, a
/// checkpoint (at most one a second) and summary.json "running".
void write_frame(Run& run);

// run_bolts.cpp (scenes with bolts only)
/// Refuses --resume of a scene with bolts (their states are not in a checkpoint yet).
void refuse_resume_with_bolts(const SceneDescription& s, const RunOptions& o);
/// bolts.csv: units and header.
void create_bolts_csv(Run& run);
/// A frame's bolts: their rows of bolts.csv, frames/bolts_NNNNNN.vtp, bolts.pvd.
void write_bolts_frame(Run& run, const std::string& blocks_file);

// run_checkpoint.cpp
/// checkpoint.json and the state file it names, after syncing the CSVs it counts.
void write_checkpoint(Run& run);
/// Takes the run up from its checkpoint (--resume), writing lost frames again.
void resume_run(Run& run);

// run_stages.cpp (docs/reference/stages.md; only for a scene with stages)
/// The names of the model's fixed points and loads, before the first stage.
void start_stages(Run& run);
/// Step observer: throws StageDue when the stage waiting `after: settled` is due.
void watch_settling(Run& run, const core::Engine& e);
/// run_to_end with stages: the frames, and each stage at its time.
void run_staged_to_end(Run& run);

// run_summary.cpp
/// RunResult's totals as of now.
void collect_totals(Run& run);
/// summary.json with `status` ("running", "interrupted", "failed", "completed") and `error`.
void write_summary(Run& run, const std::string& status, const std::string& error);
/// The warnings of a completed run: creep laws that never acted, static mechanisms.
void add_end_warnings(Run& run);
/// The message of a run that failed on `e`: what failed, and of a singular system, which block.
std::string failure_text(const Run& run, const std::exception& e);

}  // namespace rheodda::scene
