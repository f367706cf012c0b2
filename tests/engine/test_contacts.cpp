// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Contact detection: a joint between two blocks carries exactly two contacts
// (k_n = 2·g0/l, the paper's Eq. 4); touching corners of aligned blocks none.
#include <gtest/gtest.h>

#include <map>

#include "../scenes.hpp"
#include "contact/broad_phase.hpp"
#include "contact/contact_kinematics.hpp"
#include "contact/narrow_phase.hpp"

using namespace dda;

namespace {

struct Polys {
  std::vector<int> start{0};
  std::vector<Vec2> vertices;
  std::vector<int> joints;
  void add(const std::vector<Vec2>& p) {
    vertices.insert(vertices.end(), p.begin(), p.end());
    joints.insert(joints.end(), p.size(), 0);
    start.push_back(static_cast<int>(vertices.size()));
  }
  BlockPolygons view() const { return {start, vertices}; }
};

std::map<std::pair<int, int>, int> contacts_per_pair(const Polys& p, double range) {
  const auto pairs = find_candidate_pairs(p.view(), range);
  NarrowPhaseSettings s;
  s.range = range;
  std::map<std::pair<int, int>, int> count;
  for (const Contact& c : detect_contacts(p.view(), p.joints, pairs, s))
    ++count[{std::min(c.vblock, c.eblock), std::max(c.vblock, c.eblock)}];
  return count;
}

}  // namespace

TEST(Contacts, RegularGridHasTwoContactsPerJointAndNoneAcrossCorners) {
  Polys p;
  const int n = 4;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) p.add(test::rectangle(c * 0.2, r * 0.2, 0.2, 0.2));
  const auto count = contacts_per_pair(p, 0.006);
  // 2·n·(n-1) joints, each with two contacts; no diagonal pairs.
  EXPECT_EQ(count.size(), static_cast<std::size_t>(2 * n * (n - 1)));
  for (const auto& [pair, k] : count) {
    const int a = pair.first, b = pair.second;
    const bool side = (b - a == 1 && a / n == b / n) || b - a == n;
    EXPECT_TRUE(side) << "contact across a corner between " << a << " and " << b;
    EXPECT_EQ(k, 2) << "pair " << a << "," << b;
  }
}

TEST(Contacts, RotatedGridBehavesTheSame) {
  Polys p;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.add(test::rotated(test::rectangle(c * 2.0, r * 2.0, 2, 2), deg_to_rad(45)));
  const auto count = contacts_per_pair(p, 0.6);  // a wide range, as in the blasting model
  EXPECT_EQ(count.size(), 12u);
  for (const auto& [pair, k] : count) EXPECT_EQ(k, 2);
}

TEST(Contacts, RunningBondGivesContactsAtOverlapEnds) {
  // Upper brick spans x ∈ [0.5, 1.5] over two lower bricks: two joints of
  // length 0.5, each with two contacts, plus the lower bricks' shared joint.
  Polys p;
  p.add(test::rectangle(0, 0, 1, 0.5));
  p.add(test::rectangle(1, 0, 1, 0.5));
  p.add(test::rectangle(0.5, 0.5, 1, 0.5));
  const auto count = contacts_per_pair(p, 0.005);
  EXPECT_EQ(count.at({0, 1}), 2);
  EXPECT_EQ(count.at({0, 2}), 2);
  EXPECT_EQ(count.at({1, 2}), 2);
}

TEST(Contacts, CornerPokingIntoAnEdgeMakesOneContact) {
  Polys p;
  p.add(test::rectangle(0, 0, 2, 1));                         // floor block
  p.add({{1.0, 1.001}, {1.5, 1.5}, {1.0, 2.0}, {0.5, 1.5}});  // a diamond above it
  const auto pairs = find_candidate_pairs(p.view(), 0.01);
  NarrowPhaseSettings s;
  s.range = 0.01;
  const auto contacts = detect_contacts(p.view(), p.joints, pairs, s);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].vblock, 1);
  EXPECT_EQ(contacts[0].vertex, 0);
  EXPECT_EQ(contacts[0].eblock, 0);
  EXPECT_EQ(contacts[0].edge, 2);  // the floor's top edge (2,1)→(0,1)
}

// The blast model cut with 1 m joints (bench scene blast(1)): a small
// triangle on the chamber roof and a block right of the chamber, 1 m apart
// across the chamber's corner. The search range (1.25 m) pairs their
// vertices; the triangle's corner lies behind the line of one of the other
// block's edges but far outside the block. Taken as a contact, such a
// pair is a locked contact 0.17 m "deep" whose 1.7e10 N spring crushes the
// triangle (blast(1) dies with "the linear solver did not converge").
TEST(Contacts, VertexBesideAFarCornerIsNotAPenetration) {
  Polys p;
  p.add({{3.4142136, 2.0}, {3.6568542, 2.0}, {3.5355339, 2.1213203}});
  p.add({{4.0, 1.1715729}, {4.0, 0.2426407}, {4.2426407, 0.0}, {4.9497475, 0.7071068}, {4.2426407, 1.4142136}});
  const double range = 1.25;
  const auto pairs = find_candidate_pairs(p.view(), range);
  ASSERT_EQ(pairs.size(), 1u);
  NarrowPhaseSettings s;
  s.range = range;
  const std::vector<Vec2> centroids{{3.5355339, 2.0404401}, {4.4, 0.7}};
  for (const Contact& c : detect_contacts(p.view(), p.joints, pairs, s)) {
    const ContactKinematics k = contact_kinematics(p.view(), centroids, c);
    EXPECT_LE(k.d0, 0.0) << "vertex " << c.vertex << " of block " << c.vblock << " against edge " << c.edge
                         << " of block " << c.eblock << " reads as " << k.d0 << " m deep";
  }
}

