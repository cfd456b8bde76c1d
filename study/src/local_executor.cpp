// The local executor of a study: each case a child process of this one
// (`rheodda run`, fork and exec with a parent-death signal), at most `jobs` at once.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/prctl.h>
#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

#include "rheodda/study/study.hpp"

extern char** environ;

namespace rheodda::study {
namespace fs = std::filesystem;
namespace {

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
  // moment resumes to identical files (docs/reference/outputs.md). A pipe closed by the exec
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

}  // namespace rheodda::study
