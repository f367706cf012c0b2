// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Block cutting beyond the paper's cases: non-persistent sets and seeds, tree
// cutting of dangling joints, T-junctions, tags, slivers, inner loops,
// near-degenerate joints, bad input, and randomised arrangements.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "cutting_support.hpp"
#include "geometry/joint_sets.hpp"
#include "geometry/random.hpp"

namespace dda::geometry::test {
namespace {

CutInput square(double side = 10) {
  CutInput in;
  in.domain = rectangle(0, 0, side, side);
  return in;
}

JointLine line(double ax, double ay, double bx, double by, int material = 0) {
  return JointLine{Vec2(ax, ay), Vec2(bx, by), material};
}

// ---- Non-persistent sets and seeds --------------------------------------------

CutInput non_persistent(std::uint64_t seed) {
  CutInput in = square(20);
  JointSet a = persistent_set(30, 1.0), b = persistent_set(120, 1.0);
  for (JointSet* s : {&a, &b}) {
    s->trace_length = 4;
    s->bridge_length = 1;
    s->spacing_sd = 0.1;
    s->dip_sd_deg = 5;
    s->trace_sd = 0.5;
    s->seed = seed;
  }
  in.sets = {a, b};
  in.min_block_area = 1e-3;
  in.inner_cut_material = 0;
  return in;
}

TEST(NonPersistentSet, SameSeedSameBlocksDifferentSeedDifferentBlocks) {
  const BlockSet first = cut_blocks(non_persistent(42));
  const BlockSet again = cut_blocks(non_persistent(42));
  const BlockSet other = cut_blocks(non_persistent(43));
  EXPECT_GT(first.blocks.size(), 50u);
  EXPECT_EQ(fingerprint(first), fingerprint(again));
  EXPECT_NE(fingerprint(first), fingerprint(other));
  expect_valid_partition(first, non_persistent(42));
  expect_valid_partition(other, non_persistent(43));
  // Rock bridges leave traces that end in the rock: tree cutting removed them.
  EXPECT_GT(first.stats.dangling_edges_removed, 0);
}

TEST(NonPersistentSet, FewerBlocksThanThePersistentSet) {
  CutInput persistent = square(20);
  persistent.sets = {persistent_set(30, 1.0), persistent_set(120, 1.0)};
  CutInput broken = persistent;
  for (JointSet& s : broken.sets) {
    s.trace_length = 3;
    s.bridge_length = 1;
    s.seed = 5;
  }
  broken.inner_cut_material = 0;  // short traces can close loops that touch nothing else
  const BlockSet full = cut_blocks(persistent);
  const BlockSet partial = cut_blocks(broken);
  EXPECT_LT(partial.blocks.size(), full.blocks.size());
  expect_valid_partition(partial, broken);
}

TEST(NonPersistentSet, TracesAndBridgesAlternateAlongEachLine) {
  JointSet s = persistent_set(0, 1.0);
  s.trace_length = 2;
  s.bridge_length = 0.5;
  s.seed = 11;
  const auto segments = joint_set_segments(s, 0, Vec2(0, 0), Vec2(10, 3), 0.0);
  ASSERT_FALSE(segments.empty());
  // Group by line (y) and check the gaps between traces on one line.
  for (double y : {0.0, 1.0, 2.0, 3.0}) {
    std::vector<std::pair<double, double>> on_line;
    for (const auto& seg : segments)
      if (std::abs(seg.a.y() - y) < 1e-12)
        on_line.push_back({std::min(seg.a.x(), seg.b.x()), std::max(seg.a.x(), seg.b.x())});
    ASSERT_GE(on_line.size(), 3u) << "y = " << y;
    std::sort(on_line.begin(), on_line.end());
    for (std::size_t k = 0; k + 1 < on_line.size(); ++k)
      EXPECT_NEAR(on_line[k + 1].first - on_line[k].second, 0.5, 1e-12);
    for (std::size_t k = 1; k + 1 < on_line.size(); ++k) EXPECT_NEAR(on_line[k].second - on_line[k].first, 2.0, 1e-12);
  }
}

TEST(NonPersistentSet, SpacingVariationKeepsLinesReproducible) {
  JointSet s = persistent_set(90, 0.5);
  s.spacing_sd = 0.1;
  s.seed = 3;
  const auto a = joint_set_segments(s, 0, Vec2(0, 0), Vec2(10, 10), 0.1);
  const auto b = joint_set_segments(s, 0, Vec2(0, 0), Vec2(10, 10), 0.1);
  const auto c = joint_set_segments(s, 1, Vec2(0, 0), Vec2(10, 10), 0.1);  // another set index: another stream
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].a, b[k].a);
  bool differs = a.size() != c.size();
  for (std::size_t k = 0; !differs && k < a.size(); ++k) differs = a[k].a != c[k].a;
  EXPECT_TRUE(differs);
  // Around 20 lines cross a 10 m box at a mean spacing of 0.5 m.
  EXPECT_GT(a.size(), 12u);
  EXPECT_LT(a.size(), 32u);
}

