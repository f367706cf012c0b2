// PCG against a direct sparse solve on systems the engine assembled.
#include <gtest/gtest.h>

#include "scenes.hpp"
#include "solver/linear_solver.hpp"

using namespace dda;

namespace {

// A wall of 6 × 8 blocks in running bond on a fixed base, one step under
// gravity: a system with many contacts and all three contact states possible.
World brick_wall() {
  World w;
  const int rock = w.add_rock_material(test::granite());
  test::add_fixed_base(w, test::rectangle(-1, -1, 8, 1), rock);
  for (int row = 0; row < 8; ++row) {
    const double offset = (row % 2) ? 0.5 : 0.0;
    for (int col = 0; col < 6; ++col) w.add_block(test::rectangle(offset + col, row * 0.5, 1, 0.5), rock);
  }
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g1 = 1e-3;
  return w;
}

void expect_pcg_matches_direct(const World& w, double g1_scale) {
  const BlockSparseMatrix& a = w.last_matrix();
  const VecX& b = w.last_rhs();
  DirectSolver direct;
  direct.set_operator(a);
  VecX x_direct;
  ASSERT_TRUE(direct.solve(b, x_direct).converged);

  PcgSolver pcg;
  pcg.tolerance = 1e-13;
  pcg.max_iterations = 20000;
  pcg.set_operator(a);
  VecX x = VecX::Zero(b.size());
  const SolveReport r = pcg.solve(b, x);
  ASSERT_TRUE(r.converged) << "residual " << r.relative_residual;
  EXPECT_LE((x - x_direct).norm() / x_direct.norm(), 1e-8) << "scale " << g1_scale;
}

}  // namespace

TEST(Solver, PcgMatchesDirectSolveOnAssembledWall) {
  World w = brick_wall();
  w.step();
  ASSERT_GT(w.contacts().size(), 100u);
  expect_pcg_matches_direct(w, 1);
  for (int i = 0; i < 5; ++i) w.step();
  expect_pcg_matches_direct(w, 1);
}

TEST(Solver, PcgMatchesDirectSolveWithLargeTimeStep) {
  // A large Δt weakens the inertia term: a harder, contact-dominated system.
  World w = brick_wall();
  w.controls().g1 = 0.05;
  w.controls().g2 = 0.05;
  w.step();
  expect_pcg_matches_direct(w, 50);
}

TEST(Solver, WarmStartFromTheSolutionNeedsNoIterations) {
  World w = brick_wall();
  w.step();
  const BlockSparseMatrix& a = w.last_matrix();
  const VecX& b = w.last_rhs();
  PcgSolver pcg;
  pcg.tolerance = 1e-10;
  pcg.set_operator(a);
  VecX x = VecX::Zero(b.size());
  const int cold = pcg.solve(b, x).iterations;
  const int warm = pcg.solve(b, x).iterations;
  EXPECT_GT(cold, 3);
  EXPECT_EQ(warm, 0);
}

TEST(Solver, ReportsNonFiniteInput) {
  World w = brick_wall();
  w.step();
  VecX b = w.last_rhs();
  b[3] = NAN;
  PcgSolver pcg;
  pcg.set_operator(w.last_matrix());
  VecX x = VecX::Zero(b.size());
  const SolveReport r = pcg.solve(b, x);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.finite);
}
