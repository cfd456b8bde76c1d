// The two solvers of K D = F: CHOLMOD and block-Jacobi PCG agree (relative
// 1e-8) with each other and with a dense LDL' of the same K; CHOLMOD's
// symbolic analysis is redone only when the block pattern changes.
#include <boost/test/unit_test.hpp>

#include <omp.h>

#include <filesystem>
#include <random>

#include "rheodda/core/block_system.hpp"
#include "rheodda/core/engine.hpp"
#include "test_support.hpp"
#include "rheodda/core/solver.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

// A random symmetric positive definite block system: a chain plus long-range
// pairs, coupling strong enough that PCG needs many iterations.
void fill_random(BlockSystem& s, int n, std::vector<std::pair<int, int>> pairs, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  s.reset(n);
  for (auto [i, j] : pairs) {
    // Add a positive semi-definite coupling B^T B-like term on (i, j) with a
    // matching diagonal, so K stays positive definite.
    Mat6 c;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) c(a, b) = u(rng);
    s.diagonal(i) += c * c.transpose();
    s.diagonal(j) += c.transpose() * c;
    s.add_stiffness(i, j, -c);
  }
  for (int b = 0; b < n; ++b) {
    s.diagonal(b) += 0.05 * Mat6::Identity();
    for (int a = 0; a < 6; ++a) s.rhs()(6 * b + a) = u(rng);
  }
  s.finalize();
}

std::vector<std::pair<int, int>> chain_pairs(int n, int reach) {
  std::vector<std::pair<int, int>> p;
  for (int i = 0; i + 1 < n; ++i) p.emplace_back(i, i + 1);
  for (int i = 0; i + reach < n; i += 3) p.emplace_back(i + reach, i);  // given as (j, i)
  return p;
}

Eigen::MatrixXd dense(const BlockSystem& s) {
  const int n = s.block_count();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int b = 0; b < n; ++b) K.block<6, 6>(6 * b, 6 * b) = s.diagonal(b);
  for (const auto& o : s.off_diagonal()) {
    K.block<6, 6>(6 * o.i, 6 * o.j) += o.k;
    K.block<6, 6>(6 * o.j, 6 * o.i) += o.k.transpose();
  }
  return K;
}

double rel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); }

}  // namespace

BOOST_AUTO_TEST_SUITE(solver)

BOOST_AUTO_TEST_CASE(cholmod_and_pcg_agree_with_a_dense_solve) {
  BlockSystem s;
  fill_random(s, 60, chain_pairs(60, 7), 1);
  const Eigen::VectorXd ref = dense(s).ldlt().solve(s.rhs());
  LinearSolver chol(SolverKind::cholmod), pcg(SolverKind::pcg, 1e-13, 5000);
  const Eigen::VectorXd x1 = chol.solve(s), x2 = pcg.solve(s);
  BOOST_TEST(rel(x1, ref) <= 1e-10);
  BOOST_TEST(rel(x2, x1) <= 1e-8);
  BOOST_TEST(pcg.stats().pcg_iterations > 1);
  BOOST_TEST((s.multiply(x1) - s.rhs()).norm() <= 1e-10 * s.rhs().norm());
}

BOOST_AUTO_TEST_CASE(symbolic_analysis_is_reused_while_the_pattern_is_unchanged) {
  LinearSolver chol(SolverKind::cholmod);
  BlockSystem s;
  const int n = 40;
  const auto pairs = chain_pairs(n, 5);
  for (unsigned seed = 1; seed <= 4; ++seed) {
    fill_random(s, n, pairs, seed);  // new values, same pattern
    const Eigen::VectorXd x = chol.solve(s);
    BOOST_TEST(rel(x, dense(s).ldlt().solve(s.rhs())) <= 1e-10);
  }
  BOOST_TEST(chol.stats().analyses == 1);
  BOOST_TEST(chol.stats().factorizations == 4);
  // Same pairs given in another order and orientation: still the same pattern.
  auto shuffled = pairs;
  std::reverse(shuffled.begin(), shuffled.end());
  for (auto& p : shuffled) std::swap(p.first, p.second);
  fill_random(s, n, shuffled, 9);
  chol.solve(s);
  BOOST_TEST(chol.stats().analyses == 1);
  // A new pair changes the pattern: one more analysis, and the answer is right.
  auto more = pairs;
  more.emplace_back(0, n - 1);
  fill_random(s, n, more, 10);
  const Eigen::VectorXd x = chol.solve(s);
  BOOST_TEST(chol.stats().analyses == 2);
  BOOST_TEST(rel(x, dense(s).ldlt().solve(s.rhs())) <= 1e-10);
}

