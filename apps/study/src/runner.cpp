// Running a study: one child `rheodda run` process per case, at most `jobs` at once;
// then study.csv and the overlay plot (docs/studies.md).
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/prctl.h>
#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "rheodda/scene/plot.hpp"
#include "rheodda/study/study.hpp"

extern char** environ;

namespace rheodda::study {
namespace fs = std::filesystem;
namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream b;
  b << in.rdbuf();
  return b.str();
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char ch : line) {
    if (ch == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (ch != '\r') {
      cur += ch;
    }
  }
  out.push_back(cur);
  return out;
}

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"') q += '"';
    q += ch == '\n' ? ' ' : ch;
  }
  return q + "\"";
}

/// The last non-empty line of a log (the child's error message).
std::string last_line(const std::string& text) {
  std::istringstream in(text);
  std::string l, last;
  while (std::getline(in, l))
    if (!l.empty()) last = l;
  return last;
}

struct Running {
  std::size_t index;
  std::chrono::steady_clock::time_point start;
};

pid_t spawn_case(const std::string& binary, const fs::path& dir, bool resume) {
  // The case program is called as `PROGRAM run SCENE -o DIR [--resume]` (rheodda itself, or --case-program).
  const std::string scene = (dir / "scene.yaml").string();
  const std::string out = dir.string();
  const std::string log = (dir / "log.txt").string();
  std::vector<std::string> args{binary, "run", scene, "-o", out};
  if (resume) args.emplace_back("--resume");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // fork and exec rather than posix_spawn, for the parent-death signal: a case must
  // not outlive the study (a SIGKILL of `rheodda study` leaves no case running on, in
  // the folder a `--resume` will use). The signal is SIGKILL: a run killed at any
  // moment resumes to identical files (docs/outputs.md). A pipe closed by the exec
  // (O_CLOEXEC) brings back the errno of an exec that failed.
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", binary, std::strerror(errno)));
  const pid_t parent = ::getpid();
  const int log_flags = O_WRONLY | O_CREAT | (resume ? O_APPEND : O_TRUNC);
  const pid_t pid = ::fork();
  if (pid == 0) {
    // The child: only async-signal-safe calls until the exec.
    int error = 0;
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) error = ESRCH;  // the study already died
    const int out_fd = error ? -1 : ::open(log.c_str(), log_flags, 0644);
    const int in_fd = error ? -1 : ::open("/dev/null", O_RDONLY);
    if (!error && (out_fd < 0 || in_fd < 0)) error = errno;
    if (!error && (::dup2(out_fd, STDOUT_FILENO) < 0 || ::dup2(out_fd, STDERR_FILENO) < 0 ||
                   ::dup2(in_fd, STDIN_FILENO) < 0))
      error = errno;
    if (!error) {
      ::execve(binary.c_str(), argv.data(), environ);
      error = errno;
    }
    [[maybe_unused]] const ssize_t w = ::write(report[1], &error, sizeof error);
    ::_exit(127);
  }
  const int fork_errno = errno;
  ::close(report[1]);
  if (pid < 0) {
    ::close(report[0]);
    throw std::runtime_error(fmt::format("cannot start {}: {}", binary, std::strerror(fork_errno)));
  }
  int child_error = 0;
  ssize_t got = 0;
  do got = ::read(report[0], &child_error, sizeof child_error);
  while (got < 0 && errno == EINTR);
  ::close(report[0]);
  if (got == static_cast<ssize_t>(sizeof child_error)) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    throw std::runtime_error(fmt::format("cannot start {}: {}", binary, std::strerror(child_error)));
  }
  return pid;
}

