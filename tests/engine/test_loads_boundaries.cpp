// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// History loads (SHI, FHI, DHI) and boundaries (Fixed, VBC, SBC) on their own.
#include <gtest/gtest.h>

#include <cmath>

#include "../scenes.hpp"
#include "core/error.hpp"

using namespace dda;

TEST(History, InterpolatesAndIntegratesPiecewiseLinear) {
  // Triangle: 0 at t=0, 2 at t=1, 0 at t=3. Integral to 3 is 3 (area).
  const History h({{0, 0}, {1, 2}, {3, 0}});
  EXPECT_DOUBLE_EQ(h.value(-1), 0);
  EXPECT_DOUBLE_EQ(h.value(0.5), 1);
  EXPECT_DOUBLE_EQ(h.value(2), 1);
  EXPECT_DOUBLE_EQ(h.value(5), 0);
  EXPECT_DOUBLE_EQ(h.integral(0.5), 0.25);
  EXPECT_DOUBLE_EQ(h.integral(1), 1);
  EXPECT_DOUBLE_EQ(h.integral(2), 2.5);
  EXPECT_DOUBLE_EQ(h.integral(3), 3);
  EXPECT_DOUBLE_EQ(h.integral(10), 3);
  // Constant before the first point.
  EXPECT_DOUBLE_EQ(History({{1, 4}, {2, 4}}).integral(1.5), 6);
}

TEST(History, RejectsBadPoints) {
  EXPECT_THROW(History(std::vector<std::pair<double, double>>{}), Error);
  EXPECT_THROW(History({{0, 1}, {0, 2}}), Error);
  EXPECT_THROW(History({{0, NAN}}), Error);
  try {
    History({{0, 0}, {1, 1}, {0.5, 2}}, "pressure on the left end");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pressure on the left end: times must increase"), std::string::npos);
  }
}

namespace {
struct FreeBlock {
  World w;
  BlockId b;
  RockMaterial rock{2000, 50e9, 0.25};
  FreeBlock() {
    const int r = w.add_rock_material(rock);
    b = w.add_block(test::rectangle(0, 0, 1, 0.5), r);  // edge 1 is the right edge, x = 1
    w.controls().g1 = 1e-5;
    w.controls().g2 = 0.01;
    // A first-order block: these tests check the paper's per-block equations,
    // so the wave model must not mesh it for the loads' pulses.
    w.controls().mesh_size = 0;
  }
};
}  // namespace

TEST(ViscousBoundary, DashpotForceIsRhoCLvOverTwoPerEndAndBalancesMomentum) {
  // Reference: each end of the edge carries t = −ρ(C_P v_n n + C_S v_s s)
  // over l/2 (paper Eqs. 6–7, 12); the block's momentum change over the step
  // equals the dashpots' impulse (DDA: m(v1 − v0)/Δt = f(v1)).
  FreeBlock s;
  Vec6 v0 = Vec6::Zero();
  v0 << 1.0, 0.5, 0, 0, 0, 0;
  s.w.set_block_velocity(s.b, v0);
  const int vbc = s.w.add_viscous_boundary({{s.b, 1}});
  s.w.step();
  const double g = s.rock.youngs / (2 * 1.25), k = s.rock.youngs / (3 * 0.5);
  const double cp = std::sqrt((k + 4 * g / 3) / s.rock.density), cs = std::sqrt(g / s.rock.density);
  const double l = 0.5;
  const auto forces = s.w.boundary_point_forces(vbc);
  ASSERT_EQ(forces.size(), 2u);
  const auto v = s.w.block_vertices(s.b);
  const Vec2 ends[2] = {v[1], v[2]};
  for (int i = 0; i < 2; ++i) {
    const Vec2 vel = s.w.velocity_at(s.b, ends[i]);
    // n = +x (outward), s = +y along the edge.
    EXPECT_NEAR(forces[i].x(), -s.rock.density * cp * l / 2 * vel.x(), 1e-6 * std::abs(forces[i].x()));
    EXPECT_NEAR(forces[i].y(), -s.rock.density * cs * l / 2 * vel.y(), 1e-6 * std::abs(forces[i].y()));
  }
  const Vec6 v1 = s.w.block_velocity(s.b);
  const double m = s.w.block_mass(s.b), dt = s.w.last_stats().dt;
  const Vec2 total = s.w.boundary_force(vbc);
  EXPECT_NEAR(m * (v1[0] - v0[0]) / dt, total.x(), 1e-9 * std::abs(total.x()));
  EXPECT_NEAR(m * (v1[1] - v0[1]) / dt, total.y(), 1e-9 * std::abs(total.y()));
  EXPECT_LT(total.x(), 0);
  EXPECT_LT(total.y(), 0);
}