BOOST_AUTO_TEST_CASE(cholmod_factorises_on_the_callers_thread_and_leaves_openmp_as_it_was) {
  // Debian's CHOLMOD opens its supernodal regions with four OpenMP threads, which
  // waited on each other on two cores (3.3x slower factorisations): rheodda runs
  // them serially. A model large enough for supernodal factorisation (a 2-D grid
  // of 40 x 40 blocks joined to their neighbours) is solved without the process
  // gaining a thread, and the caller's OpenMP setting is as it was.
  auto threads = [] {
    return std::distance(std::filesystem::directory_iterator("/proc/self/task"), std::filesystem::directory_iterator{});
  };
  BlockSystem s;
  const int side = 40, n = side * side;
  std::vector<std::pair<int, int>> pairs;
  for (int r = 0; r < side; ++r)
    for (int c = 0; c < side; ++c) {
      if (c + 1 < side) pairs.emplace_back(r * side + c, r * side + c + 1);
      if (r + 1 < side) pairs.emplace_back(r * side + c, (r + 1) * side + c);
    }
  fill_random(s, n, pairs, 5);
  omp_set_max_active_levels(3);
  const auto before = threads();
  LinearSolver chol(SolverKind::cholmod);
  const Eigen::VectorXd x = chol.solve(s);
  BOOST_TEST((s.multiply(x) - s.rhs()).norm() <= 1e-10 * s.rhs().norm());
  BOOST_TEST(threads() == before);
  BOOST_TEST(omp_get_max_active_levels() == 3);
  omp_set_max_active_levels(1);
}

BOOST_AUTO_TEST_CASE(block_diagonal_system_is_solved_exactly_by_both) {
  BlockSystem s;
  fill_random(s, 10, {}, 3);
  LinearSolver chol(SolverKind::cholmod), pcg(SolverKind::pcg);
  const Eigen::VectorXd x1 = chol.solve(s), x2 = pcg.solve(s);
  BOOST_TEST(rel(x1, x2) <= 1e-12);
  BOOST_TEST(pcg.stats().pcg_iterations <= 1);
}

BOOST_AUTO_TEST_CASE(engine_without_contacts_analyses_once) {
  Model m;
  m.settings.dt = 0.01;
  m.settings.max_displacement_ratio = 1.0;
  for (int k = 0; k < 5; ++k)
    m.blocks.push_back(block({{2.0 * k, 0}, {2.0 * k + 1, 0}, {2.0 * k + 1, 1}, {2.0 * k, 1}}));
  Engine e(m);
  e.run(20);
  BOOST_TEST(e.solver_stats().analyses == 1);
  BOOST_TEST(e.solver_stats().factorizations == 20);
}

BOOST_AUTO_TEST_CASE(a_matrix_that_is_not_positive_definite_is_reported_at_its_block_and_unknown) {
  // Three blocks, block 1's rotation r0 with no stiffness at all:
  // every solver names block 1 (cholmod also the unknown, through its ordering).
  BlockSystem s;
  s.reset(3);
  for (int b = 0; b < 3; ++b) {
    s.diagonal(b) = Mat6::Identity();
    s.rhs().segment<6>(6 * b).setOnes();
  }
  s.diagonal(1)(2, 2) = 0.0;  // a rotation nothing holds (an exact zero pivot)
  s.add_stiffness(0, 2, 0.1 * Mat6::Identity());  // a pattern for the fill-reducing ordering to permute
  s.finalize();
  for (SolverKind kind : {SolverKind::cholmod, SolverKind::pcg}) {
    LinearSolver solver(kind);
    try {
      (void)solver.solve(s);
      BOOST_ERROR("no error for a matrix that is not positive definite");
    } catch (const SingularSystemError& e) {
      BOOST_TEST(e.block == 1, e.what());
      if (kind == SolverKind::cholmod) {
        BOOST_TEST(e.unknown == 2, e.what());
        BOOST_TEST(std::string(e.what()).find("r0 (rotation)") != std::string::npos, e.what());
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