TEST(RandomNumbers, FixedSequenceAndNormalMoments) {
  // SplitMix64's reference output for seed 0 (Steele et al.; also Vigna's splitmix64.c).
  SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
  SplitMix64 gauss(1234);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double x = gauss.normal();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.01);
}

// ---- Tree cutting, T-junctions, tags -----------------------------------------

TEST(TreeCutting, JointEndingInsideTheDomainMakesNoBlock) {
  CutInput in = square();
  in.lines = {line(-1, 5, 6, 5)};
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 1u);
  EXPECT_EQ(set.blocks[0].vertices.size(), 4u);  // the joint's end on the boundary is not a corner
  EXPECT_NEAR(set.blocks[0].area, 100.0, 1e-12);
  EXPECT_GT(set.stats.dangling_edges_removed, 0);
  for (const EdgeTag& t : set.blocks[0].edges) EXPECT_EQ(t.kind, EdgeKind::Domain);
}

TEST(TreeCutting, OnlyTheDanglingPartOfAJointGoes) {
  CutInput in = square();
  in.lines = {line(5, -1, 5, 11), line(-1, 3, 7, 3), line(8, 6, 9, 7)};
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 3u);  // left half split at y = 3; the right half whole
  expect_valid_partition(set, in);
  const auto right = set.blocks_containing(Vec2(7.5, 5));
  ASSERT_EQ(right.size(), 1u);
  EXPECT_NEAR(set.blocks[right[0]].area, 50.0, 1e-12);
  EXPECT_EQ(set.blocks[right[0]].vertices.size(), 4u);  // (5, 3) is a T-junction, not its corner
}

TEST(TreeCutting, BridgeBetweenTwoLoopsIsRemoved) {
  // Two closed triangles of joints joined by one joint, floating in the
  // square: the joining joint has the same block on both sides, so it goes;
  // the triangles stay as blocks and are cut free by the automatic cuts.
  CutInput in = square();
  in.lines = {line(1, 1, 4, 1), line(4, 1, 2.5, 3), line(2.5, 3, 1, 1), line(4, 1, 6, 1),
              line(6, 1, 9, 1), line(9, 1, 7.5, 3), line(7.5, 3, 6, 1)};
  in.inner_cut_material = 7;
  const BlockSet set = cut_blocks(in);
  expect_valid_partition(set, in);
  EXPECT_GT(set.stats.inner_cuts, 0);
  const auto tri = set.blocks_containing(Vec2(2.5, 1.5));
  ASSERT_EQ(tri.size(), 1u);
  EXPECT_NEAR(set.blocks[tri[0]].area, 0.5 * 3 * 2, 1e-12);
}

