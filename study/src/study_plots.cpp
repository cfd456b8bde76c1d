// A study's pictures: study.png (the `plot` output of every case against time),
// study_sweep.png and study_map.png (outputs against the swept parameters), drawn
// from study.json and study.csv by `rheodda plot OUTDIR` too (docs/guide/studies.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "rheodda/scene/plot.hpp"
#include "study_internal.hpp"

namespace rheodda::study {
namespace fs = std::filesystem;
using detail::format_value;
using detail::read_text;
using detail::split_csv_line;
namespace {

/// The unit labels of the cases' runs, from the first line of a case's history.csv
/// ("# units: length=m force=N time=d stress=N/m^2"); empty where no case wrote one.
struct RunUnits {
  std::string length, force, time;
  /// "NAME [UNIT]" for a history.csv column whose unit is known, else NAME.
  std::string label(const std::string& column, const std::string& what = "") const {
    const std::string unit = time.empty() ? "" : scene::history_column_unit(column, length, force, time);
    return (what.empty() ? column : what) + (unit.empty() ? "" : " [" + unit + "]");
  }
};

RunUnits run_units(const std::vector<CaseResult>& results, const fs::path& out_dir) {
  RunUnits u;
  for (const auto& r : results) {
    std::ifstream h(out_dir / "cases" / r.name / "history.csv");
    std::string first;
    if (!std::getline(h, first) || first.rfind("# units:", 0) != 0) continue;
    auto value = [&](const std::string& key) {
      const auto at = first.find(" " + key + "=");
      if (at == std::string::npos) return std::string();
      const auto from = at + key.size() + 2;
      return first.substr(from, first.find(' ', from) - from);
    };
    u.length = value("length");
    u.force = value("force");
    u.time = value("time");
    break;
  }
  return u;
}

/// study.png: the `plot` output of every case against time.
void plot_histories(const StudyDescription& study, const std::vector<CaseResult>& results, const fs::path& out_dir) {
  const fs::path dat = out_dir / "study_plot.dat";
  std::ofstream d(dat);
  std::vector<std::string> titles;
  for (const auto& r : results) {
    const fs::path h = out_dir / "cases" / r.name / "history.csv";
    std::vector<std::pair<double, double>> series;
    try {
      if (fs::exists(h)) series = read_history_series(h.string(), study.plot);
    } catch (const std::exception&) {
    }
    d << "# case " << r.name << "\n";
    for (const auto& [t, v] : series) d << format_value(t) << " " << format_value(v) << "\n";
    if (series.empty()) d << "nan nan\n";
    d << "\n\n";
    titles.push_back(r.status == "completed" ? r.name : r.name + " (" + r.status + ")");
  }
  d.close();
  // Each axis with its unit in brackets, in the runs' own unit labels.
  const RunUnits units = run_units(results, out_dir);
  const fs::path gp = out_dir / "study.gp";
  std::ofstream g(gp);
  g << "# Drawn by rheodda study: " << study.plot << " of every case against time.\n"
    << "set terminal pngcairo size 1000,650 noenhanced\n"
    << "set output '" << (out_dir / "study.png").string() << "'\n"
    << "set title '" << scene::gnuplot_text(study.title) << "'\n"
    << "set xlabel '" << scene::gnuplot_text(units.label("time")) << "'\n"
    << "set ylabel '" << scene::gnuplot_text(units.label(study.plot)) << "'\n"
    << "set grid\n";
  // Many cases (a sweep): no key (the lines would hide the plot); the sweep pictures name them.
  // Ten colours, then the same dashed (scene::curve_style): 40 cases before a look repeats.
  g << (titles.size() > 12 ? "set key off\n" : "set key outside right\n") << "plot ";
  for (std::size_t i = 0; i < titles.size(); ++i)
    g << (i ? ", \\\n     " : "") << "'" << dat.string() << "' index " << i << " using 1:2 with lines lw 2 "
      << scene::curve_style(i).line() << " title '" << scene::gnuplot_text(titles[i]) << "'";
  g << "\n";
  g.close();
  scene::run_gnuplot(gp.string());
}

std::string param_label(const SweepParameter& p) {
  return p.unit == "-" ? p.name : fmt::format("{} [{}]", p.name, p.unit);
}

/// A gnuplot tick format that tells the ticks of `values` apart: gnuplot's default
/// ("% h") shows about 6 significant digits, so an output that varies by 1e-5 of its
/// size gets the same label on every tick. Enough digits for a twentieth of the range
/// at the size of the largest value, at least 3 and at most 15 ("%.Ng").
std::string tick_format(const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo)) return "% h";
  const double size = std::max(std::abs(lo), std::abs(hi));
  const int digits = static_cast<int>(std::ceil(std::log10(size / ((hi - lo) / 20.0)))) + 1;
  return fmt::format("%.{}g", std::clamp(digits, 3, 15));
}

