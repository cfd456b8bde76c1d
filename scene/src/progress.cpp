// Progress display (progress.hpp; docs/reference/cli.md, "Progress").
#include "rheodda/scene/progress.hpp"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string_view>

namespace rheodda::scene {
namespace {

/// Least time between two redraws of a terminal line [s].
constexpr double kTerminalPeriod = 0.2;
/// A ProgressPhase shows nothing for work shorter than this [s] (unless the period is shorter).
constexpr double kPhaseQuiet = 2.0;

/// The terminal's width in columns (80 when it cannot be asked).
int terminal_width(std::FILE* f) {
  winsize w{};
  if (::ioctl(::fileno(f), TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}

}  // namespace

double progress_period() {
  if (const char* p = std::getenv("RHEODDA_PROGRESS_PERIOD"); p && *p) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end != p && *end == '\0' && std::isfinite(v) && v >= 0.0) return v;
  }
  return 10.0;
}

Progress::Progress(std::FILE* stream) : stream_(stream), start_(Clock::now()) {
  if (stream_ == nullptr) return;
  mode_ = ::isatty(::fileno(stream_)) ? ProgressMode::terminal : ProgressMode::lines;
  period_ = mode_ == ProgressMode::terminal ? kTerminalPeriod : progress_period();
}

Progress::~Progress() { finish(); }

bool Progress::due() const {
  if (mode_ == ProgressMode::off) return false;
  const std::lock_guard lock(mutex_);
  return !shown_ || std::chrono::duration<double>(Clock::now() - last_).count() >= period_;
}

double Progress::elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

void Progress::draw_locked(const std::string& text) {
  // One line, cut to the terminal's width: a line that wraps cannot be redrawn by \r.
  const std::size_t width = static_cast<std::size_t>(std::max(10, terminal_width(stream_) - 1));
  const std::string_view shown = std::string_view(text).substr(0, width);
  std::fprintf(stream_, "\r%.*s\033[K", static_cast<int>(shown.size()), shown.data());
  std::fflush(stream_);
  line_open_ = true;
}

void Progress::show(const std::string& text, bool force) {
  if (mode_ == ProgressMode::off) return;
  const std::lock_guard lock(mutex_);
  const auto now = Clock::now();
  if (!force && shown_ && std::chrono::duration<double>(now - last_).count() < period_) return;
  last_ = now;
  shown_ = true;
  if (mode_ == ProgressMode::terminal) {
    text_ = text;
    draw_locked(text);
  } else {
    std::fprintf(stream_, "%s\n", text.c_str());
    std::fflush(stream_);
  }
}

void Progress::note(const std::string& line) {
  if (mode_ == ProgressMode::off) return;
  const std::lock_guard lock(mutex_);
  if (line_open_) std::fprintf(stream_, "\r\033[K");
  std::fprintf(stream_, "%s\n", line.c_str());
  if (line_open_) draw_locked(text_);
  std::fflush(stream_);
}

void Progress::finish() {
  if (mode_ != ProgressMode::terminal) return;
  const std::lock_guard lock(mutex_);
  if (!line_open_) return;
  std::fprintf(stream_, "\n");
  std::fflush(stream_);
  line_open_ = false;
}

ProgressPhase::ProgressPhase(Progress& progress, std::string text)
    : progress_(progress), text_(std::move(text)), start_(Progress::Clock::now()),
      exceptions_(std::uncaught_exceptions()) {
  if (!progress_.on()) return;
  thread_ = std::thread([this] {
    const double quiet = std::min(kPhaseQuiet, progress_period());
    std::unique_lock lock(mutex_);
    while (!stop_) {
      const double took = std::chrono::duration<double>(Progress::Clock::now() - start_).count();
      if (took >= quiet && progress_.due()) {
        progress_.show(fmt::format("{} ... {}", text_, duration_text(took)), !shown_);
        shown_ = true;
      }
      wake_.wait_for(lock, std::chrono::milliseconds(100));
    }
  });
}

ProgressPhase::~ProgressPhase() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (shown_ && std::uncaught_exceptions() == exceptions_) {  // not "done" when the work failed
    const double took = std::chrono::duration<double>(Progress::Clock::now() - start_).count();
    progress_.show(fmt::format("{}: done in {}", text_, duration_text(took)), true);
  }
  progress_.finish();
}

void ProgressPhase::set(std::string text) {
  const std::lock_guard lock(mutex_);
  text_ = std::move(text);
}

void RateEstimate::add(double wall, double done) {
  if (!samples_.empty() && wall - samples_.back().first < 0.5) return;
  samples_.emplace_back(wall, done);
  // Keep one sample at or before the window's start, so that the window spans it whole.
  while (samples_.size() > 2 && samples_[1].first <= wall - window_) samples_.pop_front();
}

std::optional<double> RateEstimate::seconds_left(double done, double target, double least) const {
  if (samples_.size() < 2) return std::nullopt;
  const double wall = samples_.back().first - samples_.front().first;
  const double moved = samples_.back().second - samples_.front().second;
  if (wall < least || !(moved > 0.0)) return std::nullopt;
  return std::max(0.0, target - done) * wall / moved;
}

std::string duration_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02} s", s / 60, s % 60);
  const long m = (s + 30) / 60;
  return fmt::format("{} h {:02} min", m / 60, m % 60);
}

}  // namespace rheodda::scene