void collect(const StudyDescription& study, const fs::path& dir, CaseResult& r) {
  const fs::path summary = dir / "summary.json";
  std::string summary_status;
  if (fs::exists(summary)) {
    try {
      const auto j = nlohmann::json::parse(read_text(summary));
      r.steps = j.value("steps", 0);
      if (j.contains("static_mechanism") && j["static_mechanism"].is_object())
        r.inertia_share = j["static_mechanism"].value("inertia_share", 0.0);
      summary_status = j.value("status", "");
      if (j.contains("error") && j["error"].is_string()) r.message = j["error"].get<std::string>();
    } catch (const std::exception& e) {
      r.message = fmt::format("unreadable summary.json: {}", e.what());
    }
  }
  const bool ok = r.exit_code == 0 && summary_status == "completed";
  r.status = ok ? "completed" : "failed";
  if (summary_status == "interrupted") {
    r.status = "interrupted";
    r.message = "stopped with the study; `rheodda study ... --resume` continues it";
  }
  if (!ok && r.message.empty() && r.status != "interrupted") {
    const std::string l = last_line(read_text(dir / "log.txt"));
    if (r.exit_code < 0) r.message = l.empty() ? "killed by a signal" : "killed by a signal; " + l;
    else r.message = l.empty() ? fmt::format("exit code {}", r.exit_code) : l;
  }
  if (ok) r.message.clear();
  r.values.assign(study.outputs.size() * study.times.size(), std::nullopt);
  if (!fs::exists(dir / "history.csv")) return;
  for (std::size_t i = 0; i < study.outputs.size(); ++i) {
    try {
      const auto series = read_history_series((dir / "history.csv").string(), study.outputs[i]);
      for (std::size_t k = 0; k < study.times.size(); ++k)
        r.values[i * study.times.size() + k] = value_at(series, study.times[k]);
    } catch (const std::exception& e) {
      if (r.message.empty()) r.message = e.what();
    }
  }
}

// Shortest text that reads back as the same double: study.csv holds the runs' values exactly.
std::string format_value(double v) { return fmt::format("{}", v); }

