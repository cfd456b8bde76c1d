#include "rheodda/scene/plot.hpp"

#include "rheodda/scene/history_columns.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "plot_bolts.hpp"
#include "plot_contacts.hpp"
#include "plot_support.hpp"

extern char** environ;

namespace rheodda::scene {

void run_gnuplot(const std::string& script) {
  // gnuplot's messages go to a file beside the script: in the error when it fails, passed on
  // to stderr when it draws.
  const std::string log = script + ".log";
  std::string prog = "gnuplot";
  std::vector<char*> argv{prog.data(), const_cast<char*>(script.c_str()), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    std::error_code ec;
    std::filesystem::remove(log, ec);
    throw std::runtime_error("cannot start gnuplot (installed by scripts/install-deps.sh)");
  }
  int status = 0;
  waitpid(pid, &status, 0);
  std::string messages;
  {
    std::ifstream in(log);
    messages.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::error_code ec;
  std::filesystem::remove(log, ec);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("gnuplot failed on {}{}", script, messages.empty() ? "" : ":\n" + messages));
  if (!messages.empty()) std::fputs(messages.c_str(), stderr);
}

std::string gnuplot_text(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out;
}

std::string gnuplot_wrapped(const std::string& s, std::size_t width) {
  std::string out = "\"", line;
  auto flush = [&](bool last) {
    for (char c : line) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    if (!last) out += "\\n";
    line.clear();
  };
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find(' ', start), s.size());
    const std::string word = s.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > width) flush(false);
    if (!line.empty()) line += ' ';
    line += word;
    start = end + 1;
  }
  flush(true);
  return out + "\"";
}

std::string CurveStyle::line() const { return fmt::format("lc rgb '{}' dt {}", colour, dash); }

CurveStyle curve_style(std::size_t i) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  static const int kDashes[] = {1, 2, 4, 3};
  static const int kPoints[] = {7, 5, 9, 13};
  const std::size_t n = std::size(kColours), round = (i / n) % std::size(kDashes);
  return {kColours[i % n], kDashes[round], kPoints[round]};
}

std::string history_column_unit(const std::string& column, const std::string& length, const std::string& force,
                                const std::string& time) {
  auto ends_with = [&](const std::string& tail) {
    return column.size() > tail.size() && column.compare(column.size() - tail.size(), tail.size(), tail) == 0;
  };
  // The declared unit of the column (history_columns.hpp), in the scene's units; forces and
  // energies per unit thickness.
  auto in_units = [&](const std::string& unit) -> std::string {
    if (unit == "time") return time;
    if (unit == "length") return length;
    if (unit == "force") return fmt::format("{}/{} thickness", force, length);
    if (unit == "force·length") return fmt::format("{}*{}/{} thickness", force, length, length);
    return "-";
  };
  for (const HistoryColumns& c : history_column_specs()) {
    const bool suffix = c.part == HistoryPart::point || c.part == HistoryPart::point_settled ||
                        c.part == HistoryPart::joint_set;
    for (const std::string& n : c.names)
      if (suffix ? ends_with(n) : column == n) return in_units(c.unit);
  }
  if (ends_with(".displacement")) return length;  // a study's derived column (study/study_series.cpp)
  return "";
}

namespace {

namespace fs = std::filesystem;

std::string quote(const std::string& s) { return gnuplot_quote(s); }
std::string terminal(const std::string& format, int w, int h) { return gnuplot_terminal(format, w, h); }
constexpr std::size_t kTitleWidth = kPlotTitleWidth;

/// 1, 2 or 5 times a power of ten, at least x.
double nice(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= x) return m * p;
  return 10.0 * p;
}

}  // namespace

