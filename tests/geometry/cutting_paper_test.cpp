// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The paper's geometries (paper/reference-numbers.md): the jointed rock bars
// of Section 2 (Fig. 2, Models 1–3) and the blasting model of Section 4.
//
// Expected blocks are worked out here independently of the cutting code: for
// the bars, each horizontal strip between two horizontal joints is clipped by
// the band between two neighbouring inclined joints (Sutherland–Hodgman
// clipping of a convex polygon by half-planes), which gives every
// parallelogram and every clipped end piece with its exact area.
#include <gtest/gtest.h>

#include <cmath>

#include "cutting_support.hpp"

namespace dda::geometry::test {
namespace {

constexpr double kPiValue = 3.14159265358979323846;

// Convex polygon ∩ {p : n·p ≥ c}.
std::vector<Vec2> clip_half_plane(const std::vector<Vec2>& poly, const Vec2& n, double c) {
  std::vector<Vec2> out;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2& p = poly[k];
    const Vec2& q = poly[(k + 1) % poly.size()];
    const double fp = n.dot(p) - c, fq = n.dot(q) - c;
    if (fp >= 0) out.push_back(p);
    if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) out.push_back(p + (fp / (fp - fq)) * (q - p));
  }
  // Drop repeated points (a clipping line through a corner).
  std::vector<Vec2> clean;
  for (const Vec2& p : out)
    if (clean.empty() || (p - clean.back()).norm() > 1e-12) clean.push_back(p);
  while (clean.size() > 1 && (clean.front() - clean.back()).norm() <= 1e-12) clean.pop_back();
  return clean;
}

struct Piece {
  std::vector<Vec2> outline;
  double area;
  Vec2 centroid;
};

// The blocks of a 20 m × 1 m bar cut by horizontal joints every 0.2 m and a
// second set at `dip` degrees, 0.2 m apart measured perpendicular to the
// joints, one of them through the bar's lower-left corner (0, 0).
std::vector<Piece> expected_bar_blocks(double dip) {
  const double rad = dip * kPiValue / 180.0;
  const Vec2 normal(-std::sin(rad), std::cos(rad));  // the inclined joints are n·p = 0.2 k
  std::vector<Piece> pieces;
  for (int row = 0; row < 5; ++row) {
    const auto strip = rectangle(0, 0.2 * row, 20, 0.2);
    for (int k = -200; k <= 200; ++k) {
      auto band = clip_half_plane(strip, normal, 0.2 * k);
      band = clip_half_plane(band, -normal, -0.2 * (k + 1));
      if (band.size() < 3) continue;
      const PolygonMoments m = polygon_moments(band);
      if (m.area < 1e-9) continue;  // the band only touches the strip at a corner
      pieces.push_back({band, m.area, m.centroid});
    }
  }
  return pieces;
}

void expect_blocks_match(const BlockSet& set, const std::vector<Piece>& expected) {
  ASSERT_EQ(set.blocks.size(), expected.size());
  for (const Piece& piece : expected) {
    const auto found = set.blocks_containing(piece.centroid);
    ASSERT_EQ(found.size(), 1u) << "at (" << piece.centroid.x() << ", " << piece.centroid.y() << ")";
    const CutBlock& block = set.blocks[found[0]];
    EXPECT_NEAR(block.area, piece.area, 1e-12);
    ASSERT_EQ(block.vertices.size(), piece.outline.size())
        << "block at (" << piece.centroid.x() << ", " << piece.centroid.y() << ")";
    for (const Vec2& v : piece.outline) {
      double nearest = 1e300;
      for (const Vec2& w : block.vertices) nearest = std::min(nearest, (v - w).norm());
      EXPECT_LT(nearest, 1e-12);
    }
  }
}

CutInput rock_bar(double second_dip) {
  CutInput in;
  in.domain = rectangle(0, 0, 20, 1);
  in.sets = {persistent_set(0, 0.2, Vec2(0, 0), 1), persistent_set(second_dip, 0.2, Vec2(0, 0), 2)};
  return in;
}

TEST(PaperRockBar, Model1Gives500SquaresOf004) {
  const CutInput in = rock_bar(90);
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 500u);  // 100 columns × 5 rows
  for (const CutBlock& b : set.blocks) {
    EXPECT_NEAR(b.area, 0.04, 1e-12);
    EXPECT_EQ(b.vertices.size(), 4u);
  }
  expect_valid_partition(set, in);
  expect_blocks_match(set, expected_bar_blocks(90));
}