/// study_sweep.png: every output against the first swept parameter, and, for a grid of
/// two parameters, study_map.png: the `plot` output at the last time over both.
/// Grid of one parameter: one curve per time; grid of more: at the last time, one curve
/// per combination of the other parameters; random and Latin-hypercube draws: one
/// panel per output and parameter, the output at the last time as points.
std::vector<std::string> plot_sweep(const StudyDescription& study, const std::vector<CaseResult>& results,
                                    const fs::path& out_dir) {
  std::vector<std::string> files;
  const auto& ps = study.parameters;
  if (ps.empty()) return files;
  const std::size_t nt = study.times.size();
  const bool grid = study.method == SweepMethod::grid;
  struct Curve {
    std::string title;
    std::vector<std::pair<double, double>> points;  // (parameter, output); failed cases left out
  };
  struct Panel {
    std::string xlabel, ylabel;
    bool logx = false;
    std::vector<Curve> curves;
  };
  std::vector<Panel> panels;
  const auto value = [&](std::size_t c, std::size_t output, std::size_t time) -> std::optional<double> {
    const auto& v = results[c].values;
    const std::size_t k = output * nt + time;
    if (results[c].status != "completed" || k >= v.size()) return std::nullopt;
    return v[k];
  };
  const auto swept = [&](std::size_t c) { return study.cases[c].parameter_values.size() == ps.size(); };
  const RunUnits units = run_units(results, out_dir);
  const std::string last_time = fmt::format("{:g}", study.times.back());
  const std::string at_last = "at t = " + last_time + (units.time.empty() ? "" : " " + units.time);
  const std::size_t columns = grid ? 1 : ps.size();
  for (std::size_t o = 0; o < study.outputs.size(); ++o) {
    if (grid && ps.size() == 1) {
      Panel pn{param_label(ps[0]), units.label(study.outputs[o]), ps[0].log_scale, {}};
      for (std::size_t t = 0; t < nt; ++t) {
        Curve cv{fmt::format("t = {:g}", study.times[t]), {}};
        for (std::size_t c = 0; c < results.size(); ++c)
          if (swept(c))
            if (auto v = value(c, o, t)) cv.points.emplace_back(study.cases[c].parameter_values[0], *v);
        pn.curves.push_back(std::move(cv));
      }
      panels.push_back(std::move(pn));
    } else if (grid) {
      Panel pn{param_label(ps[0]), units.label(study.outputs[o], study.outputs[o] + " " + at_last),
               ps[0].log_scale, {}};
      std::map<std::vector<double>, std::size_t> curve_of;  // the other parameters' values -> curve
      for (std::size_t c = 0; c < results.size(); ++c) {
        if (!swept(c)) continue;
        const auto& pv = study.cases[c].parameter_values;
        const std::vector<double> rest(pv.begin() + 1, pv.end());
        if (!curve_of.count(rest)) {
          std::vector<std::string> label;
          for (std::size_t i = 1; i < ps.size(); ++i)
            label.push_back(fmt::format("{} = {:.4g}{}", ps[i].name, pv[i], ps[i].unit == "-" ? "" : " " + ps[i].unit));
          curve_of[rest] = pn.curves.size();
          pn.curves.push_back({fmt::format("{}", fmt::join(label, ", ")), {}});
        }
        if (auto v = value(c, o, nt - 1)) pn.curves[curve_of[rest]].points.emplace_back(pv[0], *v);
      }
      panels.push_back(std::move(pn));
    } else {
      for (std::size_t i = 0; i < ps.size(); ++i) {
        Panel pn{param_label(ps[i]), units.label(study.outputs[o], study.outputs[o] + " " + at_last),
                 ps[i].log_scale, {}};
        Curve cv{"", {}};
        for (std::size_t c = 0; c < results.size(); ++c)
          if (swept(c))
            if (auto v = value(c, o, nt - 1)) cv.points.emplace_back(study.cases[c].parameter_values[i], *v);
        pn.curves.push_back(std::move(cv));
        panels.push_back(std::move(pn));
      }
    }
  }
  const fs::path dat = out_dir / "study_sweep.dat";
  {
    std::ofstream d(dat);
    for (auto& pn : panels)
      for (auto& cv : pn.curves) {
        std::sort(cv.points.begin(), cv.points.end());
        d << "# " << pn.ylabel << " against " << pn.xlabel << (cv.title.empty() ? "" : ": " + cv.title) << "\n";
        for (const auto& [x, y] : cv.points) d << format_value(x) << " " << format_value(y) << "\n";
        if (cv.points.empty()) d << "nan nan\n";
        d << "\n\n";
      }
  }
  const std::size_t rows = (panels.size() + columns - 1) / columns;
  const fs::path gp = out_dir / "study_sweep.gp";
  {
    std::ofstream g(gp);
    g << "# Drawn by rheodda study: the outputs against the swept parameters (docs/guide/studies.md).\n"
      << "set terminal pngcairo size " << 560 * columns + 240 << "," << 380 * rows + 60 << " noenhanced\n"
      << "set output '" << (out_dir / "study_sweep.png").string() << "'\n"
      << "set grid\nset key outside right\n"
      << "set multiplot layout " << rows << "," << columns << " title '" << scene::gnuplot_text(study.title) << "'\n";
    std::size_t block = 0;
    for (const auto& pn : panels) {
      std::vector<double> xs, ys;
      for (const auto& cv : pn.curves)
        for (const auto& [x, y] : cv.points) xs.push_back(x), ys.push_back(y);
      g << "set format x '" << (pn.logx ? std::string("% h") : tick_format(xs)) << "'\n"
        << "set format y '" << tick_format(ys) << "'\n";
      g << (pn.logx ? "set logscale x\n" : "unset logscale x\n") << "set xlabel '" << scene::gnuplot_text(pn.xlabel) << "'\n"
        << "set ylabel '" << scene::gnuplot_text(pn.ylabel) << "'\n"
        << (pn.curves.size() > 10 ? "set key off\n" : "set key outside right\n") << "plot ";
      for (std::size_t i = 0; i < pn.curves.size(); ++i, ++block)
        g << (i ? ", \\\n     " : "") << "'" << dat.string() << "' index " << block << " using 1:2 with "
          << (grid ? fmt::format("linespoints lw 2 {} pt {}", scene::curve_style(i).line(), scene::curve_style(i).point)
                   : std::string("points pt 7"))
          << " title '" << scene::gnuplot_text(pn.curves[i].title) << "'";
      g << "\n";
    }
    g << "unset multiplot\n";
  }
  scene::run_gnuplot(gp.string());
  files.push_back((out_dir / "study_sweep.png").string());
  if (!(grid && ps.size() == 2)) return files;
  // The map: rows of constant first parameter, separated by blank lines (gnuplot's grid format).
  const std::size_t o = static_cast<std::size_t>(
      std::find(study.outputs.begin(), study.outputs.end(), study.plot) - study.outputs.begin());
  const fs::path mdat = out_dir / "study_map.dat";
  {
    std::ofstream d(mdat);
    d << "# " << ps[0].name << " " << ps[1].name << " " << study.plot << "@" << last_time << "\n";
    std::size_t k = 0;
    for (std::size_t c = 0; c < results.size(); ++c) {
      if (!swept(c)) continue;
      const auto& pv = study.cases[c].parameter_values;
      const auto v = value(c, o, nt - 1);
      d << format_value(pv[0]) << " " << format_value(pv[1]) << " " << (v ? format_value(*v) : "nan") << "\n";
      if (++k % ps[1].values.size() == 0) d << "\n";  // the last parameter varies fastest
    }
  }
  const fs::path mgp = out_dir / "study_map.gp";
  {
    std::ofstream g(mgp);
    g << "# Drawn by rheodda study: " << study.plot << " at t = " << last_time << " over the two swept parameters.\n"
      << "set terminal pngcairo size 900,700 noenhanced\n"
      << "set output '" << (out_dir / "study_map.png").string() << "'\n"
      << "set title '" << scene::gnuplot_text(study.title) << "'\n"
      << "set view map\nset pm3d corners2color mean interpolate 8,8\nset autoscale fix\n"
      << (ps[0].log_scale ? "set logscale x\n" : "") << (ps[1].log_scale ? "set logscale y\n" : "")
      << "set xlabel '" << scene::gnuplot_text(param_label(ps[0])) << "'\n"
      << "set ylabel '" << scene::gnuplot_text(param_label(ps[1])) << "'\n"
      << "set cblabel '" << scene::gnuplot_text(units.label(study.plot, study.plot + " " + at_last)) << "'\n"
      << "splot '" << mdat.string() << "' using 1:2:3 with pm3d notitle, '' using 1:2:3 with points pt 7 lc rgb 'black' notitle\n";
  }
  scene::run_gnuplot(mgp.string());
  files.push_back((out_dir / "study_map.png").string());
  return files;
}

}  // namespace