void write_study_csv(const StudyDescription& study, const std::vector<CaseResult>& results, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  out << "case,status";
  for (const auto& p : study.parameters) out << "," << p.name << " [" << p.unit << "]";
  for (const auto& o : study.outputs)
    for (double t : study.times) out << "," << csv_quote(fmt::format("{}@{:g}", o, t));
  out << ",wall_seconds,steps,inertia_share,message\n";
  for (std::size_t c = 0; c < results.size(); ++c) {
    const auto& r = results[c];
    out << csv_quote(r.name) << "," << r.status;
    const auto& pv = study.cases[c].parameter_values;
    for (std::size_t i = 0; i < study.parameters.size(); ++i) out << "," << (i < pv.size() ? format_value(pv[i]) : "");
    for (const auto& v : r.values) out << "," << (v ? format_value(*v) : "");
    out << "," << fmt::format("{:.3f}", r.wall_seconds) << "," << r.steps << ","
        << (r.inertia_share ? format_value(*r.inertia_share) : "") << "," << csv_quote(r.message) << "\n";
  }
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
  // Axis units from the first line of a case's history.csv ("# units: length=m force=N time=d ...").
  std::string units, time_unit;
  for (const auto& r : results) {
    std::ifstream h(out_dir / "cases" / r.name / "history.csv");
    std::string first;
    if (!std::getline(h, first) || first.rfind("# units:", 0) != 0) continue;
    units = first.substr(2);
    const auto at = first.find("time=");
    if (at != std::string::npos) time_unit = first.substr(at + 5, first.find(' ', at) - (at + 5));
    break;
  }
  const fs::path gp = out_dir / "study.gp";
  std::ofstream g(gp);
  g << "# Drawn by rheodda study: " << study.plot << " of every case against time.\n"
    << "set terminal pngcairo size 1000,650 noenhanced\n"
    << "set output '" << (out_dir / "study.png").string() << "'\n"
    << "set title '" << scene::gnuplot_text(study.title) << "'\n"
    << "set xlabel 'time" << (time_unit.empty() ? "" : " [" + time_unit + "]") << "'\n"
    << "set ylabel '" << study.plot << (units.empty() ? "" : " (" + units + ")") << "'\n"
    << "set grid\n";
  // Many cases (a sweep): no key (the lines would hide the plot); the sweep pictures name them.
  g << (titles.size() > 12 ? "set key off\n" : "set key outside right\n") << "plot ";
  for (std::size_t i = 0; i < titles.size(); ++i)
    g << (i ? ", \\\n     " : "") << "'" << dat.string() << "' index " << i << " using 1:2 with lines lw 2 title '"
      << scene::gnuplot_text(titles[i]) << "'";
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
  const std::string last_time = fmt::format("{:g}", study.times.back());
  const std::size_t columns = grid ? 1 : ps.size();
  for (std::size_t o = 0; o < study.outputs.size(); ++o) {
    if (grid && ps.size() == 1) {
      Panel pn{param_label(ps[0]), study.outputs[o], ps[0].log_scale, {}};
      for (std::size_t t = 0; t < nt; ++t) {
        Curve cv{fmt::format("t = {:g}", study.times[t]), {}};
        for (std::size_t c = 0; c < results.size(); ++c)
          if (swept(c))
            if (auto v = value(c, o, t)) cv.points.emplace_back(study.cases[c].parameter_values[0], *v);
        pn.curves.push_back(std::move(cv));
      }
      panels.push_back(std::move(pn));
    } else if (grid) {
      Panel pn{param_label(ps[0]), study.outputs[o] + " at t = " + last_time, ps[0].log_scale, {}};
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
        Panel pn{param_label(ps[i]), study.outputs[o] + " at t = " + last_time, ps[i].log_scale, {}};
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
    g << "# Drawn by rheodda study: the outputs against the swept parameters (docs/studies.md).\n"
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
          << (grid ? "linespoints lw 2 pt 7" : "points pt 7") << " title '" << scene::gnuplot_text(pn.curves[i].title) << "'";
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
      << "set cblabel '" << scene::gnuplot_text(study.plot + " at t = " + last_time) << "'\n"
      << "splot '" << mdat.string() << "' using 1:2:3 with pm3d notitle, '' using 1:2:3 with points pt 7 lc rgb 'black' notitle\n";
  }
  scene::run_gnuplot(mgp.string());
  files.push_back((out_dir / "study_map.png").string());
  return files;
}

/// study.json: what `rheodda plot OUTDIR` needs besides study.csv to redraw a study.
void write_study_json(const StudyDescription& study, const fs::path& path) {
  using nlohmann::json;
  json ps = json::array();
  for (const auto& p : study.parameters)
    ps.push_back({{"name", p.name}, {"key", p.key}, {"unit", p.unit}, {"scale", p.log_scale ? "log" : "linear"},
                  {"values", p.values}});
  json cases = json::array();
  for (const auto& c : study.cases) cases.push_back({{"name", c.name}, {"parameter_values", c.parameter_values}});
  const char* method = study.method == SweepMethod::grid ? "grid"
                       : study.method == SweepMethod::random ? "random" : "latin_hypercube";
  const json j{{"study", study.file}, {"title", study.title}, {"scene", study.scene}, {"outputs", study.outputs},
               {"times", study.times}, {"plot", study.plot}, {"method", method}, {"samples", study.samples},
               {"seed", study.seed}, {"parameters", ps}, {"cases", cases}};
  std::ofstream(path, std::ios::binary) << j.dump(2) << "\n";
}

}  // namespace

std::vector<std::pair<double, double>> read_history_series(const std::string& history_csv, const std::string& column) {
  std::ifstream in(history_csv);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", history_csv));
  std::string line;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    header = split_csv_line(line);
    break;
  }
  const auto col = [&](const std::string& name) -> int {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  };
  const int it = col("time");
  int iu = col(column), iv = -1;
  const std::string suffix = ".displacement";
  if (iu < 0 && column.size() > suffix.size() && column.compare(column.size() - suffix.size(), suffix.size(), suffix) == 0) {
    const std::string point = column.substr(0, column.size() - suffix.size());
    iu = col(point + ".u");
    iv = col(point + ".v");
    if (iv < 0) iu = -1;
  }
  if (it < 0 || iu < 0) throw std::runtime_error(fmt::format("{} has no column '{}'", history_csv, column));
  std::vector<std::pair<double, double>> out;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto f = split_csv_line(line);
    const auto at = [&](int i) { return i < static_cast<int>(f.size()) ? f[static_cast<std::size_t>(i)] : std::string(); };
    if (at(iu).empty() || (iv >= 0 && at(iv).empty())) continue;  // e.g. no closed contact at that time
    const double t = std::stod(at(it));
    const double u = std::stod(at(iu));
    out.emplace_back(t, iv >= 0 ? std::hypot(u, std::stod(at(iv))) : u);
  }
  return out;
}

