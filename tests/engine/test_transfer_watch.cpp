// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The transfer watch (contact/transfer_watch.hpp) skips the contact-transfer
// tests (passed_corner, slid_past_end, aligned_edges_slid) while the blocks
// have not moved by a test's slack. Reference: the tests themselves. A
// skipped test must be one that would have answered false, exactly (no
// tolerance: the steps are then bit for bit those of testing every contact
// every step), and the slack must not be vacuous (else the watch saves
// nothing).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "contact/narrow_phase.hpp"
#include "contact/transfer_watch.hpp"

using namespace dda;

namespace {

// Two blocks: a rectangle B (the edge's block; its top edge, edge 2, runs
// from (l, 0) to (0, 0)... counter-clockwise: (0,-1), (l,-1), (l,0), (0,0))
// and a quadrilateral A whose first vertex touches B's top edge at `along`,
// `depth` behind it, its outline tilted by `tilt`.
struct Pair {
  std::vector<int> start{0, 4, 8};
  std::vector<Vec2> vertices;
  BlockPolygons polygons() const { return {start, vertices}; }
};

Pair pair_at(double l, double along, double depth, double tilt, double width) {
  Pair p;
  p.vertices = {{0, -1}, {l, -1}, {l, 0}, {0, 0}};
  const Vec2 v(l - along, -depth);  // edge 2 runs from (l, 0) towards (0, 0)
  const Vec2 u(std::cos(tilt), std::sin(tilt)), up(-u.y(), u.x());
  p.vertices.insert(p.vertices.end(), {v, v + width * u, v + width * u + up, v + up});
  return p;
}

Contact contact_of_pair() {
  Contact c;
  c.vblock = 1, c.vertex = 0, c.eblock = 0, c.edge = 2;
  return c;
}

// Moves every vertex by at most `reach`: each block as a whole (half the
// time) or each vertex on its own, along one of the directions that matter
// most (along or across the edge, either way) or a random one.
void shake(std::vector<Vec2>& vertices, double reach, std::mt19937& rng) {
  std::uniform_int_distribution<int> pick(0, 4);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), size(0.9, 1.0);
  const Vec2 directions[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  auto direction = [&] {
    const int k = pick(rng);
    const double a = angle(rng);
    return k < 4 ? directions[k] : Vec2(std::cos(a), std::sin(a));
  };
  const bool whole = pick(rng) < 2;
  Vec2 block_move = reach * size(rng) * direction();
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    if (whole && v % 4 == 0) block_move = reach * size(rng) * direction();  // 4 vertices a block
    vertices[v] += whole ? block_move : reach * size(rng) * direction();
  }
}

// One configuration of a test (`is_true`, of the outlines) with its slack:
// 0 where the test is true; otherwise no shake by the slack makes it true.
// Returns whether the configuration had slack.
template <class Test>
bool check_slack(const Pair& p, double slack, std::mt19937& rng, Test is_true) {
  if (is_true(p.polygons())) {
    EXPECT_EQ(slack, 0);
    return false;
  }
  if (slack == 0) return false;
  for (int move = 0; move < 20; ++move) {
    Pair q = p;
    shake(q.vertices, slack, rng);
    if (is_true(q.polygons())) {
      ADD_FAILURE() << "a shake by the slack " << slack << " turned the test true";
      return false;
    }
  }
  return true;
}

}  // namespace

// Contacts near every threshold of the two tests (a vertex just inside or
// past an end, just above or below the corner margin, on an edge 1 m or
// 1 mm long, far from the origin): no motion within the slack turns a test
// true.
TEST(TransferWatch, NoMotionWithinTheSlackTurnsATransferTestTrue) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> along(-0.08, 1.08), depth(-0.01, 0.003), tilt(-0.5, 0.5), width(0.02, 2);
  int tested = 0;
  for (const double l : {1.0, 1e-3})
    for (const double x0 : {0.0, 1e4})
      for (int trial = 0; trial < 4000; ++trial) {
        Pair p = pair_at(l, along(rng) * l, depth(rng) * l, tilt(rng), width(rng) * l);
        for (Vec2& v : p.vertices) v.x() += x0;
        const Contact c = contact_of_pair();
        SCOPED_TRACE(testing::Message() << "l " << l << " x0 " << x0 << " trial " << trial);
        tested += check_slack(p, transfer_slack(p.polygons(), c), rng, [&](const BlockPolygons& polys) {
          return passed_corner(polys, c) || slid_past_end(polys, c);
        });
        if (HasFailure()) return;
      }
  EXPECT_GT(tested, 4000);  // most contacts have slack
}

