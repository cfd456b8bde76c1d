// `rheodda plot` of a run with bolts (docs/reference/outputs.md, "bolts.csv"): the axial
// force of every bolt against time, from bolts.csv, into plots/bolts.<format>.
#include <fmt/format.h>

#include <filesystem>
#include <map>

#include "plot_bolts.hpp"
#include "plot_support.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/plot.hpp"

namespace rheodda::scene {

std::string plot_bolts(const std::string& out_dir, const std::string& format, const std::string& title,
                       const std::string& time_unit, const std::string& force_unit, const std::string& length_unit) {
  namespace fs = std::filesystem;
  const fs::path dir(out_dir);
  // time,step,bolt,state,force,... -> per bolt "time force" lines, in file order.
  std::map<std::string, std::string> series;
  std::vector<std::string> order;
  for_each_csv_row((dir / "bolts.csv").string(), [&](const std::vector<std::string>&, const std::vector<std::string>& cells) {
    if (cells.size() < 5) return;
    if (!series.count(cells[2])) order.push_back(cells[2]);
    series[cells[2]] += cells[0] + " " + cells[4] + "\n";
  });
  const auto q = gnuplot_quote;
  const fs::path picture = dir / "plots" / ("bolts." + format);
  std::string plot;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const fs::path dat = dir / "plots" / fmt::format("bolt_{}.dat", k);
    write_file_atomic(dat.string(), series[order[k]]);
    plot += fmt::format("{}{} using 1:2 with linespoints lw 1.5 pt 7 ps 0.5 title {} noenhanced", k ? ", \\\n     " : "",
                        q(dat.string()), q(order[k]));
  }
  const std::string script = fmt::format(
      "{}\nset output {}\nset title {} noenhanced\nset key top left noenhanced\nset grid lc rgb '#dddddd'\n"
      "set xlabel 'time [{}]' noenhanced\nset ylabel 'bolt axial force, tension > 0 [{}/{} thickness]' noenhanced\n"
      "plot {}, \\\n     0 with lines lc rgb '#bbbbbb' notitle\n",
      gnuplot_terminal(format, 1000, 500),
      q(picture.string()), q(title + ": bolt forces"), time_unit, force_unit, length_unit, plot);
  const fs::path gp = dir / "plots" / "bolts.gp";
  write_file_atomic(gp.string(), script);
  run_gnuplot(gp.string());
  return picture.string();
}

}  // namespace rheodda::scene
