// `rheodda plot` of a run's contacts (docs/reference/outputs.md, "contacts.csv";
// docs/guide/getting-started.md): where creep and slip act. At each drawn frame, the blocks
// with their contacts coloured by state and by a chosen column, and per joint set the
// contacts' shear stress against their Mohr-Coulomb strength at the same normal
// stress (the mobilised friction), from the rows of contacts.csv at the frame's time.
#include "plot_contacts.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <tuple>
#include <stdexcept>

#include "plot_support.hpp"
#include "rheodda/scene/plot.hpp"

namespace rheodda::scene {
namespace {

namespace fs = std::filesystem;

/// A contact's row at a frame, as the pictures need it.
struct ContactRow {
  std::string joint_set;
  std::string state;       ///< open, sliding, locked
  double x = 0.0, y = 0.0; ///< contact vertex [length]
  double normal_force = 0.0, shear_force = 0.0, shear_strength = 0.0;  ///< [force/length thickness]
  double tributary_length = 0.0;                                      ///< [length]
  double colour = 0.0;     ///< the chosen column's value (its magnitude where signed along the edge)
};

/// The columns signed along the contact's entrance edge: their sign is a direction, drawn
/// as magnitudes.
bool signed_along_edge(const std::string& column) {
  return column == "shear_force" || column == "shear_displacement" || column == "creep_displacement";
}

/// The unit of a contacts.csv column in the run's units.
std::string column_unit(const std::string& column, const PlotUnits& u) {
  if (column == "normal_force" || column == "shear_force" || column == "shear_strength")
    return fmt::format("{}/{} thickness", u.force, u.length);
  if (column == "water_pressure") return u.stress;
  if (column == "mobilised_friction") return "-";
  return u.length;  // displacements, penetration, lengths
}

/// |F_s| / strength, or NaN where the strength is zero (an unloaded point contact).
double mobilised(const ContactRow& r) {
  return r.shear_strength > 0.0 ? std::abs(r.shear_force) / r.shear_strength : std::nan("");
}

/// The rows of contacts.csv at the frames' times: for each frame, those of the time in
/// the file nearest to it (the collection prints times to 6 digits, contacts.csv to 10).
std::vector<std::vector<ContactRow>> rows_at(const fs::path& csv, const std::vector<ContactFrame>& frames,
                                             const std::string& column) {
  double span = 0.0;
  for (const auto& f : frames) span = std::max(span, std::abs(f.time));
  const double near = 1e-5 * std::max(span, 1e-300);
  std::map<double, std::vector<ContactRow>> found;  // by the row's time
  std::vector<int> at;
  bool checked = false;
  for_each_csv_row(csv.string(), [&](const std::vector<std::string>& header, const std::vector<std::string>& cells) {
    if (!checked) {
      checked = true;
      auto index = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end())
          throw std::invalid_argument(fmt::format("{}: no column {} (it has: {}); a run written before it was "
                                                  "added has to be run again",
                                                  csv.string(), name, fmt::join(header, ", ")));
        return static_cast<int>(it - header.begin());
      };
      at = {index("time"), index("joint_set"), index("state"), index("x"), index("y"), index("normal_force"),
            index("shear_force"), index("shear_strength"), index("tributary_length"),
            column == "mobilised_friction" ? -1 : index(column)};
    }
    const double t = std::stod(cells.at(at[0]));
    if (std::none_of(frames.begin(), frames.end(), [&](const ContactFrame& f) { return std::abs(f.time - t) <= near; }))
      return;
    ContactRow r;
    r.joint_set = cells.at(at[1]);
    r.state = cells.at(at[2]);
    r.x = std::stod(cells.at(at[3]));
    r.y = std::stod(cells.at(at[4]));
    r.normal_force = std::stod(cells.at(at[5]));
    r.shear_force = std::stod(cells.at(at[6]));
    r.shear_strength = std::stod(cells.at(at[7]));
    r.tributary_length = std::stod(cells.at(at[8]));
    if (at[9] < 0) {
      r.colour = mobilised(r);
    } else {
      const std::string& v = cells.at(at[9]);
      r.colour = v.empty() ? std::nan("") : std::stod(v);
      if (signed_along_edge(column)) r.colour = std::abs(r.colour);
    }
    found[t].push_back(std::move(r));
  });
  std::vector<std::vector<ContactRow>> out(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const double* best = nullptr;
    for (const auto& [t, rows] : found)
      if (std::abs(t - frames[i].time) <= near && (!best || std::abs(t - frames[i].time) < std::abs(*best - frames[i].time)))
        best = &t;
    if (best) out[i] = found.at(*best);
  }
  return out;
}