TEST(Outlines, TJunctionVerticesAreNotInsertedIntoTheLongEdge) {
  // Staggered bricks: the vertical joints of the two rows do not line up.
  CutInput in;
  in.domain = rectangle(0, 0, 4, 2);
  in.lines = {line(0, 1, 4, 1), line(1, 0, 1, 1), line(3, 0, 3, 1), line(2, 1, 2, 2)};
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 5u);
  for (const CutBlock& b : set.blocks) EXPECT_EQ(b.vertices.size(), 4u);
  expect_valid_partition(set, in);
  // Reading order: bottom row left to right, then the top row.
  EXPECT_NEAR(set.blocks[0].centroid.x(), 0.5, 1e-12);
  EXPECT_NEAR(set.blocks[1].centroid.x(), 2.0, 1e-12);
  EXPECT_NEAR(set.blocks[3].centroid.y(), 1.5, 1e-12);
}

TEST(Outlines, VertexStaysWhereTheEdgeTagChanges) {
  // A joint along the chamber's floor: the floor is hole boundary, the rest joint.
  CutInput in = square();
  in.holes = {rectangle(4, 4, 2, 2)};
  in.lines = {line(-1, 4, 11, 4, 3)};
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 2u);
  expect_valid_partition(set, in);
  const CutBlock& below = set.blocks[0];
  const CutBlock& above = set.blocks[1];
  EXPECT_EQ(below.vertices.size(), 6u);  // (4,4) and (6,4): joint meets hole boundary
  EXPECT_EQ(above.vertices.size(), 8u);
  int hole_edges = 0, joint_edges = 0;
  for (const EdgeTag& t : below.edges) {
    hole_edges += t.kind == EdgeKind::Hole;
    if (t.kind == EdgeKind::Joint) {
      ++joint_edges;
      EXPECT_EQ(t.joint_material, 3);
    }
  }
  EXPECT_EQ(hole_edges, 1);
  EXPECT_EQ(joint_edges, 2);
}

TEST(Outlines, JointsOnTheBoundaryBecomeBoundary) {
  CutInput in = square();
  in.lines = {line(0, 0, 10, 0, 5), line(0, 5, 10, 5, 5)};
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 2u);
  double boundary = 0;
  for (EdgeRef e : set.domain_boundary_edges()) boundary += set.edge_length(e);
  EXPECT_NEAR(boundary, 40.0, 1e-12);
}

TEST(MaterialRegions, CentroidPicksTheRegionAndTheLastRegionWins) {
  CutInput in;
  in.domain = rectangle(0, 0, 20, 1);
  in.sets = {persistent_set(0, 0.2), persistent_set(90, 0.2)};
  in.default_rock_material = 1;
  in.regions = {{rectangle(10, -1, 11, 3), 2}, {rectangle(15, -1, 6, 3), 3}};
  const BlockSet set = cut_blocks(in);
  int counts[4] = {0, 0, 0, 0};
  for (const CutBlock& b : set.blocks) {
    ++counts[b.rock_material];
    const int expected = b.centroid.x() > 15 ? 3 : b.centroid.x() > 10 ? 2 : 1;
    EXPECT_EQ(b.rock_material, expected);
  }
  EXPECT_EQ(counts[1], 250);
  EXPECT_EQ(counts[2], 125);
  EXPECT_EQ(counts[3], 125);
}

// ---- Slivers ------------------------------------------------------------------------

CutInput thin_layer() {
  CutInput in = square();
  in.lines = {line(-1, 5, 11, 5), line(-1, 5.0001, 11, 5.0001)};  // a 0.1 mm layer: 0.001 m²
  return in;
}

TEST(Slivers, KeptWhenAboveTheMinimumArea) {
  const BlockSet set = cut_blocks(thin_layer());
  EXPECT_EQ(set.blocks.size(), 3u);
  expect_valid_partition(set, thin_layer());
}

