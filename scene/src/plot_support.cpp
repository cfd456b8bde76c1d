#include "plot_support.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rheodda/scene/plot.hpp"

namespace rheodda::scene {

std::string gnuplot_quote(const std::string& s) { return "'" + gnuplot_text(s) + "'"; }

std::string gnuplot_terminal(const std::string& format, int w, int h) {
  return format == "svg" ? fmt::format("set terminal svg size {},{} dynamic background rgb 'white'", w, h)
                         : fmt::format("set terminal pngcairo size {},{} font 'sans,11'", w, h);
}

std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(',', start);
    cells.push_back(line.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return cells;
}

void for_each_csv_row(const std::string& path,
                      const std::function<void(const std::vector<std::string>&, const std::vector<std::string>&)>& row) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", path));
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = csv_cells(line);
      continue;
    }
    row(header, csv_cells(line));
  }
}

}  // namespace rheodda::scene