std::string plot_scene(const SceneDescription& s, const std::string& picture, const std::string& format) {
  // One data file of edge segments per joint set (and one for the rock mass's region
  // boundary), each drawn in its own colour with the joint set's name in the key.
  const std::size_t sets = s.joint_sets.size();
  std::vector<std::string> edges(sets + 1);  // [sets]: region boundary
  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    const auto& b = s.blocks[i];
    const bool generated = s.rock_mass && i >= s.rock_mass->first_block &&
                           i < s.rock_mass->first_block + s.rock_mass->block_count;
    for (std::size_t k = 0; k < b.polygon.size(); ++k) {
      const Point& p = b.polygon[k];
      const Point& q = b.polygon[(k + 1) % b.polygon.size()];
      const bool boundary = generated && s.rock_mass->edge_on_boundary[i - s.rock_mass->first_block][k];
      const std::size_t slot = boundary ? sets : static_cast<std::size_t>(b.edge_joint_set[k]);
      edges[slot] += fmt::format("{:.10g} {:.10g}\n{:.10g} {:.10g}\n\n", p[0], p[1], q[0], q[1]);
    }
  }
  const fs::path pic(picture);
  const fs::path stem = pic.parent_path() / pic.stem();
  static const char* kColours[] = {"#1f4e9a", "#d1495b", "#2e933c", "#edae49", "#7b2cbf", "#00798c", "#8d6a9f", "#c05805"};
  std::string plots;
  for (std::size_t k = 0; k <= sets; ++k) {
    if (edges[k].empty()) continue;
    const fs::path dat = fs::path(stem.string() + fmt::format("_edges{}.dat", k));
    write_file_atomic(dat.string(), edges[k]);
    const std::string title = k == sets ? std::string("region boundary") : s.joint_sets[k].name;
    plots += fmt::format("{}{} with lines lw {} lc rgb '{}' title {} noenhanced", plots.empty() ? "" : ", \\\n     ",
                         quote(dat.string()), k == sets ? 2.0 : 1.2, k == sets ? "#555555" : kColours[k % 8],
                         quote(title));
  }
  const std::string script = fmt::format(
      "{}\nset output {}\nset title {} noenhanced\nset size ratio -1\nset xlabel 'x [{}]' noenhanced\n"
      "set ylabel 'y [{}]' noenhanced\nset key outside bottom center horizontal\nplot {}\n",
      terminal(format, 1000, 760), quote(picture),
      gnuplot_wrapped(fmt::format("{}: {} blocks, edges by joint set", s.title, s.blocks.size()), kTitleWidth), s.units.length,
      s.units.length, plots);
  const std::string gp = stem.string() + ".gp";
  write_file_atomic(gp, script);
  run_gnuplot(gp);
  return picture;
}

