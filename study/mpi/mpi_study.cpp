// Cases over MPI ranks: rank 0 dispatches, the other ranks run (mpi_study.hpp).
//
// Messages (MPI_CHAR text, MPI_COMM_WORLD):
//   rank 0 -> worker  kTask   "INDEX RESUME DIR"            run this case
//                     kStop   ""                            SIGTERM the running case
//                     kQuit   ""                            serve no more
//   worker -> rank 0  kResult "INDEX EXIT SIGNAL WALL\nERROR" how the case ended
// Both sides poll (MPI_Iprobe, then a sleep of 1 ms, on workers up to 16 ms) instead of blocking in MPI_Recv,
// which Open MPI implements as a busy wait: an idle rank must not take a core from
// the cases.
#include "mpi_study.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <fmt/format.h>

namespace rheodda::study::mpi {
namespace {

constexpr int kTask = 1, kStop = 2, kQuit = 3, kResult = 4;

void send_text(const std::string& text, int to, int tag) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

/// Receives the probed message.
std::string receive_text(const MPI_Status& probed) {
  int count = 0;
  MPI_Get_count(&probed, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

/// A probed message from `source` (or any rank) with `tag` (or any), without blocking.
bool probe(int source, int tag, MPI_Status& status) {
  int flag = 0;
  MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
  return flag != 0;
}

void pause() { std::this_thread::sleep_for(std::chrono::milliseconds(1)); }

class RankExecutor final : public CaseExecutor {
 public:
  explicit RankExecutor(int size) : size_(size) {
    for (int r = 1; r < size; ++r) idle_.push_back(r);
  }
  ~RankExecutor() override {
    for (const auto& [rank, _] : busy_) send_text("", rank, kStop);  // an exception on the way: stop the cases
    for (int r = 1; r < size_; ++r) send_text("", r, kQuit);
  }
  std::size_t capacity() const override { return static_cast<std::size_t>(size_ - 1); }
  std::size_t running() const override { return busy_.size(); }
  void start(const CaseTask& task) override {
    if (idle_.empty()) throw std::logic_error("no idle rank");
    const int rank = idle_.front();
    idle_.pop_front();
    send_text(fmt::format("{} {} {}", task.index, task.resume ? 1 : 0, task.dir), rank, kTask);
    busy_[rank] = task.index;
  }
  std::optional<CaseOutcome> poll() override {
    MPI_Status st;
    if (!probe(MPI_ANY_SOURCE, kResult, st)) {
      pause();
      return std::nullopt;
    }
    const std::string text = receive_text(st);
    CaseOutcome o;
    std::istringstream in(text);
    in >> o.index >> o.exit_code >> o.signal >> o.wall_seconds;
    in.ignore(1);
    std::getline(in, o.error, '\0');
    busy_.erase(st.MPI_SOURCE);
    idle_.push_back(st.MPI_SOURCE);
    return o;
  }
  void stop_all() override {
    for (const auto& [rank, _] : busy_) send_text("", rank, kStop);
  }

 private:
  int size_;
  std::deque<int> idle_;
  std::map<int, std::size_t> busy_;  // rank -> case index
};

}  // namespace

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

Session::Session() {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Session::~Session() { MPI_Finalize(); }

std::unique_ptr<CaseExecutor> rank_executor(const Session& session) {
  return std::make_unique<RankExecutor>(session.size());
}

void serve_cases(const std::string& binary, const volatile std::sig_atomic_t* stop) {
  // The per-case process isolation of `rheodda study -j`; this loop does its own waiting.
  const auto local = local_executor(binary, 1, 0);
  bool stopped = false;
  // Waiting backs off from 1 to 16 ms while nothing happens: 64 oversubscribed ranks
  // polling every millisecond would take the cores from rank 0 and the cases.
  int wait_ms = 1;
  for (;;) {
    bool active = false;
    if (stop && *stop && !stopped && local->running() > 0) {
      local->stop_all();
      stopped = true;
    }
    if (local->running() > 0) {
      if (auto o = local->poll()) {
        send_text(fmt::format("{} {} {} {}\n{}", o->index, o->exit_code, o->signal, o->wall_seconds, o->error), 0,
                  kResult);
        stopped = false;
        active = true;
      }
    }
    MPI_Status st;
    if (!probe(0, MPI_ANY_TAG, st)) {
      if (active) {
        wait_ms = 1;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
        wait_ms = std::min(16, 2 * wait_ms);
      }
      continue;
    }
    wait_ms = 1;
    const std::string text = receive_text(st);
    if (st.MPI_TAG == kQuit) {
      if (local->running() > 0) local->stop_all();  // rank 0 gave up (an error): leave no case behind
      return;  // the executor's destructor waits for the case process
    }
    if (st.MPI_TAG == kStop) {
      if (local->running() > 0 && !stopped) local->stop_all();
      stopped = true;
      continue;
    }
    // kTask
    std::istringstream in(text);
    CaseTask task;
    int resume = 0;
    in >> task.index >> resume;
    in.ignore(1);
    std::getline(in, task.dir, '\0');
    task.resume = resume != 0;
    const auto start = std::chrono::steady_clock::now();
    try {
      local->start(task);
    } catch (const std::exception& e) {  // e.g. the case program cannot be started on this node
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      send_text(fmt::format("{} {} {} {}\n{}", task.index, -1, 0, wall, e.what()), 0, kResult);
    }
  }
}

void run_over_ranks(const std::string& binary, const volatile std::sig_atomic_t* stop,
                    const std::function<void(CaseExecutor*)>& rank0) {
  const Session session;
  if (session.rank() != 0) return serve_cases(binary, stop);
  std::unique_ptr<CaseExecutor> ranks;
  if (session.size() > 1) ranks = rank_executor(session);  // its destructor tells the workers to quit
  rank0(ranks.get());
}

}  // namespace rheodda::study::mpi