TEST(Slivers, MergedIntoANeighbour) {
  CutInput in = thin_layer();
  in.min_block_area = 0.01;
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 2u);
  EXPECT_EQ(set.stats.slivers_merged, 1);
  expect_valid_partition(set, in);
  for (const CutBlock& b : set.blocks) EXPECT_EQ(b.vertices.size(), 4u);
}

TEST(Slivers, MergedIntoTheNeighbourSharingTheLongestEdge) {
  // A thin wedge along the bottom of the left block: it shares 6 m with the
  // left block and 0.05 m with the right one.
  CutInput in = square();
  in.lines = {line(6, -1, 6, 11), line(-1, 0.05, 6, 0.05)};
  in.min_block_area = 0.5;
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 2u);
  const auto left = set.blocks_containing(Vec2(3, 5));
  ASSERT_EQ(left.size(), 1u);
  EXPECT_NEAR(set.blocks[left[0]].area, 60.0, 1e-12);
}

TEST(Slivers, ReportedUnderTheErrorPolicy) {
  CutInput in = thin_layer();
  in.min_block_area = 0.01;
  in.sliver_policy = SliverPolicy::Error;
  try {
    cut_blocks(in);
    FAIL() << "expected dda::Error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("smaller than the minimum block area"), std::string::npos) << m;
    EXPECT_NE(m.find("1 block(s)"), std::string::npos) << m;
    EXPECT_NE(m.find("area 0.000999"), std::string::npos) << m;
  }
}

// ---- Inner loops --------------------------------------------------------------------

TEST(InnerLoops, HoleWithoutJointsIsReported) {
  CutInput in = square();
  in.holes = {rectangle(4, 4, 2, 2)};
  try {
    cut_blocks(in);
    FAIL() << "expected dda::Error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("hole 1 is not reached by any joint"), std::string::npos) << m;
    EXPECT_NE(m.find("inner_cut_material"), std::string::npos) << m;
  }
}

TEST(InnerLoops, HoleCutFreeWithTheGivenMaterial) {
  CutInput in = square();
  in.holes = {rectangle(4, 4, 2, 2)};
  in.inner_cut_material = 9;
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 2u);
  EXPECT_EQ(set.stats.inner_cuts, 2);
  expect_valid_partition(set, in);
  int cut_edges = 0;
  for (const CutBlock& b : set.blocks)
    for (const EdgeTag& t : b.edges)
      if (t.kind == EdgeKind::Joint) {
        EXPECT_EQ(t.joint_material, 9);
        ++cut_edges;
      }
  EXPECT_EQ(cut_edges, 4);  // two cuts, each seen from both blocks
}

TEST(InnerLoops, IsolatedJointLoopIsReported) {
  CutInput in = square();
  in.lines = {line(1.5, 2, 8.5, 2), line(7.6, 1.4, 4.6, 7.4), line(5.4, 7.4, 2.4, 1.4)};
  try {
    cut_blocks(in);
    FAIL() << "expected dda::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("closed loop of joints"), std::string::npos) << e.what();
  }
  in.inner_cut_material = 0;
  const BlockSet set = cut_blocks(in);
  EXPECT_EQ(set.blocks.size(), 3u);  // the triangle and the square cut in two around it
  expect_valid_partition(set, in);
}

TEST(InnerLoops, LoopTouchingTheOthersAtOnePointIsReportedOrCut) {
  // A triangle of joints hanging from the joint y = 5 by its apex (3, 5):
  // the block below would pass twice through (3, 5).
  CutInput in = square();
  in.lines = {line(-1, 5, 11, 5), line(3, 5, 5.4, 1.4), line(5.5, 2, 0.5, 2), line(0.6, 1.4, 3, 5)};
  try {
    cut_blocks(in);
    FAIL() << "expected dda::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("only at that point"), std::string::npos) << e.what();
  }
  in.inner_cut_material = 4;
  const BlockSet set = cut_blocks(in);
  EXPECT_EQ(set.blocks.size(), 4u);  // above, the triangle, and the rock below cut in two
  EXPECT_EQ(set.stats.inner_cuts, 1);
  expect_valid_partition(set, in);
  const auto tri = set.blocks_containing(Vec2(3, 3));
  ASSERT_EQ(tri.size(), 1u);
  EXPECT_NEAR(set.blocks[tri[0]].area, 6.0, 1e-12);
}

