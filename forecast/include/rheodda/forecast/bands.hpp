// What `rheodda forecast` makes of its ensemble's histories (docs/guide/forecast.md):
// the derived point displacements, the percentile bands of every column, the
// probability that a column exceeds a threshold, the fan chart of one column.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rheodda/forecast/forecast.hpp"

namespace rheodda::forecast {

/// The index of the column `name` of `h`, if it has one.
std::optional<std::size_t> column_index(const History& h, const std::string& name);

/// Adds POINT.displacement = hypot(POINT.u, POINT.v) [length] for each measurement
/// point of `h`, and POINT.displacement_after_settling of its columns after settling
/// (as `rheodda study` reads them).
void add_point_displacements(History& h);

/// bands.csv: at each of `times` (the run's output times) [time], the percentiles
/// `percentiles` of every column of `columns` across the members that have a finite
/// value there (interpolated in time, history_at), and how many members had one.
void write_bands(const std::string& path, const std::vector<History>& members, const std::vector<std::string>& columns,
                 const std::vector<double>& percentiles, const std::vector<double>& times);

/// How many members' `column` exceeds a threshold by a time (its largest value up to then).
struct Exceedance {
  std::size_t members = 0;
  std::size_t exceeding = 0;
  double probability = 0.0;  ///< exceeding / members
  double std_error = 0.0;    ///< binomial standard error sqrt(p (1 - p) / members)
};
Exceedance exceedance(const std::vector<History>& members, const std::string& column, double threshold, double by);

/// The fan chart of one column of bands.csv (fan.gp, drawn into fan.png by gnuplot).
struct FanChart {
  std::string out_dir;                    ///< holds bands.csv; fan.gp and fan.png are written there
  std::vector<std::string> band_columns;  ///< bands.csv's columns, in order
  std::vector<double> percentiles;        ///< as bands.csv holds them
  std::string column;                     ///< the column drawn
  bool units_line = false;                ///< bands.csv starts with a "# units" line
  std::string title, time_unit, length_unit;
  std::optional<double> threshold;        ///< drawn as a dashed line
};
/// Writes fan.gp (the outer bands lighter, the median) and runs gnuplot on it; throws
/// std::runtime_error when gnuplot fails.
void draw_fan_chart(const FanChart& c);

}  // namespace rheodda::forecast
