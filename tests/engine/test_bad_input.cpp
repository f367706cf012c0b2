// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// User errors give dda::Error naming the object and the cause.
#include <gtest/gtest.h>

#include "../scenes.hpp"
#include "core/error.hpp"

using namespace dda;

namespace {
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}
#define EXPECT_MESSAGE(expr, part) \
  EXPECT_NE(error_of([&] { expr; }).find(part), std::string::npos) << error_of([&] { expr; })
}  // namespace

TEST(BadInput, DegeneratePolygonsNameTheBlock) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(0, 0, 1, 1), rock);
  EXPECT_MESSAGE(w.add_block({{0, 0}, {1, 0}, {2, 0}}, rock), "block 1: polygon has zero area");
  EXPECT_MESSAGE(w.add_block({{0, 0}, {4, 0}, {4, 4}, {1, -1}}, rock), "block 1: polygon is self-intersecting");
  EXPECT_MESSAGE(w.add_block({{0, 0}, {1, 0}, {1, 0}, {1, 1}}, rock), "block 1: vertices 2 and 3 are repeated");
  EXPECT_MESSAGE(w.add_block(test::rectangle(5, 0, 1, 1), 3), "block 1: unknown rock material 3");
  EXPECT_EQ(w.block_count(), 1u) << "a rejected block must not be half-added";
}

TEST(BadInput, MaterialConstantsAreChecked) {
  World w;
  EXPECT_MESSAGE(w.add_rock_material(RockMaterial{NAN, 5e9, 0.25}), "density is not a finite number");
  EXPECT_MESSAGE(w.add_rock_material(RockMaterial{2600, 0, 0.25}), "Young's modulus must be positive");
  EXPECT_MESSAGE(w.add_rock_material(RockMaterial{2600, -1, 0.25}), "Young's modulus must be positive");
  EXPECT_MESSAGE(w.add_rock_material(RockMaterial{2600, 5e9, 0.5}), "Poisson's ratio must lie in [0, 0.5)");
  EXPECT_MESSAGE(w.add_joint_material(JointMaterial{NAN, 0, 0}), "friction angle");
  EXPECT_MESSAGE(w.add_joint_material(JointMaterial{30, -1, 0}), "cohesion must be zero or positive");
  // A constant broken after creation is caught at the next step.
  const int rock = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(0, 0, 1, 1), rock);
  w.rock_material(rock).youngs = NAN;
  EXPECT_MESSAGE(w.step(), "rock material 0: Young's modulus is not a finite number");
}

TEST(BadInput, ControlsAreChecked) {
  World w;
  w.add_block(test::rectangle(0, 0, 1, 1), w.add_rock_material(test::granite()));
  w.controls().g2 = -1;
  EXPECT_MESSAGE(w.step(), "g2 must be positive");
  w.controls().g2 = 0.01;
  w.controls().gg = 2;
  EXPECT_MESSAGE(w.step(), "gg must lie in [0, 1]");
}

TEST(BadInput, OverlappingBlocksAtTheStartAreNamed) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(0, 0, 1, 1), rock);
  w.add_block(test::rectangle(0.5, 0.5, 1, 1), rock);
  EXPECT_MESSAGE(w.step(), "blocks 0 and 1 overlap at the start");

  World inside;
  inside.add_block(test::rectangle(0, 0, 2, 2), inside.add_rock_material(test::granite()));
  inside.add_block({{0.5, 0.5}, {1.5, 0.5}, {1, 1.5}}, 0);
  EXPECT_MESSAGE(inside.step(), "overlap at the start");

  // Touching blocks are fine.
  World touching;
  touching.add_block(test::rectangle(0, 0, 1, 1), touching.add_rock_material(test::granite()));
  touching.add_block(test::rectangle(1, 0, 1, 1), 0);
  EXPECT_NO_THROW(touching.step());

  // Also when the shared edge is computed with cos/sin round-off.
  World rotated;
  const int rock2 = rotated.add_rock_material(test::granite());
  for (int i = 0; i < 5; ++i)
    rotated.add_block(test::rotated(test::rectangle(i * 0.3, 0, 0.3, 0.2), deg_to_rad(33)), rock2);
  EXPECT_NO_THROW(rotated.step());
}

