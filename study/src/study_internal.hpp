// Internal to rheodda_study: what the study file's reader (study_file.cpp), its case scenes
// (study_cases.cpp), the runner (runner.cpp), the study's record (study_report.cpp) and its
// pictures (study_plots.cpp) share.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "rheodda/scene/scene.hpp"
#include "rheodda/study/study.hpp"

namespace YAML {
class Node;
}

namespace rheodda::study::detail {

/// Applies one override of a study file `file` (`case_key`: "set" or "cases[NAME].set") to a
/// scene's YAML tree; throws SceneError at the override (study_file.cpp).
void apply(YAML::Node root, const Override& o, const std::string& file, const std::string& case_key);

/// The history.csv columns a scene's run will have (scene::history_columns), and the derived
/// POINT.displacement (with a settling stage also POINT.displacement_after_settling).
std::set<std::string> output_columns(const scene::SceneDescription& s);

/// The whole file as bytes ("" when it cannot be read).
std::string read_text(const std::filesystem::path& p);

/// The fields of a CSV line split at every comma (no quoting; a '\r' dropped).
std::vector<std::string> split_csv_line(const std::string& line);

/// Shortest text that reads back as the same double.
std::string format_value(double v);

/// study.csv's column of `output` at time `t`: "OUTPUT@T", T as %g (e.g. block.u@100,
/// x@1e+06), or as format_value where %g would not read back as `t` (0.1234567, not 0.123457).
std::string output_column(const std::string& output, double t);

/// study.csv: one row per case, its parameters, outputs at the study's times, wall time, steps and message.
void write_study_csv(const StudyDescription& study, const std::vector<CaseResult>& results,
                     const std::filesystem::path& path);

/// study.json: what `rheodda plot OUTDIR` needs besides study.csv to redraw a study.
void write_study_json(const StudyDescription& study, const std::filesystem::path& path);

}  // namespace rheodda::study::detail
