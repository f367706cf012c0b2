// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
// PCG against a direct sparse solve on systems the engine assembled.
#include <gtest/gtest.h>

#include "../scenes.hpp"
#include "assembly/contact_operator.hpp"
#include "solver/direct_solver.hpp"
#include "solver/pcg.hpp"

using namespace dda;

namespace {

// The benchmarks' wall(6) (79 blocks in running bond on a fixed base) after
// its steps under gravity: a system with many contacts.
World brick_wall() { return test::brick_wall(6); }

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

// A re-solve after a change confined to one block row (its diagonal block and
// its load) keeps the last residual on the other rows and still reaches the
// direct solution of the changed system (reference: Eigen's LDLᵀ, 1e-8).
// With hops > 0 it first solves on a patch (PcgSolver::patch_hops): the
// changed row and the rows within `hops` couplings of it, the rest held. On
// the wall (contact springs against a little inertia) the global PCG has to
// finish the job; on a wave problem's system (`patch_alone`: a kicked bar of
// 1 m blocks at Δt = 2e-6 s, inertia dominant) the patch alone meets the
// tolerance, with no iteration over all rows.
void expect_resolve_matches_direct(const World& w, int hops, bool patch_alone) {
  BlockSparseMatrix a = w.last_matrix();
  VecX b = w.last_rhs();
  PcgSolver pcg;
  pcg.tolerance = 1e-13;
  pcg.max_iterations = 20000;
  pcg.patch_hops = hops;
  pcg.set_operator(a);
  VecX x = VecX::Zero(b.size());
  ASSERT_TRUE(pcg.solve(b, x).converged);

  const int row = a.rows() / 2;
  a.value(a.diagonal(row)) += 0.5 * a.value(a.diagonal(row)).diagonal().asDiagonal().toDenseMatrix();
  b.segment<6>(6 * row) += Vec6::Constant(1e-3 * b.norm());
  std::vector<char> changed(a.rows(), 0);
  changed[row] = 1;
  pcg.set_operator(a);
  const SolveReport r = pcg.resolve(b, x, changed);
  ASSERT_TRUE(r.converged);
  if (hops == 0) {
    EXPECT_GT(r.iterations, 0);
    EXPECT_EQ(r.patch_rows, 0);
  } else {
    EXPECT_GT(r.patch_iterations, 0);
    EXPECT_GT(r.patch_rows, 1 + hops);
    EXPECT_LT(r.patch_rows, a.rows());
    if (patch_alone) {
      EXPECT_EQ(r.iterations, 0) << "the patch alone should have met the tolerance";
    } else {
      EXPECT_GT(r.iterations, 0);
    }
  }

  DirectSolver direct;
  direct.set_operator(a);
  VecX x_direct;
  ASSERT_TRUE(direct.solve(b, x_direct).converged);
  EXPECT_LE((x - x_direct).norm() / x_direct.norm(), 1e-8);
}

TEST(Solver, ResolveAfterARowChangeMatchesTheDirectSolve) {
  World w = brick_wall();
  w.step();
  expect_resolve_matches_direct(w, 0, false);
}

TEST(Solver, PatchResolveMatchesTheDirectSolve) {
  World wall = brick_wall();
  wall.step();
  expect_resolve_matches_direct(wall, 2, false);

  World bar = test::kicked_bar(60, 3, 1.0);
  bar.step();
  expect_resolve_matches_direct(bar, 8, true);
}

TEST(Solver, PatchOverItsShareOfTheRowsIsNotUsed) {
  World w = brick_wall();
  w.step();
  const BlockSparseMatrix& a = w.last_matrix();
  VecX b = w.last_rhs();
  PcgSolver pcg;
  pcg.patch_hops = 50;  // the whole wall
  pcg.set_operator(a);
  VecX x = VecX::Zero(b.size());
  ASSERT_TRUE(pcg.solve(b, x).converged);
  std::vector<char> changed(a.rows(), 0);
  changed[a.rows() / 2] = 1;
  b.segment<6>(6 * (a.rows() / 2)) += Vec6::Constant(1e-3 * b.norm());
  const SolveReport r = pcg.resolve(b, x, changed);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.patch_rows, 0);
  EXPECT_EQ(r.patch_iterations, 0);
  EXPECT_GT(r.iterations, 0);
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

// The matrix-free product (assembly/contact_operator.hpp) against the same
// system stored as 6×6 blocks: open, sliding and locked contacts, two
// contacts on one block pair, random linearisations. Reference: the stored
// product; tolerance 1e-13 of its norm (only the order of the sums differs).
TEST(Solver, MatrixFreeProductEqualsTheStoredMatrix) {
  struct Link {
    int v, e;
    ContactState state;
  };
  const std::vector<Link> links = {{0, 1, ContactState::Locked},  {1, 0, ContactState::Locked},
                                   {1, 2, ContactState::Sliding}, {2, 0, ContactState::Open},
                                   {3, 1, ContactState::Locked},  {2, 3, ContactState::Sliding}};
  std::vector<Contact> contacts;
  std::vector<ContactGradients> kinematics;
  std::uint64_t seed = 12345;
  auto next = [&] {  // deterministic numbers in [-1, 1)
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / static_cast<double>(1ull << 52) - 1.0;
  };
  auto random6 = [&] {
    Vec6 v;
    for (int k = 0; k < 6; ++k) v[k] = next();
    return v;
  };
  for (const Link& l : links) {
    Contact c;
    c.vblock = l.v;
    c.eblock = l.e;
    c.state = l.state;
    contacts.push_back(c);
    ContactGradients k;
    k.en_v = random6();
    k.en_e = random6();
    k.es_v = random6();
    k.es_e = random6();
    kinematics.push_back(k);
  }
  ContactOperator op;
  op.set_contacts(4, contacts);
  for (int b = 0; b < 4; ++b) {
    const Vec6 d = random6();
    op.rewrite_diagonal(b) = Symmetric6(Mat6(Mat6::Identity() * 10 + d * d.transpose()));
  }
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    op.springs(static_cast<int>(i)).kn = contacts[i].state == ContactState::Open ? 0.0 : 3.0 + i;
    op.springs(static_cast<int>(i)).ks = contacts[i].state == ContactState::Locked ? 1.5 + i : 0.0;
  }
  op.set_kinematics(kinematics);
  op.assembled();

