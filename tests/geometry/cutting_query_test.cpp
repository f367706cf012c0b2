// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Queries on a BlockSet: blocks containing a point or in a box, edges on a
// segment or in a box, boundary edges of the domain and of a hole. Checked on
// the rock bar Model 1 (0.2 m squares, horizontal joints material 1,
// vertical joints material 2) and on a square with a chamber.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.hpp"
#include "cutting_support.hpp"

namespace dda::geometry::test {
namespace {

class Model1Queries : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    CutInput in;
    in.domain = rectangle(0, 0, 20, 1);
    in.sets = {persistent_set(0, 0.2, Vec2::Zero(), 1), persistent_set(90, 0.2, Vec2::Zero(), 2)};
    bar = new BlockSet(cut_blocks(in));
  }
  static void TearDownTestSuite() {
    delete bar;
    bar = nullptr;
  }
  static BlockSet* bar;
};
BlockSet* Model1Queries::bar = nullptr;

TEST_F(Model1Queries, BlockContainingAPoint) {
  const auto inside = bar->blocks_containing(Vec2(0.1, 0.1));
  ASSERT_EQ(inside.size(), 1u);
  const CutBlock& b = bar->blocks[inside[0]];
  EXPECT_NEAR(b.area, 0.04, 1e-12);
  for (const Vec2& corner : {Vec2(0, 0), Vec2(0.2, 0), Vec2(0.2, 0.2), Vec2(0, 0.2)}) {
    const bool has =
        std::any_of(b.vertices.begin(), b.vertices.end(), [&](const Vec2& v) { return (v - corner).norm() < 1e-12; });
    EXPECT_TRUE(has) << corner.transpose();
  }
  EXPECT_EQ(inside[0], 0);                                       // reading order: the bottom-left block comes first
  EXPECT_EQ(bar->blocks_containing(Vec2(0.2, 0.1)).size(), 2u);  // on a shared edge
  EXPECT_EQ(bar->blocks_containing(Vec2(0.2, 0.2)).size(), 4u);  // on a shared corner
  EXPECT_TRUE(bar->blocks_containing(Vec2(30, 0.5)).empty());    // outside
  EXPECT_EQ(bar->blocks_containing(Vec2(19.9, 0.9))[0], 499);    // top-right block last
}

TEST_F(Model1Queries, BlocksInABox) {
  EXPECT_EQ(bar->blocks_in_box(Vec2(0, 0), Vec2(1, 1), BoxSelect::Centroid).size(), 25u);
  EXPECT_EQ(bar->blocks_in_box(Vec2(0, 0), Vec2(1, 1), BoxSelect::Inside).size(), 25u);
  // Overlap counts the column touching x = 1 as well.
  EXPECT_EQ(bar->blocks_in_box(Vec2(0, 0), Vec2(1, 1), BoxSelect::Overlap).size(), 30u);
  // A box wholly inside one block overlaps just that block.
  EXPECT_EQ(bar->blocks_in_box(Vec2(5.02, 0.02), Vec2(5.06, 0.06), BoxSelect::Overlap).size(), 1u);
  EXPECT_TRUE(bar->blocks_in_box(Vec2(5.02, 0.02), Vec2(5.06, 0.06), BoxSelect::Centroid).empty());
  EXPECT_TRUE(bar->blocks_in_box(Vec2(5.02, 0.02), Vec2(5.06, 0.06), BoxSelect::Inside).empty());
}

TEST_F(Model1Queries, EdgesOnASegment) {
  // The loaded left end and the fixed right end of the bar.
  for (double x : {0.0, 20.0}) {
    const auto end = bar->edges_on_segment(Vec2(x, 0), Vec2(x, 1));
    ASSERT_EQ(end.size(), 5u);
    std::set<int> blocks;
    double length = 0;
    for (EdgeRef e : end) {
      EXPECT_EQ(bar->tag(e).kind, EdgeKind::Domain);
      length += bar->edge_length(e);
      blocks.insert(e.block);
    }
    EXPECT_NEAR(length, 1.0, 1e-12);
    EXPECT_EQ(blocks.size(), 5u);
  }
  // A horizontal joint: 100 edges from the blocks below and 100 from above.
  const auto joint = bar->edges_on_segment(Vec2(0, 0.2), Vec2(20, 0.2));
  ASSERT_EQ(joint.size(), 200u);
  for (EdgeRef e : joint) {
    EXPECT_EQ(bar->tag(e).kind, EdgeKind::Joint);
    EXPECT_EQ(bar->tag(e).joint_material, 1);
  }
  // Vertical joints carry the other material.
  for (EdgeRef e : bar->edges_on_segment(Vec2(10, 0), Vec2(10, 1))) EXPECT_EQ(bar->tag(e).joint_material, 2);
  // Part of a segment: only edges wholly on it.
  EXPECT_EQ(bar->edges_on_segment(Vec2(20, 0), Vec2(20, 0.5)).size(), 2u);
}

TEST_F(Model1Queries, EdgesInABox) {
  // The corner block's 4 edges plus the edges its two neighbours share with it.
  EXPECT_EQ(bar->edges_in_box(Vec2(0, 0), Vec2(0.2, 0.2)).size(), 6u);
}

TEST_F(Model1Queries, DomainBoundaryEdges) {
  const auto edges = bar->domain_boundary_edges();
  EXPECT_EQ(edges.size(), 210u);  // 2 × 100 along the sides, 2 × 5 at the ends
  double length = 0;
  for (EdgeRef e : edges) length += bar->edge_length(e);
  EXPECT_NEAR(length, 42.0, 1e-9);
  EXPECT_THROW(bar->hole_boundary_edges(0), Error);  // the bar has no hole
}

TEST(HoleQueries, BoundaryEdgesOfEachHole) {
  CutInput in;
  in.domain = rectangle(0, 0, 20, 10);
  in.holes = {rectangle(2, 2, 4, 2), {Vec2(12, 3), Vec2(16, 3), Vec2(14, 7)}};
  in.sets = {persistent_set(30, 1.1, Vec2(0.05, 0.05)), persistent_set(150, 0.9, Vec2(0.05, 0.05))};
  const BlockSet set = cut_blocks(in);
  double first = 0, second = 0;
  for (EdgeRef e : set.hole_boundary_edges(0)) {
    first += set.edge_length(e);
    EXPECT_EQ(set.tag(e).hole, 0);
    // Every edge of hole 1 lies on one of its sides.
    const auto [a, b] = set.edge_points(e);
    const Vec2 m = 0.5 * (a + b);
    EXPECT_LT(distance_to_outline(in.holes[0], m), 1e-12);
  }
  for (EdgeRef e : set.hole_boundary_edges(1)) second += set.edge_length(e);
  EXPECT_NEAR(first, 12.0, 1e-9);
  EXPECT_NEAR(second, 4 + 2 * std::sqrt(20.0), 1e-9);
  EXPECT_THROW(set.hole_boundary_edges(2), Error);
  // A point inside a hole is in no block.
  EXPECT_TRUE(set.blocks_containing(Vec2(4, 3)).empty());
  // The edges on the chamber's roof are the hole's.
  const auto roof = set.edges_on_segment(Vec2(2, 4), Vec2(6, 4));
  ASSERT_FALSE(roof.empty());
  double roof_length = 0;
  for (EdgeRef e : roof) {
    EXPECT_EQ(set.tag(e).kind, EdgeKind::Hole);
    roof_length += set.edge_length(e);
  }
  EXPECT_NEAR(roof_length, 4.0, 1e-9);
  expect_valid_partition(set, in);
}

}  // namespace
}  // namespace dda::geometry::test