/// The blocks' current outlines, a polygon per block ("x y" lines, a blank line between).
std::string outlines(const std::vector<FrameBlock>& blocks) {
  std::string text;
  for (const auto& b : blocks) {
    if (b.removed.value_or(false)) continue;  // excavated by a stage
    for (std::size_t v = 0; v <= b.vertices.size(); ++v) {
      const std::size_t w = v % b.vertices.size();
      text += fmt::format("{:.10g} {:.10g}\n", b.vertices[w][0], b.vertices[w][1]);
    }
    text += "\n";
  }
  return text;
}

/// The height [pixels] of a 1000-pixel wide picture of two panels of the blocks drawn to
/// scale, one above the other: each panel as high as the blocks' extent is for its width.
int canvas_height(const std::vector<FrameBlock>& blocks) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& b : blocks)
    for (const auto& v : b.vertices) {
      x0 = std::min(x0, v[0]);
      x1 = std::max(x1, v[0]);
      y0 = std::min(y0, v[1]);
      y1 = std::max(y1, v[1]);
    }
  const double aspect = (x1 > x0 && y1 >= y0) ? (y1 - y0) / (x1 - x0) : 1.0;
  return static_cast<int>(std::clamp(2.0 * 800.0 * aspect + 300.0, 700.0, 2200.0));
}

