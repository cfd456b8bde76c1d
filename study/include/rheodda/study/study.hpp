// `rheodda study`: one base scene plus a list of variations, run as independent
// cases in parallel, their results gathered into one table and one plot
// (docs/guide/studies.md).
//
// A study file (YAML) names a base scene and a list of cases; each case changes
// scene keys by dotted paths (`set: {joint_sets.base.friction_angle: 40}`). Every
// case scene is built and validated before anything runs (a bad study is refused
// whole, with the study file's line and key). Each case then runs as a child
// process of the rheodda binary (`rheodda run`) in OUTDIR/cases/NAME/: a case that
// fails or crashes is reported in study.csv and does not affect the others.
#pragma once

#include <csignal>
#include <cstdint>
#include <functional>
#include <memory>
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
  /// Value of each swept parameter (StudyDescription::parameters) [its unit]; empty
  /// for a case listed by hand under `cases`.
  std::vector<double> parameter_values;
  /// The case scene's title suffix "name = value unit, ..." of a swept case; empty for a listed case.
  std::string sweep_label;
};

/// How a sweep turns its parameters into cases (docs/guide/studies.md, "Sweeps").
enum class SweepMethod {
  grid,             ///< every combination of the parameters' values (product)
  random,           ///< `samples` independent draws, uniform in each range (or in its logarithm)
  latin_hypercube,  ///< `samples` draws, one in each of `samples` equal strata of every range
};

/// One swept parameter: a scene key (any map key or law parameter) and its values.
struct SweepParameter {
  std::string name;      ///< short name: case names, titles, the study.csv column "NAME [UNIT]"
  std::string key;       ///< dotted scene key, as in `set` (e.g. joint_sets.base.law.E1)
  std::string unit;      ///< written next to the values (study.csv header, plots); "-" if none
  bool log_scale = false;  ///< `scale: log`: ranges spaced/drawn in the logarithm, plot axes logarithmic
  std::vector<double> values;  ///< grid: the listed values, or `count` values spanning `range`
  double from = 0.0, to = 0.0;  ///< `range: [from, to]` (random and Latin-hypercube draws, grid ranges)
  SourceLocation where{};
};

struct StudyDescription {
  std::string file;                ///< the study file's path as given
  std::string title;               ///< `title:`; default: the file name
  std::string scene;               ///< base scene path (relative ones resolved against the study file's folder)
  SourceLocation scene_where{};    ///< of the `scene:` value in the study file
  std::vector<std::string> outputs;  ///< history.csv columns, or `POINT.displacement` = hypot(POINT.u, POINT.v)
                                     ///< (`POINT.displacement_after_settling` of the columns after settling)
  std::vector<double> times;       ///< times the outputs are read at [scene time unit]; linear interpolation
  std::string plot;                ///< the output overlaid across cases in study.png; default: outputs[0]
  /// `frames`: each case also writes contacts.csv, bolts.csv and the VTK frames (for `rheodda
  /// plot` of a case's blocks, ParaView); false (the default): history.csv, events.csv and
  /// summary.json only (analysis.frames: false in each case scene).
  bool frames = false;
  std::vector<StudyCase> cases;    ///< the listed cases first, then the sweep's
  std::size_t common_count = 0;    ///< the first common_count overrides of each case's `set` are the study's `set`
  std::vector<SweepParameter> parameters;  ///< `sweep.parameters`; empty without a sweep
  SweepMethod method = SweepMethod::grid;
  std::size_t samples = 0;         ///< random / Latin-hypercube draws
  std::uint64_t seed = 0;          ///< of the draws (std::mt19937_64); the same seed gives the same cases
};

/// The values a sweep draws: row k holds sample k's value of each parameter, in
/// parameter order. Grid: the product (last parameter fastest). Random: uniform in
/// [from, to] (or in [ln from, ln to] with log_scale). Latin hypercube: for each
/// parameter, a random permutation of the `samples` strata of [0, 1), a uniform draw
/// inside the stratum (McKay, Beckman & Conover 1979), mapped as for random.
std::vector<std::vector<double>> sweep_values(const std::vector<SweepParameter>& parameters, SweepMethod method,
                                              std::size_t samples, std::uint64_t seed);

/// Reads and checks the study file (keys, types, names); throws SceneError with
/// the study file, line, column and key.
StudyDescription load_study(const std::string& path);
StudyDescription parse_study(const std::string& text, const std::string& file);

/// The base scene text with the case's overrides applied (YAML). Throws SceneError
/// located at the override in the study file when a path does not resolve. The study's
/// `times` (those within the case's duration) join the case's analysis.output_times, so
/// that its history.csv has a row at each; analysis.frames is the study's `frames` unless
/// the case sets it.
/// Unless the case sets `title` itself, the case scene's title is the base scene's
/// title (or file name) followed by the case's name and changes, case_title().
/// The case's own changes come first, then the study's common `set`.
std::string case_scene_text(const StudyDescription& study, const std::string& base_text, const StudyCase& c);

/// Builds every case scene and validates it with the scene loader, and checks that
/// every output names a column the case's history.csv will have. Returns the case
/// scene texts in case order. Throws SceneError located in the study file. When `stop`
/// is set non-zero (a signal) it returns at once, with the texts prepared so far.
std::vector<std::string> prepare_cases(const StudyDescription& study,
                                       const volatile std::sig_atomic_t* stop = nullptr);