namespace {

/// The blocks at the frames `o` asks for (plots/blocks_NNNNNN.*): returns the pictures.
std::vector<std::string> plot_frames(const PlotOptions& o, const std::string& title, const PlotUnits& units,
                                     const std::vector<std::pair<double, std::string>>& frames) {
  const std::string &L = units.length, &T = units.time;
  const fs::path dir(o.out_dir);
  std::vector<std::size_t> chosen;
  if (o.times.empty()) {
    // The first, middle and last frame (within the time window --from, --to).
    // (A frame's time is that of its step, which may differ from the output time in the
    // last bits: 0.15000000000000002 for 0.15.)
    const double eps = 1e-9 * std::max({std::abs(frames.front().first), std::abs(frames.back().first), 1e-300});
    std::vector<std::size_t> in;
    for (std::size_t k = 0; k < frames.size(); ++k)
      if ((!o.from || frames[k].first >= *o.from - eps) && (!o.to || frames[k].first <= *o.to + eps)) in.push_back(k);
    if (in.empty())
      throw std::invalid_argument(fmt::format("--from {}, --to {}: no frame in that window (the frames span {:g} to {:g} {})",
                                              o.from ? fmt::format("{:g}", *o.from) : "-", o.to ? fmt::format("{:g}", *o.to) : "-",
                                              frames.front().first, frames.back().first, T));
    chosen = {in.front(), in[in.size() / 2], in.back()};
  } else {
    const double first = frames.front().first, last = frames.back().first;
    // Times closer than this to a frame's time are that frame (the .pvd holds %g-printed times).
    const double same = 1e-9 * std::max({std::abs(first), std::abs(last), 1e-300});
    for (double t : o.times) {
      std::size_t best = 0;
      for (std::size_t k = 1; k < frames.size(); ++k)
        if (std::abs(frames[k].first - t) < std::abs(frames[best].first - t)) best = k;
      chosen.push_back(best);
      if (!o.warn || std::abs(frames[best].first - t) <= same) continue;
      if (t > last)
        o.warn(fmt::format("--times {:g}: the run's frames end at t = {:g} {}; drawing the last frame (t = {:g} {})",
                           t, last, T, last, T));
      else if (t < first)
        o.warn(fmt::format("--times {:g}: the run's frames start at t = {:g} {}; drawing the first frame", t,
                           first, T));
      else
        o.warn(fmt::format("--times {:g}: no frame at that time; drawing the nearest, t = {:g} {}", t,
                           frames[best].first, T));
    }
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());

  std::vector<std::string> written;

  // Magnification: tiny displacements (creep) are drawn at 5% of the model size.
  std::vector<std::vector<FrameBlock>> data;
  double dmax = 0.0, x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (std::size_t k : chosen) {
    data.push_back(read_vtk_polydata((dir / frames[k].second).string()));
    for (const auto& b : data.back())
      for (std::size_t v = 0; v < b.vertices.size(); ++v) {
        if (!b.removed.value_or(false))  // an excavated block is not drawn moved (below)
          dmax = std::max(dmax, std::hypot(b.displacement[v][0], b.displacement[v][1]));
        x0 = std::min(x0, b.vertices[v][0] - b.displacement[v][0]);
        x1 = std::max(x1, b.vertices[v][0] - b.displacement[v][0]);
        y0 = std::min(y0, b.vertices[v][1] - b.displacement[v][1]);
        y1 = std::max(y1, b.vertices[v][1] - b.displacement[v][1]);
      }
  }
  const double size = std::max(x1 - x0, y1 - y0);
  double scale = o.scale;
  if (scale <= 0.0) scale = (dmax > 0.0 && dmax < 0.02 * size) ? nice(0.05 * size / dmax) : 1.0;

  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const std::size_t k = chosen[i];
    const std::string stem = fmt::format("blocks_{:06d}", k);
    std::string initial, deformed;
    for (const auto& b : data[i]) {
      // A block a stage removed (docs/reference/stages.md) is drawn where it was only: the
      // dashed outline of the initial blocks shows the excavation.
      const bool drawn = !b.removed.value_or(false);
      for (std::size_t v = 0; v <= b.vertices.size(); ++v) {
        const std::size_t w = v % b.vertices.size();
        const double ix = b.vertices[w][0] - b.displacement[w][0], iy = b.vertices[w][1] - b.displacement[w][1];
        initial += fmt::format("{:.10g} {:.10g}\n", ix, iy);
        if (drawn)
          deformed += fmt::format("{:.10g} {:.10g} {}\n", ix + scale * b.displacement[w][0],
                                  iy + scale * b.displacement[w][1], b.fixed ? 1 : 0);
      }
      initial += "\n";
      if (drawn) deformed += "\n";
    }
    const fs::path dat_i = dir / "plots" / (stem + "_initial.dat");
    const fs::path dat_d = dir / "plots" / (stem + "_deformed.dat");
    write_file_atomic(dat_i.string(), initial);
    write_file_atomic(dat_d.string(), deformed);
    const fs::path picture = dir / "plots" / (stem + "." + o.format);
    const std::string script = fmt::format(
        "{}\nset output {}\nset title {} noenhanced\nset size ratio -1\nset xlabel 'x [{}]' noenhanced\n"
        "set ylabel 'y [{}]' noenhanced\nset key outside bottom center horizontal\nset grid lc rgb '#dddddd'\n"
        "plot {} with lines dt 2 lc rgb '#999999' title 'initial', \\\n"
        "     {} with lines lw 1.5 lc rgb '#1f4e9a' title {} noenhanced\n",
        terminal(o.format, 1000, 760), quote(picture.string()),
        gnuplot_wrapped(fmt::format("{}: blocks at t = {:g} {}", title, frames[k].first, T), kTitleWidth), L, L, quote(dat_i.string()),
        quote(dat_d.string()),
        quote(scale == 1.0 ? std::string("deformed") : fmt::format("deformed (displacements x {:g})", scale)));
    const fs::path gp = dir / "plots" / (stem + ".gp");
    write_file_atomic(gp.string(), script);
    run_gnuplot(gp.string());
    written.push_back(picture.string());
  }

