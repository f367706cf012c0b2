// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The aggregation multigrid preconditioner (solver/multigrid.hpp) on systems
// the engine assembled for the benchmark brick walls: it must give the direct
// solution, need far fewer CG iterations than block-Jacobi, be a symmetric
// positive definite operator (or CG is not valid), reuse its hierarchy while
// the sparsity pattern holds, and give the same bits for any thread count.
// Also the Auto rule of solver/preconditioner_choice.hpp.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstdio>
#include <cstring>

#include "../scenes.hpp"
#include "solver/direct_solver.hpp"
#include "solver/multigrid.hpp"
#include "solver/pcg.hpp"
#include "solver/preconditioner_choice.hpp"

using namespace dda;

namespace {

// test::brick_wall, solved on one thread with block-Jacobi unless a test says otherwise.
World brick_wall(int n) {
  World w = test::brick_wall(n);
  w.controls().threads = 1;
  w.controls().solver.pcg.preconditioner = Preconditioning::BlockJacobi;
  return w;
}

std::vector<Vec2> centroids(const World& w) {
  std::vector<Vec2> c;
  for (std::size_t b = 0; b < w.block_count(); ++b) c.push_back(w.block_centroid(static_cast<BlockId>(b)));
  return c;
}

// A wall stepped a few times; its last system A·D = F is what the tests solve.
struct WallSystem {
  World world;
  std::vector<Vec2> centres;
  explicit WallSystem(int n, int steps = 3) : world(brick_wall(n)) {
    for (int s = 0; s < steps; ++s) world.step();
    centres = centroids(world);
  }
  const BlockSparseMatrix& a() const { return world.last_matrix(); }
  const VecX& b() const { return world.last_rhs(); }
};

std::unique_ptr<Multigrid> multigrid_for(const WallSystem& s, const MultigridOptions& o = {}) {
  auto mg = std::make_unique<Multigrid>(o);
  mg->set_block_centroids(s.centres);
  return mg;
}

SolveReport cold_solve(PcgSolver& pcg, const BlockSparseMatrix& a, const VecX& b, VecX& x, double tol = 1e-10) {
  pcg.tolerance = tol;
  pcg.max_iterations = 100000;
  pcg.set_operator(a);
  x = VecX::Zero(b.size());
  return pcg.solve(b, x);
}

VecX direct_solution(const BlockSparseMatrix& a, const VecX& b) {
  DirectSolver direct;
  direct.set_operator(a);
  VecX x;
  EXPECT_TRUE(direct.solve(b, x).converged);
  return x;
}

}  // namespace

TEST(Multigrid, PcgMatchesDirectSolveOnWall10) {
  const WallSystem s(10);
  ASSERT_EQ(s.a().rows(), 211);
  const VecX x_direct = direct_solution(s.a(), s.b());
  PcgSolver pcg(multigrid_for(s));
  VecX x;
  const SolveReport r = cold_solve(pcg, s.a(), s.b(), x, 1e-13);
  ASSERT_TRUE(r.converged) << "residual " << r.relative_residual;
  EXPECT_LE((x - x_direct).norm() / x_direct.norm(), 1e-8);
  auto& mg = static_cast<Multigrid&>(pcg.preconditioner());
  EXPECT_GE(mg.levels(), 2);  // it did coarsen
  EXPECT_LT(mg.level_blocks(1), mg.level_blocks(0) / 3);
}

TEST(Multigrid, PcgMatchesDirectSolveWithoutCentroidsAndWithPlainAggregation) {
  // No geometry: piecewise-constant transfer. Tentative prolongator only:
  // unsmoothed aggregation. Both are still valid preconditioners.
  const WallSystem s(10);
  const VecX x_direct = direct_solution(s.a(), s.b());
  {
    PcgSolver pcg(std::make_unique<Multigrid>());
    VecX x;
    ASSERT_TRUE(cold_solve(pcg, s.a(), s.b(), x, 1e-13).converged);
    EXPECT_LE((x - x_direct).norm() / x_direct.norm(), 1e-8);
  }
  {
    MultigridOptions o;
    o.smooth_prolongator = false;
    PcgSolver pcg(multigrid_for(s, o));
    VecX x;
    ASSERT_TRUE(cold_solve(pcg, s.a(), s.b(), x, 1e-13).converged);
    EXPECT_LE((x - x_direct).norm() / x_direct.norm(), 1e-8);
  }
}