// No edge crossing and no vertex strictly inside: these passed the start
// check before and ran with no contact between the blocks.
TEST(BadInput, CoincidingAndCollinearOverlappingBlocksAreNamed) {
  World same;
  const int rock = same.add_rock_material(test::granite());
  same.add_block(test::rectangle(0, 0, 1, 1), rock);
  same.add_block(test::rectangle(2, 0, 1, 1), rock);
  same.add_block(test::rectangle(0, 0, 1, 1), rock);
  EXPECT_MESSAGE(same.step(), "blocks 0 and 2 overlap at the start: they share area");

  // Overlapping by half along their collinear top and bottom edges.
  World half;
  half.add_block(test::rectangle(0, 0, 1, 1), half.add_rock_material(test::granite()));
  half.add_block(test::rectangle(0.5, 0, 1, 1), 0);
  EXPECT_MESSAGE(half.step(), "blocks 0 and 1 overlap at the start");

  // One inside the other, sharing three sides.
  World inside;
  inside.add_block(test::rectangle(0, 0, 2, 1), inside.add_rock_material(test::granite()));
  inside.add_block(test::rectangle(0, 0, 1, 1), 0);
  EXPECT_MESSAGE(inside.step(), "blocks 0 and 1 overlap at the start");

  // Rotated copies (round-off in every vertex) coincide too.
  World rotated;
  const int rock2 = rotated.add_rock_material(test::granite());
  rotated.add_block(test::rotated(test::rectangle(0, 0, 0.3, 0.2), deg_to_rad(33)), rock2);
  rotated.add_block(test::rotated(test::rectangle(0, 0, 0.3, 0.2), deg_to_rad(33)), rock2);
  EXPECT_MESSAGE(rotated.step(), "blocks 0 and 1 overlap at the start");

  // A block on two others, its bottom edge over their T-junction: fine.
  World stacked;
  stacked.add_block(test::rectangle(0, 0, 1, 1), stacked.add_rock_material(test::granite()));
  stacked.add_block(test::rectangle(1, 0, 1, 1), 0);
  stacked.add_block(test::rectangle(0.5, 1, 1, 1), 0);
  EXPECT_NO_THROW(stacked.step());
}

TEST(BadInput, DivergingStepNamesTheBlock) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(0, 0, 1, 1), rock);
  const BlockId b = w.add_block(test::rectangle(3, 0, 1, 1), rock);
  Vec6 v = Vec6::Zero();
  v[0] = 1e306;  // finite, but the inertia term overflows
  w.set_block_velocity(b, v);
  EXPECT_MESSAGE(w.step(), "diverged: block 1 has a non-finite load");
  EXPECT_MESSAGE(w.set_block_velocity(b, Vec6::Constant(NAN)), "block 1: velocity is not finite");
}

// Entries that are finite but so large that the solve overflows used to give
// "the linear solve produced non-finite values" with no block named.
TEST(BadInput, OverflowingSolveNamesTheBlock) {
  World dense;
  const int rock = dense.add_rock_material(test::granite());
  RockMaterial heavy = test::granite();
  heavy.density = 1e300;  // the inertia term 2ρ/Δt² overflows
  dense.controls().g1 = 1e-4;
  dense.controls().gravity = Vec2(0, -9.81);
  const int heavy_rock = dense.add_rock_material(heavy);
  dense.add_block(test::rectangle(0, 0, 1, 1), rock);
  dense.add_block(test::rectangle(3, 0, 1, 1), heavy_rock);
  EXPECT_MESSAGE(dense.step(), "diverged: block 1 has a non-finite stiffness");

  World loaded;
  const int rock2 = loaded.add_rock_material(test::granite());
  loaded.add_block(test::rectangle(0, 0, 1, 1), rock2);
  const BlockId b = loaded.add_block(test::rectangle(3, 0, 1, 1), rock2);
  loaded.add_point_load(b, Vec2(3.5, 0.5), Vec2(0, -1e300));  // finite, but its square is not
  EXPECT_MESSAGE(loaded.step(), "the linear solve overflowed; block 1 has the largest load");
}

TEST(BadInput, EmptyModelAndUnknownIds) {
  World w;
  EXPECT_MESSAGE(w.step(), "the model has no blocks");
  EXPECT_MESSAGE(w.block_centroid(0), "no block 0");
  EXPECT_MESSAGE(w.set_point_load(4, Vec2(1, 0)), "no point load 4");
}

TEST(BadInput, StepThatWouldTurnABlockInsideOutIsRefusedNamingTheBlock) {
  // A flat triangle whose apex is pulled through its base in one step by a
  // stiff target spring: the step is cut and redone, then refused; the state
  // is never left with a block of negative area.
  World w;
  const int rock = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(5, 0, 1, 1), rock);
  const BlockId sliver = w.add_block({{0, 0}, {2, 0}, {1, 0.05}}, rock);
  w.add_fixed_point(sliver, Vec2(0, 0));
  w.add_fixed_point(sliver, Vec2(2, 0));
  const int t = w.add_displacement_target(sliver, Vec2(1, 0.05));
  w.set_target_displacement(t, Vec2(0, -0.5));
  w.controls().g1 = 1e-3;
  w.controls().g2 = 1000;             // no displacement bound: only the inversion check can refuse the step
  w.controls().contact_range = 1000;  // (nor the contact range)
  w.controls().max_step_cuts = 3;
  EXPECT_MESSAGE(w.step(), "would turn inside out (its area would become zero or negative) (block 1)");
  EXPECT_GT(w.block_area(sliver), 0);
}