  // Where creep and slip act at the same frames (plot_contacts.cpp).
  if (fs::exists(dir / "contacts.csv")) {
    std::vector<ContactFrame> drawn;
    for (std::size_t i = 0; i < chosen.size(); ++i) drawn.push_back({chosen[i], frames[chosen[i]].first, &data[i]});
    for (auto& p : plot_contacts(o.out_dir, o.format, title, units, drawn, o.contact_column)) written.push_back(std::move(p));
  }
  return written;
}

/// The frames listed in OUT_DIR/blocks.pvd: (time, file), in its order.
std::vector<std::pair<double, std::string>> listed_frames(const fs::path& dir) {
  std::vector<std::pair<double, std::string>> frames;
  const std::string pvd = read_file((dir / "blocks.pvd").string());
  const std::regex entry("timestep=\"([^\"]+)\" part=\"0\" file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator(); ++it)
    frames.emplace_back(std::stod((*it)[1].str()), (*it)[2].str());
  if (frames.empty()) throw std::invalid_argument(fmt::format("{}/blocks.pvd lists no frame", dir.string()));
  return frames;
}

/// history.csv's column names (its first line that is not a comment), read without the rows.
std::vector<std::string> history_header(const fs::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", csv.string()));
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') break;
  std::vector<std::string> header;
  std::stringstream ss(line);
  std::string col;
  while (std::getline(ss, col, ',')) header.push_back(col);
  return header;
}

/// plots/history.*: the measurement points' displacements (and, with a settling stage,
/// those after it) and the recorded joint sets' mean shear displacement and force.
void plot_history(const PlotOptions& o, const nlohmann::json& summary, const std::string& title,
                  const std::string& L, const std::string& T, const std::string& F, std::vector<std::string>& written) {
  const fs::path dir(o.out_dir);
  // History curves: measurement points (u, v) and recorded joint sets (mean shear displacement, force).
  const std::vector<std::string> header = history_header(dir / "history.csv");
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i) + 1;
    return 0;
  };
  const std::string csv = quote((dir / "history.csv").string());
  std::vector<std::string> point_curves, settled_curves, joint_curves, force_curves;
  for (const auto& mp : summary.at("measurement_points")) {
    const std::string n = mp.get<std::string>();
    point_curves.push_back(fmt::format("{} using 1:{} with lines lw 1.5 title {} noenhanced", csv,
                                       column(n + ".u"), quote(n + ".u")));
    point_curves.push_back(fmt::format("{} using 1:{} with lines lw 1.5 dt 2 title {} noenhanced", csv,
                                       column(n + ".v"), quote(n + ".v")));
    // With a settling stage: the displacement since its end (empty before it, not drawn).
    for (const char* c : {".u_after_settling", ".v_after_settling"})
      if (column(n + c) > 0)
        settled_curves.push_back(fmt::format("{} using 1:{} with lines lw 1.5{} title {} noenhanced", csv,
                                             column(n + c), c[1] == 'v' ? " dt 2" : "", quote(n + c)));
  }
  for (const auto& js : summary.at("recorded_joint_sets")) {
    const std::string n = js.get<std::string>();
    joint_curves.push_back(fmt::format("{} using 1:{} with lines lw 1.5 title {} noenhanced", csv,
                                       column(n + ".shear_displacement"), quote(n + ".shear_displacement")));
    force_curves.push_back(fmt::format("{} using 1:{} with lines lw 1.5 title {} noenhanced", csv,
                                       column(n + ".shear_force"), quote(n + ".shear_force")));
  }
  const int panels = int(!point_curves.empty()) + int(!settled_curves.empty()) + int(!joint_curves.empty()) +
                     int(!force_curves.empty());
  if (panels > 0) {
    const fs::path picture = dir / "plots" / ("history." + o.format);
    std::string script = fmt::format(
        "{}\nset output {}\nset datafile separator ','\nset key top left noenhanced\nset grid lc rgb '#dddddd'\n"
        "set xlabel 'time [{}]' noenhanced\nset offsets 0, 0, graph 0.05, graph 0.05\nset xrange [{}:{}]\n"
        "set multiplot layout {},1 title {} noenhanced\n",
        terminal(o.format, 1000, 330 * panels + 40), quote(picture.string()), T,
        o.from ? fmt::format("{:.17g}", *o.from) : "*", o.to ? fmt::format("{:.17g}", *o.to) : "*", panels,
        quote(title + ": history"));
    auto panel = [&](const std::vector<std::string>& curves, const std::string& ylabel) {
      if (curves.empty()) return;
      script += fmt::format("set ylabel {} noenhanced\nplot ", quote(ylabel));
      for (std::size_t i = 0; i < curves.size(); ++i)
        script += (i ? ", \\\n     " : "") + fmt::format("{} ", curves[i]).replace(0, csv.size(), csv + " skip 2");
      script += ", \\\n     0 with lines lc rgb '#bbbbbb' notitle\n";  // keeps zero in view
    };
    panel(point_curves, fmt::format("displacement [{}]", L));
    panel(settled_curves, fmt::format("displacement after settling [{}]", L));
    panel(joint_curves, fmt::format("mean shear displacement [{}]", L));
    panel(force_curves, fmt::format("mean shear force [{}/{} thickness]", F, L));
    script += "unset multiplot\n";
    const fs::path gp = dir / "plots" / "history.gp";
    write_file_atomic(gp.string(), script);
    run_gnuplot(gp.string());
    written.push_back(picture.string());
  }
}

}  // namespace