std::optional<double> value_at(const std::vector<std::pair<double, double>>& s, double t) {
  if (s.empty() || t < s.front().first || t > s.back().first) {
    // Tolerate rounding of the last time (the run ends at its duration up to float addition).
    if (!s.empty() && std::abs(t - s.back().first) <= 1e-9 * std::max(1.0, std::abs(t))) return s.back().second;
    return std::nullopt;
  }
  for (std::size_t i = 1; i < s.size(); ++i)
    if (t <= s[i].first) {
      const auto [t0, v0] = s[i - 1];
      const auto [t1, v1] = s[i];
      if (t1 == t0) return v1;
      return v0 + (v1 - v0) * (t - t0) / (t1 - t0);  // linear interpolation between the two history rows
    }
  return s.back().second;
}

namespace {

/// Cases as child processes of this one (`rheodda run`), at most `jobs` at once.
class LocalExecutor final : public CaseExecutor {
 public:
  LocalExecutor(std::string binary, std::size_t jobs, int poll_sleep_ms)
      : binary_(std::move(binary)), jobs_(jobs), poll_sleep_ms_(poll_sleep_ms) {}
  ~LocalExecutor() override {
    for (const auto& [pid, _] : running_) {  // an exception on the way: leave no case process behind
      ::kill(pid, SIGTERM);
      int status = 0;
      waitpid(pid, &status, 0);
    }
  }
  std::size_t capacity() const override { return jobs_; }
  void start(const CaseTask& task) override {
    const pid_t pid = spawn_case(binary_, task.dir, task.resume);
    running_[pid] = {task.index, std::chrono::steady_clock::now()};
  }
  std::optional<CaseOutcome> poll() override {
    for (const auto& [p, r] : running_) {
      int status = 0;
      if (waitpid(p, &status, WNOHANG) != p) continue;
      // Wait for one of this study's children only (not for any other child of the process).
      CaseOutcome o;
      o.index = r.index;
      o.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
      o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
      running_.erase(p);
      return o;
    }
    if (poll_sleep_ms_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(poll_sleep_ms_));
    return std::nullopt;
  }
  void stop_all() override {
    for (const auto& [p, _] : running_) ::kill(p, SIGTERM);
  }
  std::size_t running() const override { return running_.size(); }

 private:
  std::string binary_;
  std::size_t jobs_;
  int poll_sleep_ms_;
  std::map<pid_t, Running> running_;
};

}  // namespace

std::unique_ptr<CaseExecutor> local_executor(const std::string& binary, std::size_t jobs, int poll_sleep_ms) {
  return std::make_unique<LocalExecutor>(binary, std::max<std::size_t>(1, jobs), poll_sleep_ms);
}

std::string case_binary(const StudyOptions& options) {
  return options.rheodda_binary.empty() ? fs::read_symlink("/proc/self/exe").string() : options.rheodda_binary;
}