TEST(Multigrid, PcgMatchesDirectSolveOnWallWithLargeTimeStep) {
  // Δt = 0.05 s: the inertia term all but vanishes, contacts and elasticity
  // dominate, block-Jacobi struggles most.
  World w = brick_wall(6);
  w.controls().g1 = 0.05;
  w.controls().g2 = 0.05;
  w.step();
  const VecX x_direct = direct_solution(w.last_matrix(), w.last_rhs());
  auto mg = std::make_unique<Multigrid>();
  mg->set_block_centroids(centroids(w));
  PcgSolver pcg(std::move(mg));
  VecX x;
  const SolveReport r = cold_solve(pcg, w.last_matrix(), w.last_rhs(), x, 1e-13);
  ASSERT_TRUE(r.converged) << "residual " << r.relative_residual;
  EXPECT_LE((x - x_direct).norm() / x_direct.norm(), 1e-8);

  PcgSolver bj;
  VecX xb;
  const int bj_iterations = cold_solve(bj, w.last_matrix(), w.last_rhs(), xb).iterations;
  const int mg_iterations = cold_solve(pcg, w.last_matrix(), w.last_rhs(), x).iterations;
  std::printf("[ wall(6), dt 0.05 ] CG iterations to 1e-10: block-Jacobi %d, multigrid %d\n", bj_iterations,
              mg_iterations);
  EXPECT_LE(mg_iterations * 5, bj_iterations * 2);  // measured 90 vs 268
}

TEST(Multigrid, FarFewerIterationsThanBlockJacobiOnWall10And20) {
  // Measured (cold start, tolerance 1e-10, the system of the 3rd step):
  // wall(10) about 370 → 88, wall(20) 452 → 118. The ratio is asserted at 0.3.
  for (int n : {10, 20}) {
    const WallSystem s(n);
    PcgSolver bj;
    VecX x;
    const SolveReport rb = cold_solve(bj, s.a(), s.b(), x);
    PcgSolver mgp(multigrid_for(s));
    const SolveReport rm = cold_solve(mgp, s.a(), s.b(), x);
    ASSERT_TRUE(rb.converged);
    ASSERT_TRUE(rm.converged);
    const auto& mg = static_cast<const Multigrid&>(mgp.preconditioner());
    std::printf("[ wall(%d), %d blocks ] CG iterations to 1e-10: block-Jacobi %d, multigrid %d (%.2f); levels", n,
                s.a().rows(), rb.iterations, rm.iterations, double(rm.iterations) / rb.iterations);
    for (int l = 0; l < mg.levels(); ++l) std::printf(" %d", mg.level_blocks(l));
    std::printf("\n");
    EXPECT_LE(rm.iterations, 0.3 * rb.iterations) << "wall(" << n << ")";
  }
}

TEST(Multigrid, IsASymmetricPositiveDefiniteOperator) {
  const WallSystem s(10);
  auto mg = multigrid_for(s);
  mg->setup(s.a());
  const int n = 6 * s.a().rows();
  VecX u(n), v(n), mu, mv;
  for (int i = 0; i < n; ++i) {
    u[i] = std::sin(0.37 * i + 1.0);
    v[i] = std::cos(0.11 * i * i + 0.5);
  }
  mg->apply(u, mu);
  mg->apply(v, mv);
  EXPECT_NEAR(u.dot(mv), v.dot(mu), 1e-10 * std::abs(u.dot(mv)) + 1e-300);
  EXPECT_GT(u.dot(mu), 0);
  EXPECT_GT(v.dot(mv), 0);
}

TEST(Multigrid, ReusesItsHierarchyWhileThePatternHolds) {
  World w = brick_wall(10);
  w.step();
  BlockSparseMatrix a = w.last_matrix();  // a copy we may change
  Multigrid mg;
  mg.set_block_centroids(centroids(w));
  mg.setup(a);
  EXPECT_EQ(mg.aggregations(), 1);
  for (int k = 0; k < a.nonzero_blocks(); ++k) a.value(k) *= 1.5;  // new values, same pattern
  mg.setup(a);
  EXPECT_EQ(mg.aggregations(), 1);
  // The re-setup used the new values: CG converges as fast as with a fresh hierarchy.
  PcgSolver reused(std::make_unique<Multigrid>(mg));
  PcgSolver fresh(std::make_unique<Multigrid>());
  static_cast<Multigrid&>(fresh.preconditioner()).set_block_centroids(centroids(w));
  VecX x1, x2;
  const VecX b = w.last_rhs();
  const int it_reused = cold_solve(reused, a, b, x1).iterations;
  const int it_fresh = cold_solve(fresh, a, b, x2).iterations;
  EXPECT_LE(std::abs(it_reused - it_fresh), 2);
  // A different pattern aggregates again.
  World w2 = brick_wall(11);
  w2.step();
  mg.set_block_centroids(centroids(w2));
  mg.setup(w2.last_matrix());
  EXPECT_EQ(mg.aggregations(), 2);
}

