// The columns of history.csv declared once: each by its name (or, for a column per
// measurement point or recorded joint set, the suffix after that name), its unit and its
// meaning, in the order of a row. Everything that lists them reads them from here: the
// run's header and the study's check of its outputs (history_columns, run_writer.cpp),
// Python's Simulation.history() (python/src/simulation.cpp), the plots' axis units
// (history_column_unit, plot.cpp), and the table of docs/reference/outputs.md
// (`rheodda keys --markdown history`, spliced by scripts/scene-format-tables.sh between
// <!-- history:begin/end -->, checked by a test). What a row's values are stays in
// history_row (run_writer.cpp), in this order.
#pragma once

#include <string>
#include <vector>

namespace rheodda::scene {

/// Which part of a history.csv row a column is in, and when a scene's run has it.
enum class HistoryPart {
  step,           ///< every row, first: the row's step
  point,          ///< per measurement point, `<point>` and the suffix
  point_settled,  ///< per measurement point after its `.u`, `.v`; with a settling stage (`analysis.settle`) only
  joint_set,      ///< per joint set with `record: true`, `<joint_set>` and the suffix
  energy,         ///< every row: the energy balance (kHistoryEnergyColumns, output.hpp)
  bolt,           ///< with bolts only, after the energy balance
  stage,          ///< with `stages:` only, last
};

/// Columns of history.csv declared together: one row of docs/reference/outputs.md's table.
struct HistoryColumns {
  HistoryPart part = HistoryPart::step;
  std::vector<std::string> names;  ///< the columns, or the suffixes (".u") of a per-point or per-joint set part
  std::string unit;                ///< "time", "length", "force", "force·length", "–"
  std::string meaning;             ///< one table cell
};

/// Every declaration, in the order of a row.
const std::vector<HistoryColumns>& history_column_specs();

/// The names (or suffixes) of the part `p`, in the order of a row.
std::vector<std::string> history_part_columns(HistoryPart p);

/// The columns of a row, in order: the step's, each point's (`settled`: with those after the
/// settling stage), each recorded joint set's, the energy balance, the bolts' (`bolts`) and
/// the stage (`stages`). A run's history.csv (history_columns, output.hpp) and Python's
/// Simulation.history() (which keeps neither the settled, bolt nor stage columns) are these.
std::vector<std::string> history_columns_of(const std::vector<std::string>& points, bool settled,
                                            const std::vector<std::string>& recorded_joint_sets, bool bolts,
                                            bool stages);

/// docs/reference/outputs.md's table of history.csv's columns (`| column | unit | meaning |`).
std::string history_table_markdown();

}  // namespace rheodda::scene