/// A case scene's text without its header comment (the leading '#' lines, which name
/// the study and the base scene by their paths as typed): what `--resume` compares to
/// recognise a case already run, whatever the spelling of the paths.
std::string case_scene_body(const std::string& text);

/// The folder name of drawn case k (0-based) of `count` (random and Latin-hypercube
/// sweeps, forecast members): "sample" and k + 1 zero-padded to at least two digits and
/// to the digits of `count`: sample07 of 20, sample007 of 100 to 999.
std::string drawn_case_name(std::size_t k, std::size_t count);

/// The title of a case scene: "BASE [case NAME: key = value, key removed, ...]", listing
/// the case's own overrides first, then the study's common ones (docs/guide/studies.md).
std::string case_title(const std::string& base_title, const StudyCase& c, std::size_t common_count);

/// A case handed to an executor: its index in the study and its folder (scene.yaml in it).
struct CaseTask {
  std::size_t index = 0;
  std::string dir;      ///< OUTDIR/cases/NAME
  bool resume = false;  ///< `rheodda run --resume` (an interrupted case)
};

/// How a case process ended.
struct CaseOutcome {
  std::size_t index = 0;
  int exit_code = 0;          ///< of the case process; -1 when a signal ended it
  int signal = 0;             ///< the signal that ended it (0: none)
  double wall_seconds = 0.0;  ///< the case process's wall time [s]
  std::string error;          ///< the case could not be started (e.g. a missing program); empty otherwise
};

/// Where cases run: child processes of this one (local_executor), or MPI ranks
/// (study/mpi). run_study starts cases while running() < capacity() and polls.
class CaseExecutor {
 public:
  virtual ~CaseExecutor() = default;
  virtual std::size_t capacity() const = 0;  ///< cases at once
  virtual std::size_t running() const = 0;   ///< cases started and not yet reported
  /// Starts a case (as `PROGRAM run DIR/scene.yaml -o DIR`, output in DIR/log.txt).
  virtual void start(const CaseTask& task) = 0;
  /// A finished case, or nullopt after a short wait (a few ms) when none has finished.
  virtual std::optional<CaseOutcome> poll() = 0;
  /// SIGTERM to every running case (each stops after its step, keeping a checkpoint).
  virtual void stop_all() = 0;
};

/// Child processes of this one, at most `jobs` at once, each `binary run ...`; poll()
/// sleeps `poll_sleep_ms` [ms] when no case has finished (0: returns at once).
std::unique_ptr<CaseExecutor> local_executor(const std::string& binary, std::size_t jobs, int poll_sleep_ms = 5);

struct StudyOptions {
  std::string out_dir;         ///< created if missing; cases go to out_dir/cases/NAME/
  int jobs = 0;                ///< cases run at once; 0: the machine's hardware threads
  std::string rheodda_binary;  ///< the program run per case (`rheodda run`); empty: this process's executable
  bool progress = false;       ///< a line on stderr per finished case, and the study's state between them
                               ///< (docs/reference/cli.md, "Progress")
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
  /// Where cases run; null: local_executor(rheodda_binary, jobs).
  CaseExecutor* executor = nullptr;
};

/// The program a case runs: options.rheodda_binary, else this process's executable.
std::string case_binary(const StudyOptions& options);

struct CaseResult {
  std::string name;
  std::string status;    ///< "completed", "failed", "interrupted" (stopped, resumable) or "not started"
  std::string message;   ///< why it failed (empty when completed)
  int exit_code = 0;     ///< of the child `rheodda run` (-1: killed by a signal)
  int steps = 0;         ///< accepted steps (summary.json)
  double wall_seconds = 0.0;  ///< the case process's wall time [s]
  /// Static analyses: the share of the work of gravity and loads the static steps'
  /// inertia term took (summary.json static_mechanism.inertia_share; docs/reference/engine.md,
  /// "Mechanisms in static analysis") [-]; empty for a dynamic case or without a summary.
  std::optional<double> inertia_share;
  /// values[i * times.size() + j]: output i at times[j]; empty when the run did not reach the time.
  std::vector<std::optional<double>> values;
};

/// Runs every case (at most `jobs` at once), writes out_dir/study.csv and, unless
/// disabled, out_dir/study.png (+ study.gp, study_plot.dat). Throws SceneError for
/// a bad study (nothing is run then).
std::vector<CaseResult> run_study(const StudyDescription& study, const StudyOptions& options);

/// True when `dir` holds a study's outputs (study.json and study.csv).
bool is_study_dir(const std::string& dir);

/// Draws a study from its folder (study.json, study.csv, cases/*/history.csv):
/// study.png (the `plot` output of every case against time) and, for a sweep,
/// study_sweep.png (the outputs against the swept parameters) and, for a grid of two
/// parameters, study_map.png. Returns the pictures written. Throws
/// std::invalid_argument for a folder that is not a study's, std::runtime_error
/// when gnuplot fails.
std::vector<std::string> plot_study_dir(const std::string& dir);

/// Reads output `column` of a run's history.csv as (time, value) pairs;
/// `POINT.displacement` is derived as hypot(POINT.u, POINT.v), and
/// `POINT.displacement_after_settling` as hypot(POINT.u_after_settling,
/// POINT.v_after_settling). Throws std::runtime_error.
std::vector<std::pair<double, double>> read_history_series(const std::string& history_csv, const std::string& column);

/// Linear interpolation of a series at t; nullopt outside its time range.
std::optional<double> value_at(const std::vector<std::pair<double, double>>& series, double t);

}  // namespace rheodda::study