TEST(Contacts, FarApartBlocksHaveNoCandidatePairs) {
  Polys p;
  p.add(test::rectangle(0, 0, 1, 1));
  p.add(test::rectangle(1.1, 0, 1, 1));
  EXPECT_TRUE(find_candidate_pairs(p.view(), 0.05).empty());
  EXPECT_EQ(find_candidate_pairs(p.view(), 0.2).size(), 1u);
}

// Blocks scattered as far apart as a double reaches (a model that diverged,
// a damaged checkpoint): the grid's cell counts must not overflow a long (the
// checkpoint fuzzer found 3e223 cells cast to one: UBSan's
// float-cast-overflow), and a span that overflows a double leaves no grid.
// The touching pair is found either way, and no other.
TEST(Contacts, BlocksAsFarApartAsADoubleReachesArePaired) {
  const std::vector<std::pair<int, int>> touching{{0, 1}};
  Polys far;
  far.add(test::rectangle(0, 0, 1, 1));
  far.add(test::rectangle(1.1, 0, 1, 1));
  far.add(test::rectangle(1e220, 0, 1, 1));
  EXPECT_EQ(find_candidate_pairs(far.view(), 0.2), touching);
  Polys overflowing = far;
  overflowing.add(test::rectangle(-1.7e308, 0, 1e300, 1));
  overflowing.add(test::rectangle(1.7e308, 0, 1e300, 1));
  EXPECT_EQ(find_candidate_pairs(overflowing.view(), 0.2), touching);
}

// The automatic contact range: a tenth of the median edge (0.05 m here)
// instead of Shi's 2.5·g2·(half height) = 0.625 m, which in a fine model
// (0.5 m blocks in a 100 m high model) would pair every block with its second
// neighbours: the list then holds just the two contacts per joint.
TEST(ContactRange, FineModelsDoNotCarrySecondNeighbours) {
  auto contacts_with = [](double range) {
    World w;
    const int rock = w.add_rock_material(test::granite());
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) w.add_block(test::rectangle(0.5 * i, 0.5 * j, 0.5, 0.5), rock);
    const BlockId tall = w.add_block(test::rectangle(50, 0, 1, 100), rock);  // makes the half height 50 m
    w.add_fixed_point(tall, Vec2(50.5, 1));
    w.add_fixed_point(tall, Vec2(50.5, 99));
    w.controls().g1 = 1e-4;
    w.controls().g2 = 0.005;
    w.controls().contact_range = range;
    return w.step().contacts;
  };
  EXPECT_EQ(contacts_with(0), 2 * 2 * 6 * 5);  // 60 joints between the 36 blocks, two contacts each
  EXPECT_GT(contacts_with(0.625), 2 * 2 * 6 * 5);
}

// A block falling 10 cm a step outruns the automatic range (a tenth of its
// 1 m edge): the range widens and the step is redone at the same Δt, so the
// fall stays exact and no step is cut.
TEST(ContactRange, FastMotionWidensTheRangeInsteadOfCuttingTheStep) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  const BlockId b = w.add_block(test::rectangle(0, 0, 1, 1), rock);
  const double g = 9.81, dt = 0.01;
  w.controls().gravity = Vec2(0, -g);
  w.controls().g1 = dt;
  w.controls().g2 = 0.5;
  const double y0 = w.block_centroid(b).y();
  for (int i = 1; i <= 100; ++i) {
    const StepStats s = w.step();
    ASSERT_EQ(s.step_cuts, 0) << "step " << i << ": " << s.cut_reason;
    const double t = i * dt;
    ASSERT_NEAR(w.block_centroid(b).y(), y0 - 0.5 * g * t * t, 1e-9) << "step " << i;
  }
}

// An explicit range is a hard bound: moving further in a step cuts it.
TEST(ContactRange, AnExplicitRangeCutsStepsThatMoveFurther) {
  World w;
  const int rock = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(0, 0, 1, 1), rock);
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g1 = 0.1;  // 4.9 cm in the first step
  w.controls().g2 = 0.5;
  w.controls().contact_range = 0.05;  // at most 2 cm a step
  const StepStats s = w.step();
  EXPECT_GT(s.step_cuts, 0);
  EXPECT_NE(s.cut_reason.find("contact range"), std::string::npos) << s.cut_reason;
}
