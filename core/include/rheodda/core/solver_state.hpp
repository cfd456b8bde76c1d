// What the linear solver (solver.hpp) reports and what it carries from one
// solve to the next. Apart from solver.hpp so that the engine's state
// (engine.hpp, EngineState) and the solvers (solver.hpp, block_amg.hpp) each
// take these two types without the other's header.
#pragma once

#include <utility>
#include <vector>

#include "rheodda/core/model.hpp"

namespace rheodda::core {

/// Counters of the linear solver since the engine was built.
struct SolverStats {
  long analyses = 0;        ///< CHOLMOD symbolic analyses (pattern changes) [-]
  long factorizations = 0;  ///< CHOLMOD numeric factorisations [-]
  long solves = 0;          ///< linear solves [-]
  long pcg_iterations = 0;  ///< total PCG iterations [-]
  /// Under `automatic`: the step at whose solve amg's conjugate gradient did not
  /// converge and CHOLMOD took over for the rest of the run (-1: never) [-].
  long amg_fallback_solve = -1;
};

/// What the linear solver carries from one solve to the next (solver.hpp):
/// enough for a solver restored from it to solve the next systems bit for bit
/// as the one it was taken from (a resumed run, docs/reference/outputs.md "Interrupting
/// and resuming"). CHOLMOD keeps nothing that a fresh analysis of the same
/// pattern would not give again; amg keeps its warm start and the part of its
/// hierarchy that depends on earlier systems (block_amg.hpp, "Reuse").
struct SolverState {
  bool amg_failed = false;       ///< automatic: amg gave way to CHOLMOD for the rest of the run
  long amg_fallback_solve = -1;  ///< SolverStats::amg_fallback_solve of that event [-]
  std::vector<double> warm_start;  ///< amg: the last solution, start of the next solve
  /// amg: the hierarchy's aggregates as they were built for the block pattern
  /// `pattern` (level-0 block pairs (i, j)); empty when there is none.
  std::vector<std::pair<int, int>> pattern;
  std::vector<Vec2> positions;     ///< level-0 block points at the last refresh that moved them [length]
  std::vector<std::vector<int>> aggregates;  ///< per level but the coarsest: coarse block of each block
  std::vector<int> coarse_blocks;  ///< per level but the coarsest: blocks of the next level [-]
  std::vector<double> omega;       ///< per level but the coarsest: prolongator smoothing weight [-]
};

}  // namespace rheodda::core