TEST(InnerLoops, LoopHangingFromALoopIsCutFree) {
  // Triangle T1 hangs from the joint y = 5 at P = (6, 5); triangle T2 hangs
  // from T1 at Q = (2, 2). T1's extreme vertices (P right and up, Q left and
  // down) are all touching points, so its cut starts square to its longest side.
  CutInput in = square();
  const Vec2 p(6, 5), q(2, 2), r(5, 3.5), a(1, 1), b(2.5, 0.5);
  in.lines = {line(-1, 5, 11, 5), {p, q, 0}, {q, r, 0}, {r, p, 0}, {q, a, 0}, {a, b, 0}, {b, q, 0}};
  EXPECT_THROW(cut_blocks(in), Error);
  in.inner_cut_material = 1;
  const BlockSet set = cut_blocks(in);
  expect_valid_partition(set, in);
  EXPECT_EQ(set.stats.inner_cuts, 2);
  const auto t1 = set.blocks_containing((p + q + r) / 3);
  ASSERT_EQ(t1.size(), 1u);
  EXPECT_NEAR(set.blocks[t1[0]].area, 1.5, 1e-12);
}

// ---- Near-degenerate joints ----------------------------------------------------------

TEST(Robustness, NearlyCoincidentJointsAreOne) {
  CutInput in = square();
  in.lines = {line(-1, 5, 11, 5), line(-1, 5 + 1e-12, 11, 5 - 1e-12), line(0, 5, 10, 5)};
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 2u);
  expect_valid_partition(set, in);
}

TEST(Robustness, JointsThroughCornersAndOneCommonPoint) {
  CutInput in = square();
  for (int k = 0; k < 8; ++k) {
    const double a = k * 22.5 * 3.14159265358979323846 / 180.0;
    in.lines.push_back(line(5 - 20 * std::cos(a), 5 - 20 * std::sin(a), 5 + 20 * std::cos(a), 5 + 20 * std::sin(a)));
  }
  const BlockSet set = cut_blocks(in);
  EXPECT_EQ(set.blocks.size(), 16u);
  expect_valid_partition(set, in);
  // By symmetry the pieces come in two sizes: between 0° and 22.5° the
  // triangle (5,5), (10,5), (10, 5 + 5 tan 22.5°); between 22.5° and 45° the rest
  // of the 12.5 m² eighth.
  const double small = 0.5 * 5 * 5 * std::tan(22.5 * 3.14159265358979323846 / 180.0);
  for (const CutBlock& b : set.blocks) {
    const bool either = std::abs(b.area - small) < 1e-12 || std::abs(b.area - (12.5 - small)) < 1e-12;
    EXPECT_TRUE(either) << b.area;
  }
}

TEST(Robustness, NearlyParallelJointsCrossingAtATinyAngle) {
  CutInput in = square();
  in.lines = {line(0, 5, 10, 5), line(0, 5 - 1e-6, 10, 5 + 1e-6), line(0, 5 + 1e-3, 10, 5 - 1e-3)};
  const BlockSet set = cut_blocks(in);
  expect_valid_partition(set, in);
  EXPECT_NEAR(set.total_area(), 100.0, 1e-12 * 100);
}

TEST(Robustness, JointsEndingJustShortOfOrJustPastABoundary) {
  CutInput in = square();
  in.lines = {line(1e-11, 3, 10 - 1e-11, 3), line(-1e-11, 6, 10 + 1e-11, 6), line(5, 3 + 1e-11, 5, 6 - 1e-11)};
  const BlockSet set = cut_blocks(in);
  EXPECT_EQ(set.blocks.size(), 4u);
  expect_valid_partition(set, in);
}

