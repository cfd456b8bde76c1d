// A study's cases spread over MPI ranks (docs/guide/studies.md, "On a cluster: MPI"):
// `mpirun -np N rheodda study STUDY.yaml -o OUT` (or `srun`). Rank 0 prepares the
// study, hands one case at a time to whichever worker rank is idle (a dynamic queue:
// a slow case holds only its own rank), gathers the outcomes and writes study.csv;
// ranks 1..N-1 run each case they are given as a child process (`rheodda run`), so
// a case that crashes takes down its process, not the rank. The case folders are on
// a file system every rank sees (OUT/cases/NAME/).
//
// Not installed with the library (rheodda::study stays free of MPI); the rheodda
// program links it when CMake finds MPI.
#pragma once

#include <csignal>
#include <functional>
#include <memory>
#include <string>

#include "rheodda/study/study.hpp"

namespace rheodda::study::mpi {

/// True when an MPI launcher started this process (mpirun/mpiexec of Open MPI, srun,
/// a PMI or PMIx launcher): its environment says so. Checked before MPI_Init, so that
/// a plain `rheodda study` never starts MPI.
bool launched_by_mpi();

/// MPI_Init on construction, MPI_Finalize on destruction.
class Session {
 public:
  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

/// Rank 0's executor: each case goes to an idle rank among 1..size-1 (capacity size-1).
/// Its destructor tells every worker rank to stop serving (also after an exception).
std::unique_ptr<CaseExecutor> rank_executor(const Session& session);

/// Ranks 1..size-1: run the cases rank 0 sends, one at a time, each as a child process
/// of `binary` (`binary run DIR/scene.yaml -o DIR`), and report how each ended, until rank 0
/// says stop. When *stop becomes non-zero (SIGINT/SIGTERM), the running case is sent
/// SIGTERM (it stops after its step with a checkpoint) and reported.
void serve_cases(const std::string& binary, const volatile std::sig_atomic_t* stop);

/// The whole MPI life of a command: MPI_Init; on rank 0, `rank0(executor)` with an
/// executor over ranks 1..size-1 (null when there is one rank only: run locally); on the
/// other ranks serve_cases(binary, stop); MPI_Finalize on every way out (also when
/// `rank0` throws, after the workers were told to stop).
void run_over_ranks(const std::string& binary, const volatile std::sig_atomic_t* stop,
                    const std::function<void(CaseExecutor*)>& rank0);

}  // namespace rheodda::study::mpi