/// plots/contacts_NNNNNN.<format>.
std::string draw_layout(const fs::path& dir, const std::string& format, const std::string& title,
                        const PlotUnits& units, const ContactFrame& f, const std::vector<ContactRow>& rows,
                        const std::string& column) {
  const std::string stem = fmt::format("contacts_{:06d}", f.number);
  const fs::path blocks_dat = dir / "plots" / (stem + "_blocks.dat"), dat = dir / "plots" / (stem + ".dat");
  write_file_atomic(blocks_dat.string(), outlines(*f.blocks));
  std::map<std::string, int> count;
  std::string points = "# x y state(0 open, 1 sliding, 2 locked) value\n";
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& r : rows) {
    ++count[r.state];
    const int s = r.state == "open" ? 0 : r.state == "sliding" ? 1 : 2;
    points += fmt::format("{:.10g} {:.10g} {} {:.10g}\n", r.x, r.y, s, r.colour);
    if (std::isfinite(r.colour)) {
      lo = std::min(lo, r.colour);
      hi = std::max(hi, r.colour);
    }
  }
  write_file_atomic(dat.string(), points);
  const std::string label =
      fmt::format("{}{}{} [{}]", signed_along_edge(column) ? "|" : "", column, signed_along_edge(column) ? "|" : "",
                  column_unit(column, units));
  // A colour range that is one value (every contact at 0, e.g. a joint set without a law)
  // still draws: gnuplot refuses an empty range.
  const std::string cbrange = (lo < hi) ? fmt::format("set cbrange [{:.10g}:{:.10g}]\n", lo, hi)
                              : std::isfinite(lo) ? fmt::format("set cbrange [{:.10g}:{:.10g}]\n", lo - 0.5 * std::max(std::abs(lo), 1e-30), lo + 0.5 * std::max(std::abs(lo), 1e-30))
                                                  : std::string();
  const fs::path picture = dir / "plots" / (stem + "." + format);
  const std::string q_blocks = gnuplot_quote(blocks_dat.string()), q_dat = gnuplot_quote(dat.string());
  // A series per state that has contacts (gnuplot warns of one with no point).
  std::string states;
  for (const auto& [word, code, look] : {std::tuple{"locked", 2, "pt 7 ps 0.8 lc rgb '#1f77b4'"},
                                         std::tuple{"sliding", 1, "pt 7 ps 1.0 lc rgb '#d62728'"},
                                         std::tuple{"open", 0, "pt 6 ps 0.6 lc rgb '#7f7f7f'"}})
    if (count.count(word))
      states += fmt::format(", \\\n     {} using 1:($3=={} ? $2 : 1/0) with points {} title '{} ({})'", q_dat, code, look,
                            word, count.at(word));
  const std::string outline = fmt::format("plot {} with lines lc rgb '#aaaaaa' notitle", q_blocks);
  std::string script = fmt::format(
      "{}\nset output {}\nset size ratio -1\nset grid lc rgb '#eeeeee'\nset key outside top center horizontal noenhanced\n"
      "set xlabel 'x [{}]' noenhanced\nset ylabel 'y [{}]' noenhanced\n"
      "set multiplot layout 2,1 title {} noenhanced\n"
      "set title {} noenhanced\n{}{}\n",
      gnuplot_terminal(format, 1000, canvas_height(*f.blocks)), gnuplot_quote(picture.string()), units.length,
      units.length, gnuplot_wrapped(fmt::format("{}: contacts at t = {:g} {}", title, f.time, units.time), kPlotTitleWidth),
      gnuplot_quote(rows.empty() ? "contact state: no contact at this time" : "contact state"), outline, states);
  script += fmt::format("set title {} noenhanced\n", gnuplot_quote("contacts coloured by " + label));
  if (rows.empty())
    script += outline + "\n";
  else
    script += fmt::format(
        "{}set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 '#fde725')\n"
        "set cblabel {} noenhanced\nunset key\n{}, \\\n     {} using 1:2:4 with points pt 7 ps 0.9 lc palette notitle\n",
        cbrange, gnuplot_quote(label), outline, q_dat);
  script += "unset multiplot\n";
  const fs::path gp = dir / "plots" / (stem + ".gp");
  write_file_atomic(gp.string(), script);
  run_gnuplot(gp.string());
  return picture.string();
}

