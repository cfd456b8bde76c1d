// What the pictures of `rheodda plot` share (plot.cpp, plot_bolts.cpp,
// plot_contacts.cpp): gnuplot's quoting and terminals, and a CSV output of the run
// read by its header.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace rheodda::scene {

/// Characters per title line of a 1000-pixel picture.
inline constexpr std::size_t kPlotTitleWidth = 110;

/// `s` as a gnuplot single-quoted string.
std::string gnuplot_quote(const std::string& s);

/// The `set terminal` line of a picture of w x h pixels in `format` ("png" or "svg").
std::string gnuplot_terminal(const std::string& format, int w, int h);

/// The cells of one row of a CSV output of the run (no quoting: the run writes none).
std::vector<std::string> csv_cells(const std::string& line);

/// Reads a CSV output of the run (lines starting with '#' skipped, the first other
/// line its header): calls `row` with the header and each row's cells, in file order.
/// Throws std::runtime_error if the file cannot be read.
void for_each_csv_row(const std::string& path,
                      const std::function<void(const std::vector<std::string>& header,
                                               const std::vector<std::string>& cells)>& row);

}  // namespace rheodda::scene
