// `rheodda study`: one base scene plus a list of variations, run as independent
// cases in parallel, their results gathered into one table and one plot
// (docs/studies.md).
//
// A study file (YAML) names a base scene and a list of cases; each case changes
// scene keys by dotted paths (`set: {joint_sets.base.friction_angle: 40}`). Every
// case scene is built and validated before anything runs (a bad study is refused
// whole, with the study file's line and key). Each case then runs as a child
// process of the rheodda binary (`rheodda run`) in OUTDIR/cases/NAME/: a case that
// fails or crashes is reported in study.csv and does not affect the others.
#pragma once

#include <csignal>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/scene/error.hpp"

namespace rheodda::study {

using scene::SceneError;
using scene::SourceLocation;

/// One scene key changed by a case: `key` is a dotted path into the scene file
/// (map keys, `[N]` for the N-th list element, `[NAME]` for the list element whose
/// `name` is NAME), `value_yaml` the new value as YAML text (scalar, list or map).
struct Override {
  std::string key;         ///< e.g. "joint_sets.base.friction_angle", "blocks[block3].fixed"
  std::string value_yaml;  ///< e.g. "40", "{name: maxwell, E1: 1e8, eta1: 1e8}"
  SourceLocation where{};  ///< of the key in the study file
};

struct StudyCase {
  std::string name;                ///< folder name under OUTDIR/cases/: letters, digits, '_', '-', '.'
  std::vector<Override> set;       ///< the study's `set` first, then the case's own
  SourceLocation where{};
};

struct StudyDescription {
  std::string file;                ///< the study file's path as given
  std::string title;               ///< `title:`; default: the file name
  std::string scene;               ///< base scene path (relative ones resolved against the study file's folder)
  SourceLocation scene_where{};    ///< of the `scene:` value in the study file
  std::vector<std::string> outputs;  ///< history.csv columns, or `POINT.displacement` = hypot(POINT.u, POINT.v)
  std::vector<double> times;       ///< times the outputs are read at [scene time unit]; linear interpolation
  std::string plot;                ///< the output overlaid across cases in study.png; default: outputs[0]
  std::vector<StudyCase> cases;
  std::size_t common_count = 0;    ///< the first common_count overrides of each case's `set` are the study's `set`
};

/// Reads and checks the study file (keys, types, names); throws SceneError with
/// the study file, line, column and key.
StudyDescription load_study(const std::string& path);
StudyDescription parse_study(const std::string& text, const std::string& file);

/// The base scene text with the case's overrides applied (YAML). Throws SceneError
/// located at the override in the study file when a path does not resolve.
/// Unless the case sets `title` itself, the case scene's title is the base scene's
/// title (or file name) followed by the case's name and changes, case_title().
/// The case's own changes come first, then the study's common `set`.
std::string case_scene_text(const StudyDescription& study, const std::string& base_text, const StudyCase& c);

/// Builds every case scene and validates it with the scene loader, and checks that
/// every output names a column the case's history.csv will have. Returns the case
/// scene texts in case order. Throws SceneError located in the study file.
std::vector<std::string> prepare_cases(const StudyDescription& study);

/// The title of a case scene: "BASE [case NAME: key = value, key removed, ...]", listing
/// the case's own overrides first, then the study's common ones (docs/studies.md).
std::string case_title(const std::string& base_title, const StudyCase& c, std::size_t common_count);

struct StudyOptions {
  std::string out_dir;         ///< created if missing; cases go to out_dir/cases/NAME/
  int jobs = 0;                ///< cases run at once; 0: the machine's hardware threads
  std::string rheodda_binary;  ///< the program run per case (`rheodda run`); empty: this process's executable
  bool progress = false;       ///< one line on stderr per finished case
  bool plot = true;            ///< draw study.png with gnuplot
  /// When non-null and set non-zero (e.g. by a SIGINT/SIGTERM handler): the running
  /// cases are stopped (SIGTERM: each stops after its step and keeps a checkpoint),
  /// no further case starts, study.csv is written with each case's state, and
  /// run_study returns; `resume` continues it.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// Continue a study in out_dir: a case whose folder holds a completed run of the
  /// same scene text is kept, an interrupted one is resumed (`rheodda run --resume`),
  /// the others run from the start.
  bool resume = false;
};

struct CaseResult {
  std::string name;
  std::string status;    ///< "completed", "failed", "interrupted" (stopped, resumable) or "not started"
  std::string message;   ///< why it failed (empty when completed)
  int exit_code = 0;     ///< of the child `rheodda run` (-1: killed by a signal)
  int steps = 0;         ///< accepted steps (summary.json)
  double wall_seconds = 0.0;  ///< the case process's wall time [s]
  /// values[i * times.size() + j]: output i at times[j]; empty when the run did not reach the time.
  std::vector<std::optional<double>> values;
};

/// Runs every case (at most `jobs` at once), writes out_dir/study.csv and, unless
/// disabled, out_dir/study.png (+ study.gp, study_plot.dat). Throws SceneError for
/// a bad study (nothing is run then).
std::vector<CaseResult> run_study(const StudyDescription& study, const StudyOptions& options);

/// Reads output `column` of a run's history.csv as (time, value) pairs;
/// `POINT.displacement` is derived as hypot(POINT.u, POINT.v). Throws std::runtime_error.
std::vector<std::pair<double, double>> read_history_series(const std::string& history_csv, const std::string& column);

/// Linear interpolation of a series at t; nullopt outside its time range.
std::optional<double> value_at(const std::vector<std::pair<double, double>>& series, double t);

}  // namespace rheodda::study