std::vector<std::string> plot_run(const PlotOptions& o) {
  const fs::path dir(o.out_dir);
  // A scene file instead of a run's directory: its blocks, edges coloured by joint set,
  // into <scene without extension>-blocks.<format> beside it.
  if (fs::is_regular_file(dir)) {
    const SceneDescription s = load_scene(dir.string());
    return {plot_scene(s, (dir.parent_path() / (dir.stem().string() + "-blocks." + o.format)).string(), o.format)};
  }
  // A run without frames (analysis.frames: false, a study's case) has its history drawn.
  const bool has_frames = fs::exists(dir / "blocks.pvd");
  if (!fs::exists(dir / "summary.json") || (!has_frames && !fs::exists(dir / "history.csv")))
    throw std::invalid_argument(fmt::format("{} holds no run (no summary.json, or neither blocks.pvd nor history.csv)", o.out_dir));
  const auto summary = nlohmann::json::parse(read_file((dir / "summary.json").string()));
  const auto& units = summary.at("units");
  const std::string L = units.at("length"), T = units.at("time"), F = units.at("force");
  const PlotUnits plot_units{L, F, T, units.value("stress", F + "/" + L + "^2")};
  const std::string title = summary.at("inputs").value("title", "");
  if (o.from && o.to && !(*o.from < *o.to))
    throw std::invalid_argument(fmt::format("--from {:g} --to {:g}: the window's start must come before its end", *o.from, *o.to));
  fs::create_directories(dir / "plots");
  std::vector<std::string> written;
  if (has_frames) {
    written = plot_frames(o, title, plot_units, listed_frames(dir));
  } else if (o.warn) {
    o.warn(fmt::format("{} has no frames (analysis.frames: false): drawing the history only", o.out_dir));
  }
  plot_history(o, summary, title, L, T, F, written);
  // A run with bolts: their forces (plot_bolts.cpp).
  if (fs::exists(dir / "bolts.csv")) written.push_back(plot_bolts(o.out_dir, o.format, title, T, F, L));
  return written;
}

}  // namespace rheodda::scene
