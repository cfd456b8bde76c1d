// Progress of a long command on standard error (docs/reference/cli.md, "Progress"):
// on a terminal one line redrawn in place; otherwise (a log, a pipe) a plain line
// at the start, at most every RHEODDA_PROGRESS_PERIOD seconds (default 10) and at
// the end; nothing under --quiet.
//
// Written by hand: Debian packages no C++ progress-display library (indicators,
// tqdm-cpp and the like are not in it), and a single line redrawn with \r, cut
// to the terminal's width, needs no more than this.
//
// Usage:
//   rheodda::scene::Progress p(quiet ? nullptr : stderr);
//   for (...) if (p.due()) p.show(fmt::format("rheodda x: {} of {}", k, n));
//   p.finish();
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

namespace rheodda::scene {

enum class ProgressMode { off, terminal, lines };

/// The period of the plain lines [s]: RHEODDA_PROGRESS_PERIOD (seconds, >= 0; 0:
/// every update, for tests), else 10.
double progress_period();

class Progress {
 public:
  using Clock = std::chrono::steady_clock;
  /// Off when `stream` is null; a redrawn line when it is a terminal; plain lines otherwise.
  explicit Progress(std::FILE* stream);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  ProgressMode mode() const { return mode_; }
  bool on() const { return mode_ != ProgressMode::off; }
  bool terminal() const { return mode_ == ProgressMode::terminal; }
  /// An update would be shown now: on a terminal every 0.2 s, plain lines every
  /// period. Callers build their text only when it is due.
  bool due() const;
  /// Shows the state `text`: replaces the line on a terminal, prints it as a line
  /// otherwise; when due, or always with `force` (the start and the end).
  void show(const std::string& text, bool force = false);
  /// A line of its own (a finished case): above the redrawn line on a terminal.
  void note(const std::string& line);
  /// Ends the redrawn line (the last state stays on screen). Idempotent.
  void finish();
  /// Wall time since construction [s].
  double elapsed() const;

 private:
  void draw_locked(const std::string& text);
  std::FILE* stream_;
  ProgressMode mode_ = ProgressMode::off;
  double period_ = 10.0;
  Clock::time_point start_;
  Clock::time_point last_{};
  bool shown_ = false;       ///< something was shown (the first update is always due)
  bool line_open_ = false;   ///< terminal: a redrawn line is on screen without its newline
  std::string text_;         ///< terminal: the text of that line
  mutable std::mutex mutex_;
};

/// While it lives: `text` and the seconds it has taken, for work that reports
/// nothing itself (cutting a rock mass, writing bands.csv), drawn by a thread of
/// its own. Shown once the work has lasted 2 s (at once with a period of 0), then
/// as Progress shows updates; at its end "TEXT: done in N s", if it was shown and
/// the work did not fail.
class ProgressPhase {
 public:
  ProgressPhase(Progress& progress, std::string text);
  ~ProgressPhase();
  /// What the work is doing now (shown at the next update).
  void set(std::string text);
  ProgressPhase(const ProgressPhase&) = delete;
  ProgressPhase& operator=(const ProgressPhase&) = delete;

 private:
  Progress& progress_;
  std::string text_;
  Progress::Clock::time_point start_;
  bool stop_ = false;
  bool shown_ = false;
  int exceptions_;  ///< std::uncaught_exceptions() at the start: more at the end, the work failed
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

/// The time left at the rate of the recent past: samples of a measure of the work
/// done (simulated time, cases) against wall time, over the last `window` seconds.
class RateEstimate {
 public:
  explicit RateEstimate(double window = 60.0) : window_(window) {}
  /// Forgets the samples: the rate is that of what comes next (a new stage).
  void reset() { samples_.clear(); }
  /// A sample (wall [s], work done); kept at most one per half second.
  void add(double wall, double done);
  /// Seconds left to reach `target` from `done` at the window's rate; none until
  /// the window spans `least` seconds with the work moving on.
  std::optional<double> seconds_left(double done, double target, double least = 2.0) const;
  /// Wall seconds the samples span [s].
  double span() const { return samples_.size() < 2 ? 0.0 : samples_.back().first - samples_.front().first; }

 private:
  double window_;
  std::deque<std::pair<double, double>> samples_;
};

/// A wall time for people: "42 s", "3 min 10 s", "2 h 05 min".
std::string duration_text(double seconds);

}  // namespace rheodda::scene
