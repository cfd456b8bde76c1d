// Laboratory creep curves read from CSV: time, shear displacement and the
// applied shear stress, either one value (or staged history) for the whole
// file or one value per row (a stage column). See docs/guide/fitting.md.
//
// Conventions a fit relies on (docs/guide/fitting.md, "The CSV format"):
//   - time is measured from the first loading: the first stage starts at t = 0;
//   - a row recorded at a stage start holds the displacement just after the
//     stress change (the instantaneous jump F/E1 included);
//   - with a stress column, a stage starts at the time of the first row that
//     carries a new stress value.
#pragma once

#include <cstddef>
#include <filesystem>
#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rheodda/laws/history.hpp"

namespace rheodda::fit {

/// Error in user-given creep data: names the file, the line (1-based, 0 if the
/// whole file is meant) and the column (empty if none).
class DataError : public std::runtime_error {
 public:
  DataError(std::string file, std::size_t line, std::string column, const std::string& message);
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  const std::string& column() const { return column_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string column_;
};

/// Which columns to read and where the stress comes from.
struct CsvOptions {
  std::string time_column = "t";                   ///< time [time]
  std::string displacement_column = "displacement";  ///< total shear displacement [length]
  /// Shear stress per row [stress]; when empty, `stress` must be given.
  std::string stress_column;
  /// Shear stress of the whole file [stress]: one stage "0:VALUE" or a staged
  /// history "T:V[,T:V...]" (laws::StagedHistory). Used when stress_column is empty.
  std::optional<laws::StagedHistory> stress;
  /// Measurement standard deviation of each row's displacement [length]
  /// (`--sigma-column`): the fit then minimizes sum ((d_model - d)/sigma)^2.
  /// Empty: every point weighs the same. Each cell must be finite and > 0.
  std::string sigma_column;
};

/// One stage of constant stress and the rows measured during it.
struct StageInfo {
  double t = 0.0;            ///< start time [time]
  double stress = 0.0;       ///< shear stress from t on [stress]
  std::size_t first = 0;     ///< index of the first point of the stage
  std::size_t count = 0;     ///< number of points in the stage
};

/// A creep curve ready to fit.
struct CreepData {
  std::string source;               ///< file name used in messages
  std::vector<double> t;            ///< strictly increasing times >= 0 [time]
  std::vector<double> displacement; ///< total shear displacement [length]
  std::vector<std::size_t> line;    ///< file line of each point (1-based)
  laws::StagedHistory history;      ///< applied shear stress [stress]
  std::vector<StageInfo> stages;    ///< one per history stage, with its points
  /// Measurement standard deviation of each point [length]; empty when not
  /// given (all points weigh the same). Same size as t otherwise, all > 0.
  std::vector<double> sigma;
  std::string time_column, displacement_column, stress_column, sigma_column;  ///< as read
};

/// Parses comma-separated text: a header row naming the columns, then one row
/// per sample; blank lines and lines starting with '#' are skipped. Throws
/// DataError naming `source`, the line and the column for a missing column, a
/// cell that is not a finite number, a negative or non-increasing time, a row
/// with the wrong number of cells, a stage without points, no data rows.
CreepData parse_creep_csv(std::istream& in, const std::string& source, const CsvOptions& options);

/// Reads a file with parse_creep_csv; throws DataError if it cannot be opened.
CreepData read_creep_csv(const std::filesystem::path& path, const CsvOptions& options);

}  // namespace rheodda::fit
