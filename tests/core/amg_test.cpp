// The amg solver (core/src/block_amg.hpp): CG preconditioned by an
// aggregation V-cycle whose coarse unknowns are the DDA unknowns of groups of
// blocks. It must give CHOLMOD's answer, take an iteration count that does
// not grow with the model (block-Jacobi's does), reuse its hierarchy while the
// block pattern holds, restart warm, and keep open contacts (zero blocks) from
// joining aggregates.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "block_amg.hpp"
#include "rheodda/contact/kinematics.hpp"
#include "rheodda/core/block_system.hpp"
#include "rheodda/core/solver.hpp"

using namespace rheodda::core;
using rheodda::contact::BlockView;
using rheodda::contact::displacement_matrix;

namespace {

/// A DDA-like system: an nx x ny grid of 1 x 0.5 blocks (centroids at the
/// cell centres) with, between neighbours, two contacts on the shared edge,
/// each a normal and a shear penalty spring k_contact [force/length] between
/// the two blocks' displacements at the contact point (u = T(x) D, Shi 1988);
/// a mass-like diagonal m (inertia 2M/dt^2) and a fixed bottom row (springs
/// to the ground at its contact points). Contacts of the pairs listed in
/// `open_pairs` carry no spring (their block is zero), as open contacts do.
struct Grid {
  int nx, ny;
  double k_contact = 4e3, m = 1.0;
  std::vector<Vec2> centroids;
  double w = 1.0, h = 0.5;  // block size [length]
  int id(int i, int j) const { return j * nx + i; }
};

void spring(BlockSystem& s, const Grid& g, int a, int b, const Vec2& p, const Vec2& e, double k) {
  const Eigen::Matrix<double, 2, 6> Ta = displacement_matrix(g.centroids[a], p);
  const Vec6 ga = Ta.transpose() * e;
  if (b < 0) {  // to the ground
    s.diagonal(a) += k * ga * ga.transpose();
    return;
  }
  const Eigen::Matrix<double, 2, 6> Tb = displacement_matrix(g.centroids[b], p);
  const Vec6 gb = Tb.transpose() * e;
  s.diagonal(a) += k * ga * ga.transpose();
  s.diagonal(b) += k * gb * gb.transpose();
  s.add_stiffness(a, b, -k * ga * gb.transpose());
}

void edge(BlockSystem& s, const Grid& g, int a, int b, const Vec2& p0, const Vec2& p1, double k) {
  const Vec2 t = (p1 - p0).normalized(), n(-t.y(), t.x());
  for (const Vec2& p : {Vec2(0.75 * p0 + 0.25 * p1), Vec2(0.25 * p0 + 0.75 * p1)}) {
    spring(s, g, a, b, p, n, k);
    spring(s, g, a, b, p, t, 0.4 * k);
  }
}

BlockSystem grid_system(Grid& g, double scale = 1.0, bool open_middle_column = false) {
  const double w = g.w, h = g.h;
  g.centroids.clear();
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) g.centroids.emplace_back((i + 0.5) * w, (j + 0.5) * h);
  BlockSystem s;
  s.reset(g.nx * g.ny);
  for (int b = 0; b < g.nx * g.ny; ++b) {
    const double S = w * h;
    Mat6 M = Mat6::Zero();  // unit mass matrix of a w x h rectangle about its centroid
    M(0, 0) = M(1, 1) = S;
    M(2, 2) = S * (w * w + h * h) / 12.0;
    M(3, 3) = S * w * w / 12.0;
    M(4, 4) = S * h * h / 12.0;
    M(5, 5) = S * (w * w + h * h) / 48.0;
    s.diagonal(b) += g.m * M;
    s.diagonal(b).block<3, 3>(3, 3) += 100.0 * S * Eigen::Matrix3d::Identity();  // elastic
  }
  const double k = scale * g.k_contact;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const int a = g.id(i, j);
      const double x1 = (i + 1) * w, y0 = j * h, y1 = (j + 1) * h;
      const bool open = open_middle_column && i + 1 == g.nx / 2;
      if (i + 1 < g.nx) edge(s, g, a, g.id(i + 1, j), {x1, y0}, {x1, y1}, open ? 0.0 : k);
      if (j + 1 < g.ny) edge(s, g, a, g.id(i, j + 1), {i * w, y1}, {x1, y1}, k);
      if (j == 0) edge(s, g, a, -1, {i * w, y0}, {x1, y0}, k);
    }
  for (int b = 0; b < g.nx * g.ny; ++b) {
    const Vec2 c = g.centroids[b];
    s.rhs().segment<6>(6 * b) << 0.3 * std::sin(c.x()), -1.0 + 0.1 * std::cos(2.0 * c.y()), 0.0,
        0.0, 0.0, 0.0;
  }
  // The solver reads the centroids from the system, as the engine gives them.
  std::vector<BlockView> views;
  for (const Vec2& c : g.centroids) views.push_back(BlockView{{}, c, {}});
  s.set_centroids(views);
  s.finalize();
  return s;
}