TEST(Robustness, JointsCrossingJustOutsideACorner) {
  // Two joints cross 1.04 snap tolerances from the corner (10, 0), within one
  // tolerance of both sides: the crossing must snap onto the corner with them.
  CutInput in = square();
  const double tol = 1e-8;  // the default for a 10 m domain
  const Vec2 x(10 + 0.24 * tol, 0.98 * tol);
  in.lines = {{x - 6 * Vec2(-1, 2), x + 6 * Vec2(-1, 2), 0}, {x - 6 * Vec2(-2, 1), x + 6 * Vec2(-2, 1), 0}};
  const BlockSet set = cut_blocks(in);
  EXPECT_EQ(set.blocks.size(), 3u);
  expect_valid_partition(set, in, 1e-9);
  for (const CutBlock& b : set.blocks)
    for (const Vec2& v : b.vertices) EXPECT_TRUE(v.x() <= 10 && v.y() >= 0) << v.transpose();
}

// Random joints and near copies of them (offset by 1e-12 to 1e-6 m), lattice
// joints along the boundary, and joints through the domain's corners.
TEST(Robustness, RandomNearCopiesAlwaysTileTheDomain) {
  for (std::uint64_t seed = 500; seed < 650; ++seed) {
    SplitMix64 rng(seed);
    auto u = [&] { return rng.uniform(); };
    CutInput in;
    in.domain = seed % 2 ? rectangle(0, 0, 10, 10) : std::vector<Vec2>{Vec2(0, 0), Vec2(10, 0), Vec2(10, 4),
                                                                       Vec2(4, 4), Vec2(4, 10), Vec2(0, 10)};
    in.inner_cut_material = 0;
    in.min_block_area = seed % 3 == 0 ? 0.01 : 0.0;
    for (int k = 0; k < 30; ++k) {
      Vec2 a, b;
      const double mode = u();
      if (mode < 0.3) {
        a = Vec2(std::floor(u() * 11), std::floor(u() * 11));
        b = Vec2(std::floor(u() * 11), std::floor(u() * 11));
      } else if (mode < 0.55 && !in.lines.empty()) {
        const JointLine& l = in.lines[static_cast<std::size_t>(u() * in.lines.size())];
        const double e = std::pow(10.0, -12 + 6 * u());
        a = l.a + e * Vec2(u() - 0.5, u() - 0.5);
        b = l.b + e * Vec2(u() - 0.5, u() - 0.5);
      } else if (mode < 0.7) {
        const double angle = 6.283185307179586 * u();
        const Vec2 d(std::cos(angle), std::sin(angle));
        a = in.domain[static_cast<std::size_t>(u() * in.domain.size())] - 3 * d;
        b = a + 15 * d;
      } else {
        const Vec2 c(12 * u() - 1, 12 * u() - 1);
        const double angle = 6.283185307179586 * u(), len = 0.5 + 10 * u();
        const Vec2 d(std::cos(angle), std::sin(angle));
        a = c - 0.5 * len * d;
        b = c + 0.5 * len * d;
      }
      if ((a - b).norm() > 1e-6) in.lines.push_back({a, b, k % 3});
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    const BlockSet set = cut_blocks(in);
    // Snapping nearly coincident joints may move vertices by up to the
    // tolerance (1e-8 m here), which shifts the area sum by about that much.
    expect_valid_partition(set, in, 1e-8, 30);
  }
}

TEST(Robustness, ConcaveDomainWithHoleAndSets) {
  CutInput in;
  in.domain = {Vec2(0, 0), Vec2(30, 0), Vec2(30, 10), Vec2(12, 10), Vec2(12, 25), Vec2(0, 25)};
  in.holes = {{Vec2(3, 3), Vec2(8, 3), Vec2(8, 6), Vec2(5.5, 8), Vec2(3, 6)}};
  in.sets = {persistent_set(15, 1.3, Vec2(0.1, 0.2)), persistent_set(100, 0.9, Vec2(0.3, 0.1))};
  const BlockSet set = cut_blocks(in);
  expect_valid_partition(set, in, 1e-12, 60);
}

// Random joints whose end points come from a coarse lattice, so many of them
// overlap, meet at common points or pass through each other's ends: the cases
// a floating-point arrangement gets wrong.
TEST(Robustness, RandomLatticeJointsAlwaysTileTheDomain) {
  for (std::uint64_t seed = 1; seed <= 150; ++seed) {
    SplitMix64 rng(seed);
    CutInput in;
    in.domain = {Vec2(0, 0), Vec2(8, 0), Vec2(8, 4), Vec2(4, 4), Vec2(4, 8), Vec2(0, 8)};
    if (seed % 2 == 0) in.holes = {rectangle(1, 1, 1.5, 1.5)};
    in.inner_cut_material = 0;
    in.min_block_area = seed % 3 == 0 ? 0.05 : 0.0;
    auto lattice = [&] {
      return Vec2(std::floor(rng.uniform() * 9) - 0.5 * (seed % 5 == 0), std::floor(rng.uniform() * 9));
    };
    for (int k = 0; k < 25; ++k) {
      Vec2 a = lattice(), b = lattice();
      if ((a - b).norm() < 1e-9) continue;
      in.lines.push_back({a, b, k % 3});
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    const BlockSet set = cut_blocks(in);
    expect_valid_partition(set, in, 1e-12, 30);
    for (const CutBlock& b : set.blocks) {
      EXPECT_GE(b.area, in.min_block_area);
    }
  }
}

TEST(Robustness, RandomJointsAtRandomAnglesAlwaysTileTheDomain) {
  for (std::uint64_t seed = 100; seed < 200; ++seed) {
    SplitMix64 rng(seed);
    CutInput in = square();
    in.holes = {{Vec2(6, 6), Vec2(8, 6.5), Vec2(7, 8)}};
    in.inner_cut_material = 0;
    for (int k = 0; k < 40; ++k) {
      const Vec2 c(12 * rng.uniform() - 1, 12 * rng.uniform() - 1);
      const double angle = 6.283185307179586 * rng.uniform(), len = 1 + 8 * rng.uniform();
      const Vec2 d(std::cos(angle), std::sin(angle));
      in.lines.push_back({c - 0.5 * len * d, c + 0.5 * len * d, 0});
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    const BlockSet set = cut_blocks(in);
    expect_valid_partition(set, in, 1e-12, 30);
  }
}

// ---- Bad input ------------------------------------------------------------------------

void expect_error(const CutInput& in, std::initializer_list<const char*> parts) {
  try {
    cut_blocks(in);
    ADD_FAILURE() << "expected dda::Error mentioning " << *parts.begin();
  } catch (const Error& e) {
    const std::string m = e.what();
    for (const char* p : parts) EXPECT_NE(m.find(p), std::string::npos) << "message: " << m;
  }
}

TEST(BadInput, SelfIntersectingDomain) {
  CutInput in;
  in.domain = {Vec2(0, 0), Vec2(10, 10), Vec2(10, 0), Vec2(0, 10)};  // a bow tie
  expect_error(in, {"domain", "self-intersecting"});
}

TEST(BadInput, DomainWithNaNOrTooFewVertices) {
  CutInput in = square();
  in.domain[2].x() = std::numeric_limits<double>::quiet_NaN();
  expect_error(in, {"domain", "non-finite"});
  in.domain = {Vec2(0, 0), Vec2(1, 1)};
  expect_error(in, {"domain", "at least 3 vertices"});
  in.domain.clear();
  expect_error(in, {"domain"});
}

TEST(BadInput, HoleOutsideTheDomain) {
  CutInput in = square();
  in.holes = {rectangle(20, 20, 2, 2)};
  expect_error(in, {"hole 1", "outside the domain"});
}

TEST(BadInput, HoleCrossingOrTouchingTheBoundary) {
  CutInput in;
  in.domain = {Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(5, 2), Vec2(0, 10)};  // a notch from the top
  in.holes = {rectangle(3, 3, 4, 1)};  // all corners inside, but the notch tip pokes through it
  expect_error(in, {"hole 1", "domain boundary"});
  in.domain = rectangle(0, 0, 10, 10);
  in.holes = {rectangle(0, 4, 2, 2)};
  expect_error(in, {"hole 1", "domain boundary"});
}

TEST(BadInput, OverlappingHoles) {
  CutInput in = square();
  in.holes = {rectangle(2, 2, 3, 3), rectangle(4, 4, 3, 3)};
  expect_error(in, {"holes 1 and 2"});
  in.holes = {rectangle(2, 2, 6, 6), rectangle(4, 4, 1, 1)};
  expect_error(in, {"holes 1 and 2", "inside"});
}

TEST(BadInput, ZeroNegativeOrNaNSpacing) {
  CutInput in = square();
  in.sets = {persistent_set(0, 1), persistent_set(90, 0)};
  expect_error(in, {"joint set 2", "spacing"});
  in.sets[1].spacing = -1;
  expect_error(in, {"joint set 2", "spacing"});
  in.sets[1].spacing = std::numeric_limits<double>::quiet_NaN();
  expect_error(in, {"joint set 2", "spacing"});
  in.sets[1].spacing = 1e-9;  // a billion lines: refused, not attempted
  expect_error(in, {"joint set 2", "would make about"});
}

TEST(BadInput, SetsTooDenseToCutAreRefusedAtOnce) {
  // 40,000 joints per set: about 1.6e9 blocks. Refused before any cutting.
  CutInput in = square(100);
  in.sets = {persistent_set(30, 0.0025), persistent_set(100, 0.0025)};
  expect_error(in, {"joint sets 1 and 2", "would cross about"});
}

TEST(BadInput, NaNOrInfiniteAngle) {
  CutInput in = square();
  in.sets = {persistent_set(std::numeric_limits<double>::quiet_NaN(), 1)};
  expect_error(in, {"joint set 1", "dip"});
  in.sets = {persistent_set(std::numeric_limits<double>::infinity(), 1)};
  expect_error(in, {"joint set 1", "dip"});
}

TEST(BadInput, OtherSetFieldsLinesAndOptions) {
  CutInput in = square();
  in.sets = {persistent_set(0, 1)};
  in.sets[0].origin.x() = std::numeric_limits<double>::infinity();
  expect_error(in, {"joint set 1", "origin"});
  in.sets = {persistent_set(0, 1)};
  in.sets[0].trace_length = -2;
  expect_error(in, {"joint set 1", "trace length"});
  in.sets[0].trace_length = 0;
  in.sets[0].bridge_length = 1;
  expect_error(in, {"joint set 1", "bridge length needs a trace length"});
  in.sets = {};
  in.lines = {line(1, 1, 1, 1)};
  expect_error(in, {"joint line 1", "zero length"});
  in.lines = {line(1, 1, 2, std::numeric_limits<double>::quiet_NaN())};
  expect_error(in, {"joint line 1", "non-finite"});
  in.lines = {};
  in.min_block_area = std::numeric_limits<double>::quiet_NaN();
  expect_error(in, {"minimum block area"});
  in.min_block_area = 0;
  in.snap_tolerance = 5;
  expect_error(in, {"snap tolerance"});
  in.snap_tolerance = 0;
  in.regions = {{{Vec2(0, 0), Vec2(1, 1), Vec2(1, 0), Vec2(0, 1)}, 1}};
  expect_error(in, {"material region 1", "self-intersecting"});
}

}  // namespace
}  // namespace dda::geometry::test
