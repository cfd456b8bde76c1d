// `rheodda check SCENE --refine`: is a scene's answer a result of the model or of
// its step controls? The scene is run at its own step controls and with every
// step control halved, again and again (a refinement study, docs/guide/choosing-step-controls.md
// "Checking a scene's step controls"), and the outputs of the levels are compared:
// they should converge (successive differences shrink, the last three agree within
// `converged`), and the scene's own level should lie within `tolerance` of the
// finest. The levels run as the cases of a study (study.hpp), so they run in
// parallel and leave a study folder that `rheodda plot` draws.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rheodda/study/study.hpp"

namespace rheodda::study {

struct RefinementOptions {
  int levels = 4;                ///< L0 (the scene as written) .. L(levels-1); >= 2
  std::optional<double> until;   ///< simulated time to run each level to [time]; default: the duration
  double tolerance = 0.05;       ///< largest relative difference of L0 from the finest level [-]
  double converged = 0.01;       ///< largest relative difference between the last three levels [-]
  /// Step controls kept at the scene's value on every level, by their scene key under
  /// `analysis` ("settle.dt", "settle.max_displacement_ratio", ...): a control whose own
  /// refinement is shown converged elsewhere, so that the study refines the others
  /// without paying for it (a settling stage's dynamic steps, docs/guide/choosing-step-controls.md).
  std::vector<std::string> hold;
};

/// A refinement study: the study (one case per level) and what each level's step
/// controls are, as text ("dt 0.0625 d, max_displacement_ratio 0.0005, ...").
struct RefinementStudy {
  StudyDescription study;
  std::vector<std::string> level_controls;
  std::string study_text;  ///< the study as a study file (YAML), to rerun with `rheodda study`
};

/// The refinement study of the scene at `scene_path`: level k divides by 2^k every
/// step control the scene uses: dt, max_displacement_ratio (g2), the settling stage's
/// dt, max_displacement_ratio and collapse_dt, step_tolerance or creep_tolerance and
/// dt_max where set; but those in `options.hold` (std::invalid_argument for a key that
/// is not one of them, listing them). Its outputs are every measurement point's displacement, every recorded joint
/// set's mean shear-displacement magnitude and, under gravity, the work of gravity
/// (and of the loads, when there are any); the times are half-way and the end.
/// `study_file` is where the study is written (errors are located in it). Throws
/// SceneError for a scene the loader refuses and std::invalid_argument for options
/// out of range.
RefinementStudy refinement_study(const std::string& scene_path, const std::string& study_file,
                                 const RefinementOptions& options);

/// One output at one time over the levels.
struct RefinementQuantity {
  std::string output;  ///< history.csv column (POINT.displacement as in studies)
  double time = 0.0;   ///< [time]
  std::vector<std::optional<double>> values;  ///< per level; empty when the level did not reach the time
  std::vector<double> differences;  ///< |v_k - v_{k-1}| / scale, k = 1..levels-1 [-]
  double scale = 0.0;               ///< the largest |v_k| over the levels [output unit]
  double reference = 0.0;           ///< the finest level's value, or the Richardson limit when the
                                    ///< last three levels approach one monotonically [output unit]
  bool extrapolated = false;        ///< reference is the Richardson limit
  double error = 0.0;               ///< |v_0 - reference| / scale: L0's error [-]
  bool judged = true;               ///< false: too small to judge (below 1 % of the largest of its kind)
  bool converged = false;           ///< the last two differences <= converged (the last three levels
                                    ///< agree) and the last not larger than the one before unless
                                    ///< below converged / 2 (scatter, not a trend)
  int first_within = -1;            ///< first level from which on every level is within `tolerance`
                                    ///< of the reference (-1: none)
};

enum class RefinementVerdict {
  fine,           ///< converged, and L0 within the tolerance of the finest level
  coarse,         ///< converged, but L0 farther than the tolerance: use a finer level
  not_converged,  ///< the levels do not converge: the answer depends on the step controls
  incomplete      ///< a level failed or did not reach a time
};

struct RefinementAssessment {
  std::vector<RefinementQuantity> quantities;
  RefinementVerdict verdict = RefinementVerdict::fine;
  int recommended_level = -1;  ///< coarse: the first level every judged quantity is within tolerance at
  double largest_error = 0.0;  ///< the largest `error` of a judged quantity [-]
  double largest_inertia_share = 0.0;  ///< static analyses: the largest inertia_share of a level [-]
  std::string message;         ///< one paragraph: the verdict and what to do
};

/// Compares the levels' results (run_study's, in level order).
RefinementAssessment assess_refinement(const RefinementStudy& refinement, const std::vector<CaseResult>& results,
                                       const RefinementOptions& options);

/// The table a person reads: per level its controls, steps, wall time and inertia
/// share; per quantity its values, successive differences and L0's error; then the verdict.
std::string refinement_report(const RefinementStudy& refinement, const std::vector<CaseResult>& results,
                              const RefinementAssessment& assessment, const RefinementOptions& options);

/// The same as JSON (refinement.json, for scripts): the options, per level its name,
/// controls, status, steps, wall time and inertia share, per quantity its values,
/// differences, reference and error, then the verdict, message and recommended level.
std::string refinement_json(const RefinementStudy& refinement, const std::vector<CaseResult>& results,
                            const RefinementAssessment& assessment, const RefinementOptions& options);

/// "fine", "coarse", "not converged", "incomplete".
const char* verdict_name(RefinementVerdict v);

}  // namespace rheodda::study