bool is_study_dir(const std::string& dir) {
  return fs::exists(fs::path(dir) / "study.json") && fs::exists(fs::path(dir) / "study.csv");
}

std::vector<std::string> plot_study_dir(const std::string& dir) {
  const fs::path out_dir = dir;
  StudyDescription study;
  std::vector<CaseResult> results;
  try {
    const auto j = nlohmann::json::parse(read_text(out_dir / "study.json"));
    study.file = j.at("study").get<std::string>();
    study.title = j.at("title").get<std::string>();
    study.outputs = j.at("outputs").get<std::vector<std::string>>();
    study.times = j.at("times").get<std::vector<double>>();
    study.plot = j.at("plot").get<std::string>();
    const std::string method = j.at("method").get<std::string>();
    study.method = method == "random" ? SweepMethod::random
                   : method == "latin_hypercube" ? SweepMethod::latin_hypercube : SweepMethod::grid;
    for (const auto& p : j.at("parameters")) {
      SweepParameter sp;
      sp.name = p.at("name").get<std::string>();
      sp.key = p.at("key").get<std::string>();
      sp.unit = p.at("unit").get<std::string>();
      sp.log_scale = p.at("scale").get<std::string>() == "log";
      sp.values = p.at("values").get<std::vector<double>>();
      study.parameters.push_back(std::move(sp));
    }
    for (const auto& c : j.at("cases")) {
      StudyCase sc;
      sc.name = c.at("name").get<std::string>();
      sc.parameter_values = c.at("parameter_values").get<std::vector<double>>();
      study.cases.push_back(std::move(sc));
    }
  } catch (const std::exception& e) {
    throw std::invalid_argument(fmt::format("{}/study.json: not a study's record: {}", dir, e.what()));
  }
  // The results: study.csv, the status and OUTPUT@TIME columns of each case.
  std::ifstream in(out_dir / "study.csv");
  std::string line;
  std::getline(in, line);
  const auto header = split_csv_line(line);
  const auto column = [&](const std::string& name) -> std::size_t {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw std::invalid_argument(fmt::format("{}/study.csv has no column '{}'", dir, name));
  };
  const std::size_t status = column("status");
  std::vector<std::size_t> cols;
  for (const auto& o : study.outputs)
    for (double t : study.times) cols.push_back(column(detail::output_column(o, t)));
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    // Only the message (last column) may be quoted: the fields before it split at commas.
    const auto f = split_csv_line(line);
    CaseResult r;
    r.name = f.at(0);
    r.status = status < f.size() ? f[status] : "";
    for (std::size_t k : cols) {
      if (k < f.size() && !f[k].empty()) r.values.push_back(std::stod(f[k]));
      else r.values.push_back(std::nullopt);
    }
    results.push_back(std::move(r));
  }
  if (results.size() != study.cases.size())
    throw std::invalid_argument(fmt::format("{}/study.csv has {} cases, study.json {}", dir, results.size(), study.cases.size()));
  plot_histories(study, results, out_dir);
  std::vector<std::string> files{(out_dir / "study.png").string()};
  for (auto& f : plot_sweep(study, results, out_dir)) files.push_back(std::move(f));
  return files;
}

}  // namespace rheodda::study