TEST(Multigrid, SmallSystemIsSolvedDirectly) {
  // At most coarsest_blocks blocks: one level, a dense Cholesky; CG needs one iteration.
  World w = brick_wall(2);  // 1 + 2·2 + 2·3 = 11 blocks
  w.step();
  auto mg = std::make_unique<Multigrid>();
  mg->set_block_centroids(centroids(w));
  PcgSolver pcg(std::move(mg));
  VecX x;
  const SolveReport r = cold_solve(pcg, w.last_matrix(), w.last_rhs(), x);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 2);
  EXPECT_EQ(static_cast<Multigrid&>(pcg.preconditioner()).levels(), 1);
}

TEST(Multigrid, SameSolutionBitsForOneTwoAndFourThreads) {
  const WallSystem s(20, 1);
  std::vector<VecX> solutions;
  std::vector<int> iterations;
  for (int threads : {1, 2, 4, 1}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      PcgSolver pcg(multigrid_for(s));
      VecX x;
      iterations.push_back(cold_solve(pcg, s.a(), s.b(), x).iterations);
      solutions.push_back(x);
    });
  }
  for (std::size_t k = 1; k < solutions.size(); ++k) {
    EXPECT_EQ(iterations[k], iterations[0]);
    ASSERT_EQ(solutions[k].size(), solutions[0].size());
    EXPECT_EQ(std::memcmp(solutions[k].data(), solutions[0].data(), sizeof(double) * solutions[0].size()), 0)
        << "run " << k;
  }
}

TEST(Multigrid, WorldStateHashIsTheSameForOneTwoAndFourThreads) {
  auto run = [](int threads) {
    World w = brick_wall(8);
    w.controls().threads = threads;
    w.controls().solver.pcg.preconditioner = Preconditioning::Multigrid;
    for (int s = 0; s < 4; ++s) w.step();
    return w.state_hash();
  };
  const std::uint64_t h1 = run(1);
  EXPECT_EQ(run(2), h1);
  EXPECT_EQ(run(4), h1);
}

TEST(PreconditionerChoice, AutoRule) {
  using P = Preconditioning;
  // Explicit choices are kept.
  EXPECT_EQ(choose_preconditioning(P::Multigrid, SystemTraits(10)), P::Multigrid);
  EXPECT_EQ(choose_preconditioning(P::BlockJacobi, SystemTraits(100000)), P::BlockJacobi);
  // Small models: block-Jacobi whatever happened.
  SystemTraits small(kMultigridMinBlocks - 1);
  small.last_kind = P::BlockJacobi;
  small.last_cg_per_solve = 1e4;
  EXPECT_EQ(choose_preconditioning(P::Auto, small), P::BlockJacobi);
  // First step: block-Jacobi.
  EXPECT_EQ(choose_preconditioning(P::Auto, SystemTraits(1000)), P::BlockJacobi);
  // Adaptive, with hysteresis.
  SystemTraits t(1000);
  t.last_kind = P::BlockJacobi;
  t.last_cg_per_solve = kToMultigrid;
  EXPECT_EQ(choose_preconditioning(P::Auto, t), P::BlockJacobi);
  t.last_cg_per_solve = kToMultigrid + 1;
  EXPECT_EQ(choose_preconditioning(P::Auto, t), P::Multigrid);
  t.last_kind = P::Multigrid;
  t.last_cg_per_solve = kToBlockJacobi;
  EXPECT_EQ(choose_preconditioning(P::Auto, t), P::Multigrid);
  t.last_cg_per_solve = kToBlockJacobi - 1;
  EXPECT_EQ(choose_preconditioning(P::Auto, t), P::BlockJacobi);
  // The two thresholds leave room for the factor multigrid gains.
  EXPECT_GE(kToMultigrid / kToBlockJacobi, 6);
}