/// plots/strength_NNNNNN.<format>, or "" when no contact is closed.
std::string draw_strength(const fs::path& dir, const std::string& format, const std::string& title,
                          const PlotUnits& units, const ContactFrame& f, const std::vector<ContactRow>& rows) {
  // Per joint set, in the order of first appearance: "sigma tau strength state" lines.
  std::vector<std::string> sets;
  std::map<std::string, std::string> data;
  std::map<std::string, std::vector<double>> ratio;
  std::map<std::string, int> closed, sliding;
  for (const auto& r : rows) {
    if (r.state == "open" || !(r.tributary_length > 0.0)) continue;
    if (!data.count(r.joint_set)) sets.push_back(r.joint_set);
    const double l = r.tributary_length;
    data[r.joint_set] += fmt::format("{:.10g} {:.10g} {:.10g} {}\n", r.normal_force / l, std::abs(r.shear_force) / l,
                                     r.shear_strength / l, r.state == "sliding" ? 1 : 2);
    ++closed[r.joint_set];
    if (r.state == "sliding") ++sliding[r.joint_set];
    if (const double m = mobilised(r); std::isfinite(m)) ratio[r.joint_set].push_back(m);
  }
  if (sets.empty()) return {};
  const std::string stem = fmt::format("strength_{:06d}", f.number);
  const int cols = sets.size() > 1 ? 2 : 1, lines = static_cast<int>((sets.size() + 1) / 2);
  const fs::path picture = dir / "plots" / (stem + "." + format);
  std::string script = fmt::format(
      "{}\nset output {}\nset grid lc rgb '#eeeeee'\nset key top left noenhanced\n"
      "set xlabel 'normal stress F_n / l_t, compression > 0 [{}]' noenhanced\n"
      "set ylabel '|shear stress| |F_s| / l_t [{}]' noenhanced\nset xrange [0:*]\nset yrange [0:*]\n"
      "set multiplot layout {},{} title {} noenhanced\n",
      gnuplot_terminal(format, cols == 1 ? 1000 : 1400, cols == 1 ? 700 : lines * 520 + 60), gnuplot_quote(picture.string()), units.stress,
      units.stress, lines, cols,
      gnuplot_wrapped(fmt::format("{}: joint stress against strength at t = {:g} {}", title, f.time, units.time),
                      kPlotTitleWidth));
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::string& js = sets[k];
    const fs::path dat = dir / "plots" / fmt::format("{}_{}.dat", stem, k);
    write_file_atomic(dat.string(), "# sigma_n |tau| strength state(1 sliding, 2 locked) [stress]\n" + data[js]);
    std::vector<double>& m = ratio[js];
    std::sort(m.begin(), m.end());
    const auto near_limit = std::count_if(m.begin(), m.end(), [](double v) { return v >= 0.95; });
    const std::string mobilised_text =
        m.empty() ? std::string("no contact carries a strength")
                  : fmt::format("mobilised friction median {:.0f} %, {} at 95 % or more", 100.0 * m[m.size() / 2], near_limit);
    const std::string q = gnuplot_quote(dat.string());
    script += fmt::format(
        "set title {} noenhanced\n"
        "plot {} using 1:($4==2 ? $2 : 1/0) with points pt 7 ps 0.7 lc rgb '#1f77b4' title 'locked', \\\n"
        "     {} using 1:($4==1 ? $2 : 1/0) with points pt 7 ps 0.9 lc rgb '#d62728' title 'sliding', \\\n"
        "     {} using 1:3 with points pt 1 ps 1.4 lc rgb '#333333' title 'its strength (Mohr-Coulomb)'\n",
        gnuplot_wrapped(fmt::format("{}: {} closed, {} sliding; {}", js, closed[js], sliding[js], mobilised_text),
                        cols == 1 ? kPlotTitleWidth : 60),
        q, q, q);
  }
  script += "unset multiplot\n";
  const fs::path gp = dir / "plots" / (stem + ".gp");
  write_file_atomic(gp.string(), script);
  run_gnuplot(gp.string());
  return picture.string();
}

}  // namespace

const std::vector<std::string>& contact_colour_columns() {
  static const std::vector<std::string> columns{"creep_displacement", "shear_displacement", "shear_force",
                                                "normal_force",       "shear_strength",     "mobilised_friction",
                                                "penetration",        "length",             "tributary_length",
                                                "water_pressure"};
  return columns;
}

std::vector<std::string> plot_contacts(const std::string& out_dir, const std::string& format, const std::string& title,
                                       const PlotUnits& units, const std::vector<ContactFrame>& frames,
                                       const std::string& column) {
  const auto& known = contact_colour_columns();
  if (std::find(known.begin(), known.end(), column) == known.end())
    throw std::invalid_argument(
        fmt::format("--contact-column {}: not a column to colour contacts by; one of {}", column, fmt::join(known, ", ")));
  const fs::path dir(out_dir);
  const auto rows = rows_at(dir / "contacts.csv", frames, column);
  std::vector<std::string> written;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    written.push_back(draw_layout(dir, format, title, units, frames[i], rows[i], column));
    if (std::string s = draw_strength(dir, format, title, units, frames[i], rows[i]); !s.empty())
      written.push_back(std::move(s));
  }
  return written;
}

}  // namespace rheodda::scene
