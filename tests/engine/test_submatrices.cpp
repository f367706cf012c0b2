// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Sub-matrices: symmetry, the inertia integral against a direct quadrature
// and its compact products against the full matrix's, and zero elastic
// energy under rigid-body motion.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstring>
#include <limits>
#include <random>

#include "../scenes.hpp"
#include "block/displacement.hpp"
#include "core/material.hpp"
#include "geometry/polygon.hpp"

using namespace dda;

TEST(SubMatrices, IntegratedTTMatchesQuadrature) {
  // Integrate TᵀT over a triangle by splitting it into many small cells
  // (midpoint rule on a fine grid, exact up to discretisation).
  const std::vector<Vec2> tri = {{0, 0}, {2, 0}, {0.5, 1.5}};
  const auto pm = polygon_moments(tri);
  const Mat6 closed = integrated_tt(pm.area, pm.sxx, pm.syy, pm.sxy).full();
  Mat6 quad = Mat6::Zero();
  const int n = 600;
  const double h = 2.0 / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec2 p((i + 0.5) * h, (j + 0.5) * h);
      if (!point_in_polygon(tri, p)) continue;
      const Mat26 t = displacement_matrix(p, pm.centroid);
      quad += t.transpose() * t * h * h;
    }
  EXPECT_TRUE(closed.isApprox(closed.transpose(), 0));
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) EXPECT_NEAR(closed(r, c), quad(r, c), 5e-3 * closed.diagonal().maxCoeff());
}

// The inertia terms are made with the ten distinct entries of ∫TᵀT; they
// must give what the full 6×6 matrix's Eigen expressions gave (the engine's
// results before, bit for bit): c·(M·x), which Eigen evaluates as (c·M)·x,
// and K += c·M. Zeros may differ in sign only (the full product adds the
// zero entries' ±0 terms), which no later sum can see.
TEST(SubMatrices, IntegratedTtProductsHaveTheBitsOfTheFullMatrix) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::uniform_int_distribution<int> pick(0, 9);
  int differing = 0;
  auto compare = [&](double full, double compact, double bound) {
#ifdef DDA_NATIVE_ARCH
    // Eigen's FMA and wider packets round otherwise: within 7·ε·Σ|terms|.
    differing += !(std::abs(full - compact) <= bound);
#else
    (void)bound;
    differing += full == 0 ? compact != 0 : std::memcmp(&full, &compact, sizeof(double)) != 0;
#endif
  };
  const double eps7 = 7 * std::numeric_limits<double>::epsilon();
  for (int trial = 0; trial < 100000; ++trial) {
    const double area = std::pow(10.0, 3 * uniform(rng));
    const double sxx = area * area * (0.01 + std::abs(uniform(rng))),
                 syy = area * area * (0.01 + std::abs(uniform(rng)));
    const double sxy = pick(rng) < 2 ? 0.0 : 0.1 * uniform(rng) * std::sqrt(sxx * syy);
    const IntegratedTt tt = integrated_tt(area, sxx, syy, sxy);
    const Mat6 full = tt.full();
    Vec6 x;
    for (int i = 0; i < 6; ++i) x[i] = pick(rng) == 0 ? 0.0 : uniform(rng) * std::pow(10.0, pick(rng) - 5);
    const double c = std::pow(10.0, 8 * uniform(rng));
    const Vec6 eigen = c * (full * x), compact = tt.scaled(c) * x;
    const Vec6 bound = eps7 * ((c * full).cwiseAbs() * x.cwiseAbs());
    for (int i = 0; i < 6; ++i) compare(eigen[i], compact[i], bound[i]);
    Mat6 k = Mat6::Identity() * uniform(rng);
    Symmetric6 ks(k);
    k += c * full;
    tt.add_scaled_to(c, ks);
    for (int i = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j) compare(k(i, j), ks.at(i, j), 0.0);
  }
  EXPECT_EQ(differing, 0);
}

