// Running a study: one child `rheodda run` process per case, at most `jobs` at once;
// then study.csv and the overlay plot (docs/studies.md).
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

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
  const std::string scene = (dir / "scene.yaml").string();
  const std::string out = dir.string();
  const std::string log = (dir / "log.txt").string();
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | (resume ? O_APPEND : O_TRUNC), 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<std::string> args{binary, "run", scene, "-o", out};
  if (resume) args.emplace_back("--resume");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, binary.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", binary, std::strerror(rc)));
  return pid;
}

void collect(const StudyDescription& study, const fs::path& dir, CaseResult& r) {
  const fs::path summary = dir / "summary.json";
  std::string summary_status;
  if (fs::exists(summary)) {
    try {
      const auto j = nlohmann::json::parse(read_text(summary));
      r.steps = j.value("steps", 0);
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
    r.message = r.exit_code < 0 ? fmt::format("killed by a signal; {}", l)
                                : (l.empty() ? fmt::format("exit code {}", r.exit_code) : l);
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
  for (const auto& o : study.outputs)
    for (double t : study.times) out << "," << csv_quote(fmt::format("{}@{:g}", o, t));
  out << ",wall_seconds,steps,message\n";
  for (const auto& r : results) {
    out << csv_quote(r.name) << "," << r.status;
    for (const auto& v : r.values) out << "," << (v ? format_value(*v) : "");
    out << "," << fmt::format("{:.3f}", r.wall_seconds) << "," << r.steps << "," << csv_quote(r.message) << "\n";
  }
}

/// Text inside a gnuplot single-quoted string ('' stands for ').
std::string gp_text(const std::string& s) {
  std::string q;
  for (char ch : s) q += ch == '\'' ? std::string("''") : std::string(1, ch);
  return q;
}

void plot_study(const StudyDescription& study, const std::vector<CaseResult>& results, const fs::path& out_dir) {
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
    titles.push_back(r.status == "completed" ? r.name : r.name + " (failed)");
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
    << "set title '" << gp_text(study.title) << "'\n"
    << "set xlabel 'time" << (time_unit.empty() ? "" : " [" + time_unit + "]") << "'\n"
    << "set ylabel '" << study.plot << (units.empty() ? "" : " (" + units + ")") << "'\n"
    << "set key outside right\nset grid\n"
    << "plot ";
  for (std::size_t i = 0; i < titles.size(); ++i)
    g << (i ? ", \\\n     " : "") << "'" << dat.string() << "' index " << i << " using 1:2 with lines lw 2 title '"
      << titles[i] << "'";
  g << "\n";
  g.close();
  const std::string prog = "gnuplot";
  std::string gps = gp.string();
  char* argv[] = {const_cast<char*>(prog.c_str()), gps.data(), nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv, environ) != 0)
    throw std::runtime_error("cannot start gnuplot (installed by scripts/install-deps.sh)");
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error(fmt::format("gnuplot failed on {}", gps));
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

std::vector<CaseResult> run_study(const StudyDescription& study, const StudyOptions& options) {
  const std::vector<std::string> texts = prepare_cases(study);  // a bad study throws before anything runs
  const fs::path out_dir = options.out_dir;
  std::string binary = options.rheodda_binary;
  if (binary.empty()) binary = fs::read_symlink("/proc/self/exe").string();
  int jobs = options.jobs > 0 ? options.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  std::vector<CaseResult> results(study.cases.size());
  // What each case needs: run, resume (an interrupted run of the same scene), or
  // nothing (a completed run of the same scene, under options.resume).
  enum class Todo { run, resume, keep };
  std::vector<Todo> todo(study.cases.size(), Todo::run);
  for (std::size_t i = 0; i < study.cases.size(); ++i) {
    const fs::path dir = out_dir / "cases" / study.cases[i].name;
    results[i].name = study.cases[i].name;
    if (options.resume && fs::exists(dir / "scene.yaml") && read_text(dir / "scene.yaml") == texts[i]) {
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

  std::map<pid_t, Running> running;
  std::size_t next = 0, done = 0;
  bool stopping = false;
  auto stop_requested = [&] { return options.stop && *options.stop != 0; };
  while (done < results.size()) {
    if (stop_requested() && !stopping) {
      // Stop the running cases (each stops after its step, keeping a checkpoint);
      // start no more.
      stopping = true;
      for (const auto& [p, _] : running) ::kill(p, SIGTERM);
    }
    while (!stopping && next < results.size() && static_cast<int>(running.size()) < jobs) {
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
        const pid_t pid = spawn_case(binary, dir, todo[next] == Todo::resume);
        running[pid] = {next, std::chrono::steady_clock::now()};
      } catch (const std::exception& e) {
        results[next].status = "failed";
        results[next].exit_code = -1;
        results[next].message = e.what();
        results[next].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
        ++done;
      }
      ++next;
    }
    if (running.empty()) {
      if (stopping) break;
      continue;
    }
    int status = 0;
    pid_t pid = 0;
    // Wait for one of this study's children (not for any other child of the process).
    for (;;) {
      bool any = false;
      for (const auto& [p, _] : running) {
        const pid_t w = waitpid(p, &status, WNOHANG);
        if (w == p) {
          pid = p;
          any = true;
          break;
        }
      }
      if (any) break;
      if (stop_requested() && !stopping) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (pid == 0) continue;  // a stop request: handled at the top of the loop
    const Running r = running.at(pid);
    running.erase(pid);
    CaseResult& res = results[r.index];
    res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
    res.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    collect(study, out_dir / "cases" / res.name, res);
    ++done;
    if (options.progress)
      fmt::print(stderr, "[{}/{}] {}: {} ({:.1f} s, {} steps){}\n", done, results.size(), res.name, res.status,
                 res.wall_seconds, res.steps, res.message.empty() ? "" : ": " + res.message);
  }
  for (std::size_t i = next; i < results.size(); ++i) {
    results[i].status = "not started";
    results[i].message = "the study was stopped before this case started; `rheodda study ... --resume` runs it";
    results[i].values.assign(study.outputs.size() * study.times.size(), std::nullopt);
  }
  if (stopping) {
    write_study_csv(study, results, out_dir / "study.csv");
    return results;
  }
  write_study_csv(study, results, out_dir / "study.csv");
  if (options.plot) plot_study(study, results, out_dir);
  return results;
}

}  // namespace rheodda::study