double rel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).norm() / b.norm(); }

/// Iterations of a cold solve (a fresh solver: no warm start).
long iterations(SolverKind kind, const BlockSystem& s, double tol, Eigen::VectorXd* x = nullptr) {
  LinearSolver solver(kind, tol, 100000);
  const Eigen::VectorXd d = solver.solve(s);
  if (x) *x = d;
  return solver.stats().pcg_iterations;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(amg)

BOOST_AUTO_TEST_CASE(gives_cholmods_solution_on_a_contact_grid) {
  Grid g{30, 20, 4e3, 1.0, {}, 1.0, 0.5};
  const BlockSystem s = grid_system(g);
  LinearSolver chol(SolverKind::cholmod);
  const Eigen::VectorXd ref = chol.solve(s);
  Eigen::VectorXd x;
  iterations(SolverKind::amg, s, 1e-10, &x);
  BOOST_TEST(rel(x, ref) <= 1e-8);
  // The stop holds for the true residual, not only the CG recurrence's.
  BOOST_TEST((s.multiply(x) - s.rhs()).norm() <= 1e-10 * s.rhs().norm());
}

BOOST_AUTO_TEST_CASE(iterations_do_not_grow_with_the_model_while_block_jacobi_s_do) {
  // Contacts 4000 times stiffer than the blocks' inertia, as in a DDA wall.
  Grid small{8, 8, 4e3, 1.0, {}, 1.0, 0.5}, large{64, 64, 4e3, 1.0, {}, 1.0, 0.5};
  const BlockSystem s1 = grid_system(small), s2 = grid_system(large);
  const long amg1 = iterations(SolverKind::amg, s1, 1e-8);
  const long amg2 = iterations(SolverKind::amg, s2, 1e-8);
  const long bj1 = iterations(SolverKind::pcg, s1, 1e-8);
  const long bj2 = iterations(SolverKind::pcg, s2, 1e-8);
  BOOST_TEST_MESSAGE("cold solves to 1e-8: amg " << amg1 << " -> " << amg2
                                                 << " iterations, block-Jacobi " << bj1 << " -> "
                                                 << bj2 << " (64 -> 4096 blocks)");
  BOOST_TEST(amg2 <= 2 * amg1);  // 64 times the blocks
  BOOST_TEST(bj2 >= 3 * bj1);
  BOOST_TEST(amg2 * 5 <= bj2);
}

BOOST_AUTO_TEST_CASE(coarsens_geometrically_and_solves_the_coarsest_level_directly) {
  Grid g{64, 64, 4e3, 1.0, {}, 1.0, 0.5};
  const BlockSystem s = grid_system(g);
  BlockAmg amg;
  amg.setup(s);
  BOOST_TEST(amg.levels() >= 3);
  for (int l = 1; l < amg.levels(); ++l) BOOST_TEST(amg.blocks(l) * 3 <= amg.blocks(l - 1));
  BOOST_TEST(amg.blocks(amg.levels() - 1) <= 4 * BlockAmg::kCoarsest);
  // One V-cycle from zero is a convergent iteration: it reduces the error in
  // the energy norm |e|_A = sqrt(e' A e) (CG needs only symmetry and
  // definiteness, but a multigrid cycle that converges alone is the point).
  LinearSolver chol(SolverKind::cholmod);
  const Eigen::VectorXd x = chol.solve(s);
  Eigen::VectorXd z;
  amg.apply(s.rhs(), z);
  const Eigen::VectorXd e = x - z;
  BOOST_TEST(e.dot(s.multiply(e)) <= 0.5 * x.dot(s.multiply(x)));
}

BOOST_AUTO_TEST_CASE(reuses_the_hierarchy_while_the_pattern_holds_and_restarts_warm) {
  Grid g{20, 20, 4e3, 1.0, {}, 1.0, 0.5};
  LinearSolver amg(SolverKind::amg, 1e-10, 100000);
  const BlockSystem s1 = grid_system(g, 1.0);
  const Eigen::VectorXd x1 = amg.solve(s1);
  const long cold = amg.stats().pcg_iterations;
  // The same system again: the last solution is the answer, no iteration.
  amg.solve(s1);
  BOOST_TEST(amg.stats().pcg_iterations == cold);
  BOOST_TEST(cold > 10);
  // New values, same pattern (the next iterate of an open-close iteration):
  // no new hierarchy, and the answer is CHOLMOD's.
  const BlockSystem s2 = grid_system(g, 1.3);
  const Eigen::VectorXd x2 = amg.solve(s2);
  BOOST_TEST(amg.stats().analyses == 1);
  LinearSolver chol(SolverKind::cholmod);
  BOOST_TEST(rel(x2, chol.solve(s2)) <= 1e-8);
  BOOST_TEST(rel(x1, x2) > 1e-3);  // a different system indeed
}

BOOST_AUTO_TEST_CASE(a_refresh_follows_blocks_that_moved_as_a_new_setup_would) {
  // Same pattern, blocks 1.5 times larger (they moved apart): refreshing the
  // old hierarchy gives the V-cycle a fresh setup gives (two levels, so the
  // aggregates are those of the finest level, which the test checks).
  Grid g1{10, 10, 4e3, 1.0, {}, 1.0, 0.5}, g2{10, 10, 4e3, 1.0, {}, 1.5, 0.75};
  const BlockSystem s1 = grid_system(g1), s2 = grid_system(g2);
  BlockAmg refreshed, fresh;
  refreshed.setup(s1);
  BOOST_TEST_REQUIRE(refreshed.same_pattern(s2));
  refreshed.refresh(s2);
  fresh.setup(s2);
  BOOST_TEST_REQUIRE(fresh.levels() == 2);
  BOOST_TEST_REQUIRE((refreshed.aggregates(0) == fresh.aggregates(0)));
  Eigen::VectorXd z1, z2;
  refreshed.apply(s2.rhs(), z1);
  fresh.apply(s2.rhs(), z2);
  BOOST_TEST(rel(z1, z2) <= 1e-10);
}

BOOST_AUTO_TEST_CASE(open_contacts_do_not_join_aggregates_and_the_answer_holds) {
  // The middle column of joints is open: its blocks are zero. The two halves
  // are coupled only through the row of ground springs and the blocks above.
  Grid g{16, 16, 4e3, 1.0, {}, 1.0, 0.5};
  const BlockSystem s = grid_system(g, 1.0, true);
  BlockAmg amg;
  amg.setup(s);
  const std::vector<int>& agg = amg.aggregates(0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx / 2; ++i)
      for (int i2 = g.nx / 2; i2 < g.nx; ++i2) BOOST_TEST(agg[g.id(i, j)] != agg[g.id(i2, j)]);
  LinearSolver chol(SolverKind::cholmod);
  Eigen::VectorXd x;
  iterations(SolverKind::amg, s, 1e-10, &x);
  BOOST_TEST(rel(x, chol.solve(s)) <= 1e-8);
}

BOOST_AUTO_TEST_CASE(automatic_picks_cholmod_for_small_models_and_amg_for_large_ones) {
  BOOST_TEST((LinearSolver::resolve(SolverKind::automatic, 100) == SolverKind::cholmod));
  BOOST_TEST((LinearSolver::resolve(SolverKind::automatic, LinearSolver::kAmgBlocks) == SolverKind::amg));
  BOOST_TEST((LinearSolver::resolve(SolverKind::pcg, 100000) == SolverKind::pcg));
  Grid g{50, 40, 4e3, 1.0, {}, 1.0, 0.5};  // 2 000 blocks: amg, iterations counted
  const BlockSystem s = grid_system(g);
  LinearSolver automatic(SolverKind::automatic, 1e-10, 100000);
  LinearSolver chol(SolverKind::cholmod);
  BOOST_TEST(rel(automatic.solve(s), chol.solve(s)) <= 1e-8);
  BOOST_TEST(automatic.stats().pcg_iterations > 0);
}

BOOST_AUTO_TEST_SUITE_END()