  const BlockSparseMatrix& stored = op.stored();
  EXPECT_EQ(stored.nonzero_blocks(), 4 + 2 * 5);  // four diagonal blocks, five coupled pairs (open 2-0 included)
  const Eigen::MatrixXd dense = Eigen::MatrixXd(stored.to_sparse());
  EXPECT_LE((dense - dense.transpose()).norm(), 1e-14 * dense.norm());
  // The 0-1 coupling holds both contacts: kn·en_v en_eᵀ + ks·es_v es_eᵀ of the
  // first, with the roles swapped for the second.
  const auto& k0 = kinematics[0];
  const auto& k1 = kinematics[1];
  const Mat6 expected01 = 3.0 * k0.en_v * k0.en_e.transpose() + 1.5 * k0.es_v * k0.es_e.transpose() +
                          4.0 * k1.en_e * k1.en_v.transpose() + 2.5 * k1.es_e * k1.es_v.transpose();
  EXPECT_LE((dense.block<6, 6>(0, 6) - expected01).norm(), 1e-14 * expected01.norm());

  VecX x(24);
  for (int k = 0; k < 24; ++k) x[k] = next();
  VecX y_free = VecX::Zero(24), y_stored;
  op.multiply_rows(0, 4, x, y_free);
  stored.multiply(x, y_stored);
  EXPECT_LE((y_free - y_stored).norm(), 1e-13 * y_stored.norm());
  EXPECT_LE((y_free - dense * x).norm(), 1e-13 * y_stored.norm());

  // Products from the matrix stored once per pair (upper blocks, and the
  // lower ones read transposed).
  op.store_products(true);
  op.assembled();
  VecX y_via_stored = VecX::Zero(24);
  op.multiply_rows(0, 4, x, y_via_stored);
  EXPECT_LE((y_via_stored - y_stored).norm(), 1e-13 * y_stored.norm());
}

// The upper-triangle storage of per-block symmetric 6×6 arrays: the full
// matrix comes back exactly, and the product equals the full one up to the
// order of the sums (reference: Eigen's Mat6 product, tolerance 1e-15 of |y|).
TEST(Solver, Symmetric6KeepsTheMatrixAndItsProduct) {
  Mat6 a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) a(i, j) = 1.0 / (1 + i + j) + (i == j ? 3.0 : 0.0);  // a Hilbert-like SPD matrix
  const Symmetric6 s(a);
  EXPECT_EQ(s.full(), a);
  Vec6 x;
  x << 1, -2, 3, -4, 5, -6;
  EXPECT_LE((s * x - a * x).norm(), 1e-15 * (a * x).norm());
}