TEST(SubMatrices, ElasticMatricesAreSymmetricPositiveDefinite) {
  for (PlaneMode mode : {PlaneMode::Stress, PlaneMode::Strain}) {
    const Mat3 e = elastic_matrix(RockMaterial{2000, 50e9, 0.25}, mode);
    EXPECT_TRUE(e.isApprox(e.transpose()));
    Eigen::SelfAdjointEigenSolver<Mat3> eig(e);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0);
  }
  // Plane stress: E/(1-ν²)[1 ν 0; ν 1 0; 0 0 (1-ν)/2].
  const Mat3 e = elastic_matrix(RockMaterial{2000, 50e9, 0.25}, PlaneMode::Stress);
  EXPECT_NEAR(e(0, 0), 50e9 / (1 - 0.0625), 1);
  EXPECT_NEAR(e(2, 2), 50e9 / (1 - 0.0625) * 0.375, 1);
}

TEST(SubMatrices, RigidBodyMotionStoresNoElasticEnergyAndMovesPointsRigidly) {
  // The block's assembled matrix with no inertia contribution isolated: run
  // one step of a free block with a rigid initial velocity and no gravity;
  // its stress must stay zero, and distances between vertices unchanged.
  World w;
  const int rock = w.add_rock_material(test::granite());
  const BlockId b = w.add_block({{0, 0}, {2, 0}, {2.5, 1}, {0.3, 1.4}}, rock);
  w.controls().g1 = 1e-3;
  w.controls().g2 = 0.1;
  Vec6 v = Vec6::Zero();
  v << 1.5, -0.7, 0.2, 0, 0, 0;  // translation + spin, no strain rate
  w.set_block_velocity(b, v);
  const auto before = std::vector<Vec2>(w.block_vertices(b).begin(), w.block_vertices(b).end());
  for (int i = 0; i < 20; ++i) w.step();
  EXPECT_LT(w.block_stress(b).norm(), 1e-6) << "rigid motion produced stress";
  const auto after = w.block_vertices(b);
  for (std::size_t i = 0; i < before.size(); ++i)
    for (std::size_t j = i + 1; j < before.size(); ++j)
      EXPECT_NEAR((after[i] - after[j]).norm(), (before[i] - before[j]).norm(), 1e-9);
  // The rotation really happened: 20 steps × 1e-3 s × 0.2 rad/s.
  const double angle_before = std::atan2(before[1].y() - before[0].y(), before[1].x() - before[0].x());
  const double angle_after = std::atan2(after[1].y() - after[0].y(), after[1].x() - after[0].x());
  EXPECT_NEAR(angle_after - angle_before, 20 * 1e-3 * 0.2, 1e-9);

  // And the elastic sub-matrix itself: Dᵀ K D = 0 for rigid D, > 0 for strain.
  Mat6 k = Mat6::Zero();
  k.bottomRightCorner<3, 3>() = w.block_area(b) * elastic_matrix(test::granite(), PlaneMode::Stress);
  Vec6 rigid;
  rigid << 0.3, -0.2, 0.05, 0, 0, 0;
  EXPECT_EQ(rigid.dot(k * rigid), 0.0);
  Vec6 strain;
  strain << 0, 0, 0, 1e-4, -2e-4, 3e-4;
  EXPECT_GT(strain.dot(k * strain), 0.0);
}

TEST(SubMatrices, AssembledSystemWithContactsIsSymmetric) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  test::add_fixed_base(w, test::rectangle(0, 0, 4, 1), rock);
  w.add_block(test::rectangle(0.5, 1, 1, 1), rock);
  w.add_block(test::rectangle(1.5, 1, 1, 1), rock);
  w.add_block(test::rectangle(1.0, 2, 1, 0.5), rock);
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g1 = 1e-3;
  w.step();
  ASSERT_GT(w.contacts().size(), 4u);
  const auto a = w.last_matrix().to_sparse();
  const Eigen::MatrixXd dense = a.toDense();
  EXPECT_LT((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-9 * dense.cwiseAbs().maxCoeff());
}