std::vector<CaseResult> run_study(const StudyDescription& study, const StudyOptions& options) {
  auto stop_requested = [&] { return options.stop && *options.stop != 0; };
  // A bad study throws before anything runs; a stop while the cases are prepared
  // (20 000 of them take seconds) returns before anything is written.
  const std::vector<std::string> texts = prepare_cases(study, options.stop);
  std::vector<CaseResult> results(study.cases.size());
  auto not_started = [&](std::size_t from) {
    for (std::size_t i = from; i < results.size(); ++i) {
      results[i].name = study.cases[i].name;
      results[i].status = "not started";
      results[i].message = "the study was stopped before this case started; `rheodda study ... --resume` runs it";
      results[i].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
    }
  };
  if (stop_requested()) {
    not_started(0);
    return results;
  }
  const fs::path out_dir = options.out_dir;
  std::unique_ptr<CaseExecutor> own;
  CaseExecutor* exec = options.executor;
  if (exec == nullptr) {
    const int jobs = options.jobs > 0 ? options.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    own = local_executor(case_binary(options), static_cast<std::size_t>(jobs));
    exec = own.get();
  }

  // What each case needs: run, resume (an interrupted run of the same scene), or
  // nothing (a completed run of the same scene, under options.resume). "The same
  // scene" is the same scene text below the header comment, which names the study
  // and the base scene by the paths as typed: another spelling, another working
  // directory or a moved folder is the same case (the kept scene.yaml is not
  // rewritten, so `rheodda run --resume` finds the scene its checkpoint hashed).
  enum class Todo { run, resume, keep };
  std::vector<Todo> todo(study.cases.size(), Todo::run);
  for (std::size_t i = 0; i < study.cases.size(); ++i) {
    if (stop_requested()) {  // the folders of 20 000 cases take seconds too
      not_started(0);
      return results;
    }
    const fs::path dir = out_dir / "cases" / study.cases[i].name;
    results[i].name = study.cases[i].name;
    if (options.resume && fs::exists(dir / "scene.yaml") &&
        case_scene_body(read_text(dir / "scene.yaml")) == case_scene_body(texts[i])) {
      std::string status;
      try {
        status = nlohmann::json::parse(read_text(dir / "summary.json")).value("status", "");
      } catch (const std::exception&) {
      }
      if (status == "completed") todo[i] = Todo::keep;
      else if (fs::exists(dir / "checkpoint.json")) todo[i] = Todo::resume;
    }
    if (todo[i] != Todo::run) continue;
    fs::remove_all(dir);  // a case folder holds one run only
    fs::create_directories(dir);
    std::ofstream(dir / "scene.yaml", std::ios::binary) << texts[i];
  }

  std::size_t next = 0, done = 0;
  bool stopping = false;
  while (done < results.size()) {
    if (stop_requested() && !stopping) {
      // Stop the running cases (each stops after its step, keeping a checkpoint);
      // start no more.
      stopping = true;
      exec->stop_all();
    }
    while (!stopping && next < results.size() && exec->running() < exec->capacity()) {
      const fs::path dir = out_dir / "cases" / results[next].name;
      if (todo[next] == Todo::keep) {
        results[next].exit_code = 0;
        collect(study, dir, results[next]);
        try {
          results[next].wall_seconds =
              nlohmann::json::parse(read_text(dir / "summary.json")).value("wall_seconds", 0.0);
        } catch (const std::exception&) {
        }
        ++done;
        ++next;
        continue;
      }
      try {
        exec->start({next, dir.string(), todo[next] == Todo::resume});
      } catch (const std::exception& e) {
        results[next].status = "failed";
        results[next].exit_code = -1;
        results[next].message = e.what();
        results[next].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
        ++done;
      }
      ++next;
    }
    if (exec->running() == 0) {
      if (stopping || done == results.size()) break;
      continue;
    }
    const std::optional<CaseOutcome> o = exec->poll();
    if (!o) continue;  // nothing finished yet (a stop request is handled at the top of the loop)
    CaseResult& res = results[o->index];
    res.wall_seconds = o->wall_seconds;
    res.exit_code = o->exit_code;
    collect(study, out_dir / "cases" / res.name, res);
    const std::string killed = "killed by a signal";
    if (o->signal != 0 && res.message.rfind(killed, 0) == 0)
      res.message = fmt::format("killed by signal {} ({}){}", o->signal, strsignal(o->signal), res.message.substr(killed.size()));
    if (!o->error.empty()) res.message = o->error;
    ++done;
    if (options.progress)
      fmt::print(stderr, "[{}/{}] {}: {} ({:.1f} s, {} steps){}\n", done, results.size(), res.name, res.status,
                 res.wall_seconds, res.steps, res.message.empty() ? "" : ": " + res.message);
  }
  not_started(next);
  write_study_csv(study, results, out_dir / "study.csv");
  write_study_json(study, out_dir / "study.json");
  if (stopping) return results;
  if (options.plot) (void)plot_study_dir(out_dir.string());
  return results;
}

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
    for (double t : study.times) cols.push_back(column(fmt::format("{}@{:g}", o, t)));
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