// The contact operator multiplies with its diagonal blocks kept as
// Symmetric6; results stay those of the full Mat6 product only if every row
// is summed in the same order. Reference: Eigen's Mat6·Vec6 of the same
// matrix, compared bit for bit on random symmetric matrices and vectors,
// with exact zeros and negative zeros mixed in (in a DDA_NATIVE_ARCH build,
// to round-off).
TEST(Solver, Symmetric6ProductHasTheBitsOfTheFullProduct) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::uniform_int_distribution<int> pick(0, 9);
  auto draw = [&] {
    const int kind = pick(rng);
    return kind == 0 ? 0.0 : kind == 1 ? -0.0 : uniform(rng) * std::pow(10.0, pick(rng) - 5);
  };
  int differing = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    Mat6 a;
    for (int i = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j) a(i, j) = a(j, i) = draw();
    Vec6 x;
    for (int i = 0; i < 6; ++i) x[i] = draw();
    const Vec6 full = a * x, upper = Symmetric6(a) * x;
#ifdef DDA_NATIVE_ARCH
    // With -march=native Eigen's product uses FMA and wider packets: the two
    // then agree to round-off. Each six-term sum is within γ6·Σ|a·x| of the
    // exact one (γ6 ≈ 6·ε/2), so the two within 7·ε·Σ|a·x| of each other.
    const Vec6 bound = 7 * std::numeric_limits<double>::epsilon() * (a.cwiseAbs() * x.cwiseAbs());
    for (int i = 0; i < 6; ++i) differing += std::abs(full[i] - upper[i]) > bound[i];
#else
    for (int i = 0; i < 6; ++i) differing += std::memcmp(&full[i], &upper[i], sizeof(double)) != 0;
#endif
  }
  EXPECT_EQ(differing, 0);
}

// Block-Jacobi redoes only the rows an assembly rewrote (the operator's
// revision numbers) and changed by more than its refresh tolerance: after a
// second assembly that rewrites one diagonal block, the preconditioner applies
// the new inverse there and keeps the old ones elsewhere.
TEST(Solver, BlockJacobiFollowsRewrittenDiagonalBlocks) {
  std::vector<Contact> contacts(1);
  contacts[0].vblock = 0;
  contacts[0].eblock = 1;
  ContactOperator op;
  op.set_contacts(3, contacts);
  for (int b = 0; b < 3; ++b) op.rewrite_diagonal(b) = Symmetric6(Mat6(Mat6::Identity() * (b + 1)));
  std::vector<ContactGradients> kinematics(1);
  op.set_kinematics(kinematics);
  op.assembled();
  BlockJacobi jacobi;
  jacobi.setup(op);
  const VecX ones = VecX::Ones(18);
  VecX z;
  jacobi.apply(ones, z);
  EXPECT_DOUBLE_EQ(z[6], 0.5);
  EXPECT_DOUBLE_EQ(z[12], 1.0 / 3.0);

  op.rewrite_diagonal(1) = Symmetric6(Mat6(Mat6::Identity() * 8));  // row 1 changes, rows 0 and 2 are kept
  op.assembled();
  EXPECT_NE(op.diagonal_revision(1), op.diagonal_revision(0));
  jacobi.setup(op);
  jacobi.apply(ones, z);
  EXPECT_DOUBLE_EQ(z[0], 1.0);
  EXPECT_DOUBLE_EQ(z[6], 0.125);
  EXPECT_DOUBLE_EQ(z[12], 1.0 / 3.0);

  // A block that drifts by less than refresh_tolerance keeps its inverse; one
  // that drifts by more gets a new one.
  op.rewrite_diagonal(0) = Symmetric6(Mat6(Mat6::Identity() * (1 + 0.5 * jacobi.refresh_tolerance)));
  op.rewrite_diagonal(2) = Symmetric6(Mat6(Mat6::Identity() * 3 * (1 + 2 * jacobi.refresh_tolerance)));
  op.assembled();
  jacobi.setup(op);
  jacobi.apply(ones, z);
  EXPECT_DOUBLE_EQ(z[0], 1.0);
  EXPECT_DOUBLE_EQ(z[12], 1.0 / (3 * (1 + 2 * jacobi.refresh_tolerance)));

  // A stored matrix does not track revisions: every row is compared again.
  BlockSparseMatrix stored;
  stored.set_structure(3, {});
  for (int b = 0; b < 3; ++b) stored.value(stored.diagonal(b)) = Mat6::Identity() * 4;
  jacobi.setup(stored);
  jacobi.apply(ones, z);
  for (int k = 0; k < 18; ++k) EXPECT_DOUBLE_EQ(z[k], 0.25);
}