// A resting contact (a vertex on the middle of its edge) may move a good
// part of the corner margin before it is tested again.
TEST(TransferWatch, ARestingContactHasSlackOfTheCornerMargin) {
  const Pair p = pair_at(2, 1, 1e-6, 0, 2);
  const double slack = transfer_slack(p.polygons(), contact_of_pair());
  EXPECT_GT(slack, 0.02 * kCornerMargin * 2);
  EXPECT_LT(slack, kCornerMargin * 2);
}

// Aligned edges (B's top edge and A's bottom edge meeting end to end, near
// the slide that makes a search): no motion within the slack makes them
// slide.
TEST(TransferWatch, NoMotionWithinTheSlackSlidesAlignedEdges) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> gap(-0.06, 0.02), lift(-1e-3, 1e-3), since(-0.008, 0.002);
  int tested = 0;
  for (const double l : {1.0, 1e-3})
    for (int trial = 0; trial < 4000; ++trial) {
      // A: a square of side l whose bottom-left corner is `gap` right of B's
      // top-right corner (negative: the edges overlap by -gap).
      Pair p = pair_at(l, 0, 0, 0, l);
      const Vec2 shift(gap(rng) * l, lift(rng) * l);
      for (Vec2& v : std::span(p.vertices).subspan(4)) v += shift;
      // The shared length at the search: now's, less up to 0.8 % of the edge
      // (they slide when it grew by kAlignedSlide of the tie, 0.5 %).
      const AlignedEdges e{0, 2, 1, 0, -shift.x() + since(rng) * l};
      SCOPED_TRACE(testing::Message() << "l " << l << " trial " << trial);
      tested += check_slack(p, aligned_slack(p.polygons(), e), rng,
                            [&](const BlockPolygons& polys) { return aligned_edges_slid(polys, e); });
      if (HasFailure()) return;
    }
  EXPECT_GT(tested, 2000);
}

// The watch against testing everything: a block A that drifts along another,
// B (0.2 mm a step, every vertex jittered by 20 µm), slides past a third
// block C, whose top edge meets A's bottom edge end to end, and then off B's
// end. At every check the watch answers as the exact tests over the whole
// lists do.
TEST(TransferWatch, AnswersAsTestingEveryContactEveryStep) {
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0, 2e-5);
  const std::vector<int> start{0, 4, 8, 12};
  std::vector<Vec2> vertices = pair_at(1, 0.5, 1e-6, 0, 0.3).vertices;      // B, then A on B from x = 0.5 to 0.8
  vertices.insert(vertices.end(), {{1.2, -1}, {2, -1}, {2, 0}, {1.2, 0}});  // C, its top edge from x = 2 to 1.2
  const std::vector<Contact> contacts{contact_of_pair()};
  const std::vector<AlignedEdges> aligned{{1, 0, 2, 2, -0.4}};
  TransferWatch watch;
  int left = 0, slid = 0;
  for (int step = 0; step < 4000; ++step) {
    for (int v = 4; v < 8; ++v) vertices[v] += Vec2(2e-4 + jitter(rng), jitter(rng));
    for (int v : {0, 1, 2, 3, 8, 9, 10, 11}) vertices[v] += Vec2(jitter(rng), jitter(rng));
    const BlockPolygons polys{start, vertices};
    watch.follow(polys);
    const bool exact_left = passed_corner(polys, contacts[0]) || slid_past_end(polys, contacts[0]);
    const bool exact_slid = aligned_edges_slid(polys, aligned[0]);
    ASSERT_EQ(watch.left_an_edge(polys, contacts), exact_left) << "step " << step;
    ASSERT_EQ(watch.aligned_slid(polys, aligned), exact_slid) << "step " << step;
    left += exact_left, slid += exact_slid;
  }
  EXPECT_GT(slid, 0);  // A's edge did slide along C's
  EXPECT_GT(left, 0);  // and A's corner off B's end
}