// Model 2: inclined set at 60°. Along each horizontal joint the inclined
// joints are 0.2 / sin 60° = 0.2309 m apart, so the full blocks are
// parallelograms of 0.2 × 0.2309 = 0.046188 m². In row j (0.2 j ≤ y ≤
// 0.2 (j+1)) the inclined joints n·p = 0.2 k with 0.1 j − 10√3 < 0.2 k <
// 0.1 (j+1) cross the row: 87 of them in every row, so 88 blocks per row and
// 440 in all. Joints k = j/2 pass exactly through the left-end points
// (0, 0.2 j) where horizontal joints meet the boundary, for even j.
TEST(PaperRockBar, Model2At60Degrees) {
  const CutInput in = rock_bar(60);
  const BlockSet set = cut_blocks(in);
  const auto expected = expected_bar_blocks(60);
  EXPECT_EQ(expected.size(), 440u);
  EXPECT_EQ(set.blocks.size(), 440u);
  expect_blocks_match(set, expected);
  expect_valid_partition(set, in);
  int full = 0;
  for (const CutBlock& b : set.blocks)
    if (std::abs(b.area - 0.04 / std::sin(kPiValue / 3)) < 1e-12) ++full;
  // Whole parallelograms per row: 86, 85, 86, 85, 86. In rows 1 and 3 the
  // last inclined joint (k = −86, resp. −85) leaves the row through the bar's
  // right end, so one more band is clipped there.
  EXPECT_EQ(full, 428);
}

// Model 3: inclined set at 30°: inclined joints 0.2 / sin 30° = 0.4 m apart
// along x, full parallelograms of 0.08 m². Row j is crossed by the joints with
// −10 + 0.1√3 j < 0.2 k < 0.1√3 (j+1): 50 in row 0 (the joint k = −50 only
// touches the corner (20, 0)) and 51 in rows 1–4, so 51 + 4 × 52 = 259 blocks.
TEST(PaperRockBar, Model3At30Degrees) {
  const CutInput in = rock_bar(30);
  const BlockSet set = cut_blocks(in);
  const auto expected = expected_bar_blocks(30);
  EXPECT_EQ(expected.size(), 259u);
  EXPECT_EQ(set.blocks.size(), 259u);
  expect_blocks_match(set, expected);
  expect_valid_partition(set, in);
  // The corner piece at the origin: the triangle (0,0), (0.2√3, 0.2), (0, 0.2).
  const auto corner = set.blocks_containing(Vec2(0.05, 0.15));
  ASSERT_EQ(corner.size(), 1u);
  EXPECT_NEAR(set.blocks[corner[0]].area, 0.02 * std::sqrt(3.0), 1e-12);
  EXPECT_EQ(set.blocks[corner[0]].vertices.size(), 3u);
}

// Section 4: 100 m square, sets at 45° and 135° every 2 m (through the
// chamber centre), 8 m × 4 m chamber at the centre.
TEST(PaperBlasting, Section4AreasSumToSquareMinusChamber) {
  CutInput in;
  in.domain = rectangle(0, 0, 100, 100);
  in.holes = {rectangle(46, 48, 8, 4)};
  in.sets = {persistent_set(45, 2, Vec2(50, 50), 1), persistent_set(135, 2, Vec2(50, 50), 1)};
  const BlockSet set = cut_blocks(in);
  EXPECT_NEAR(set.total_area(), 10000.0 - 32.0, 1e-12 * 10000.0);
  expect_valid_partition(set, in, 1e-12, 60);

  // Away from the boundary and the chamber every block is a 2 m × 2 m square
  // turned by 45°.
  int interior = 0;
  for (const CutBlock& b : set.blocks) {
    bool touches = false;
    for (const EdgeTag& t : b.edges) touches = touches || t.kind != EdgeKind::Joint;
    if (touches) continue;
    ++interior;
    EXPECT_NEAR(b.area, 4.0, 1e-9);
    EXPECT_EQ(b.vertices.size(), 4u);
  }
  EXPECT_GT(interior, 2300);

  double hole_length = 0, domain_length = 0;
  for (EdgeRef e : set.hole_boundary_edges(0)) hole_length += set.edge_length(e);
  for (EdgeRef e : set.domain_boundary_edges()) domain_length += set.edge_length(e);
  EXPECT_NEAR(hole_length, 24.0, 1e-9);
  EXPECT_NEAR(domain_length, 400.0, 1e-9);
}

}  // namespace
}  // namespace dda::geometry::test
