// The fan chart of `rheodda forecast` (bands.hpp): percentile bands of one column of
// bands.csv, the outer bands lighter, the median, the threshold.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "rheodda/forecast/bands.hpp"
#include "rheodda/scene/plot.hpp"

namespace rheodda::forecast {

void draw_fan_chart(const FanChart& c) {
  namespace fs = std::filesystem;
  const fs::path out = c.out_dir;
  std::vector<double> ps = c.percentiles;
  std::sort(ps.begin(), ps.end());
  const fs::path gp = out / "fan.gp";
  std::ofstream g(gp);
  const auto col_of = [&](double p) {  // column number in bands.csv (1-based)
    const auto ci = static_cast<std::size_t>(std::find(c.band_columns.begin(), c.band_columns.end(), c.column) -
                                             c.band_columns.begin());
    const auto pi =
        static_cast<std::size_t>(std::find(c.percentiles.begin(), c.percentiles.end(), p) - c.percentiles.begin());
    return 2 + ci * c.percentiles.size() + pi;
  };
  g << "# Drawn by rheodda forecast: percentile bands of " << c.column << " across the ensemble.\n"
    << "set terminal pngcairo size 1000,650 noenhanced\n"
    << "set output '" << (out / "fan.png").string() << "'\n"
    << "set datafile separator ','\nset key bottom right\nset grid\nset format y '%.4g'\n"
    << "set title '" << scene::gnuplot_text(c.title) << "'\n"
    << "set xlabel 'time [" << c.time_unit << "]'\n"
    << "set ylabel '" << scene::gnuplot_text(c.column + " [" + c.length_unit + "]") << "'\n"
    << "plot ";
  std::vector<std::string> parts;
  const std::size_t skip = c.units_line ? 2 : 1;
  const std::size_t nb = ps.size() / 2;
  for (std::size_t b = 0; b < nb; ++b) {  // outer bands lighter
    const double shade = 0.75 - 0.45 * static_cast<double>(b) / std::max<double>(1.0, static_cast<double>(nb));
    const int rgb = static_cast<int>(255 * shade);
    parts.push_back(fmt::format("'{}' skip {} using 1:{}:{} with filledcurves lc rgb '#{:02x}{:02x}ff' title '{:g}-{:g} %'",
                                (out / "bands.csv").string(), skip, col_of(ps[b]), col_of(ps[ps.size() - 1 - b]), rgb,
                                rgb, ps[b], ps[ps.size() - 1 - b]));
  }
  if (ps.size() % 2 == 1)
    parts.push_back(fmt::format("'{}' skip {} using 1:{} with lines lw 2 lc rgb '#000080' title '{:g} % (median)'",
                                (out / "bands.csv").string(), skip, col_of(ps[nb]), ps[nb]));
  if (c.threshold)
    parts.push_back(fmt::format("{} with lines dt 2 lc rgb 'red' title 'threshold {:g}'", *c.threshold, *c.threshold));
  g << fmt::format("{}", fmt::join(parts, ", \\\n     ")) << "\n";
  g.close();
  scene::run_gnuplot(gp.string());
}

}  // namespace rheodda::forecast