TEST(SpringBoundary, SpringGivesPLTimesTheStepDisplacementAndBalancesMomentum) {
  // Reference: at each end K = p·l (Eq. 22), acting on the step's
  // displacement Δu only (the fixed-point sub-matrix without its residual
  // term, paper §3.3.1): force −p·l·Δu per end, and m(v1 − v0)/Δt = Σ forces.
  FreeBlock s;
  const double p = 1e11;
  Vec6 v0 = Vec6::Zero();
  v0 << 2.0, -0.5, 0, 0, 0, 0;
  s.w.set_block_velocity(s.b, v0);
  const int sbc = s.w.add_spring_boundary({{s.b, 1}}, p);
  const Vec2 before[2] = {s.w.block_vertices(s.b)[1], s.w.block_vertices(s.b)[2]};
  s.w.step();
  const auto forces = s.w.boundary_point_forces(sbc);
  const Vec2 after[2] = {s.w.block_vertices(s.b)[1], s.w.block_vertices(s.b)[2]};
  for (int i = 0; i < 2; ++i) {
    const Vec2 expected = -p * 0.5 * (after[i] - before[i]);
    EXPECT_NEAR(forces[i].x(), expected.x(), 1e-9 * expected.norm());
    EXPECT_NEAR(forces[i].y(), expected.y(), 1e-9 * expected.norm());
  }
  const Vec6 v1 = s.w.block_velocity(s.b);
  const double m = s.w.block_mass(s.b), dt = s.w.last_stats().dt;
  const Vec2 total = s.w.boundary_force(sbc);
  EXPECT_NEAR(m * (v1[0] - v0[0]) / dt, total.x(), 1e-9 * std::abs(total.x()));
  EXPECT_NEAR(m * (v1[1] - v0[1]) / dt, total.y(), 1e-9 * std::abs(total.y()));
  // It resists the motion but does not pull the block back to its start.
  EXPECT_LT(total.x(), 0);
  for (int i = 0; i < 50; ++i) s.w.step();
  EXPECT_GT(s.w.block_displacement(s.b).x(), 0);
  EXPECT_LT(s.w.block_velocity(s.b)[0], v0[0]);
}

TEST(PressureLoad, ShiEqualsFhiForTheSameResultant) {
  // A pressure p on the left edge (length 0.5) equals a point force p·l at
  // the edge's midpoint pushing into the block.
  FreeBlock shi, fhi;
  const int id = shi.w.add_pressure_load({{shi.b, 3}});  // edge 3: (0,0.5) → (0,0)
  shi.w.set_pressure_history(id, History({{0, 0}, {1e-4, 5e6}, {2e-4, 0}}));
  const int load = fhi.w.add_point_load(fhi.b, Vec2(0, 0.25), Vec2::Zero());
  fhi.w.set_point_load_history(load, Vec2(1, 0), History({{0, 0}, {1e-4, 5e6 * 0.5}, {2e-4, 0}}));
  // First step: undeformed edge, identical generalised forces.
  shi.w.step();
  fhi.w.step();
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(shi.w.block_velocity(shi.b)[k], fhi.w.block_velocity(fhi.b)[k],
                1e-9 * shi.w.block_velocity(shi.b).norm());
  // Later the pressure follows the strained edge (length and normal change
  // with strains of ~1e-5) while the point force keeps its direction and size:
  // the two agree to the order of the strain.
  for (int i = 0; i < 30; ++i) {
    shi.w.step();
    fhi.w.step();
  }
  EXPECT_GT(shi.w.block_velocity(shi.b)[0], 0.1);
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(shi.w.block_velocity(shi.b)[k], fhi.w.block_velocity(fhi.b)[k],
                1e-4 * shi.w.block_velocity(shi.b).norm());
  EXPECT_NEAR(shi.w.block_stress(shi.b)[0], fhi.w.block_stress(fhi.b)[0],
              1e-4 * std::abs(fhi.w.block_stress(fhi.b)[0]));
}

TEST(DisplacementTarget, VelocityHistoryIsFollowedWithinTheG2Bound) {
  // The paper's DHI pulse: triangular particle velocity, peak 2.03 m/s at
  // 0.5 ms, zero at 2.5 ms, integrated to displacement (final 2.5375 mm).
  FreeBlock s;
  const History velocity({{0, 0}, {0.5e-3, 2.03}, {2.5e-3, 0}});
  const int t = s.w.add_displacement_target(s.b, Vec2(0, 0.25), Vec2(1, 0));
  s.w.set_target_velocity_history(t, velocity);
  double worst = 0;
  while (s.w.time() < 3e-3) {
    s.w.step();
    worst = std::max(worst, std::abs(s.w.target_point_displacement(t).x() - velocity.integral(s.w.time())));
  }
  EXPECT_LE(worst, s.w.controls().g2 * s.w.half_height());
  EXPECT_NEAR(s.w.target_point_displacement(t).x(), 0.5 * 2.03 * 2.5e-3, 1e-6);
}

TEST(FixedBoundary, FixedEdgeDoesNotMove) {
  FreeBlock s;
  s.w.fix_edges({{s.b, 1}});
  s.w.controls().gravity = Vec2(0, -9.81);
  s.w.add_point_load(s.b, Vec2(0, 0.25), Vec2(-1e6, 0));
  for (int i = 0; i < 100; ++i) s.w.step();
  const auto v = s.w.block_vertices(s.b);
  EXPECT_LT((v[1] - Vec2(1, 0)).norm(), 1e-6);
  EXPECT_LT((v[2] - Vec2(1, 0.5)).norm(), 1e-6);
  EXPECT_GT((v[0] - Vec2(0, 0)).norm(), 1e-6) << "the free end does move (elastically)";
}

TEST(LoadsAndBoundaries, BadEdgesAreRejected) {
  FreeBlock s;
  EXPECT_THROW(s.w.add_pressure_load({{s.b, 7}}), Error);
  EXPECT_THROW(s.w.add_viscous_boundary({{3, 0}}), Error);
  EXPECT_THROW(s.w.add_spring_boundary({{s.b, 1}}, -1), Error);
  EXPECT_THROW(s.w.add_pressure_load({}), Error);
}
