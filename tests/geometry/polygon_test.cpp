// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// validate_simple_polygon on outlines the block cutter produces: a block whose
// side along a joint is interrupted by a notch has two collinear edges, and
// on an inclined joint their collinearity holds only to rounding. Those must
// pass, and real crossings and touches must still fail.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace dda {
namespace {

// A "U": the top side y = 2 is split by a notch between x = 1 and x = 3, so
// edges (0,2)-(1,2) and (3,2)-(4,2) are collinear. Turned by `angle` about the
// origin, the collinearity is only approximate.
std::vector<Vec2> turned_u(double angle) {
  const std::vector<Vec2> u = {Vec2(0, 0), Vec2(4, 0), Vec2(4, 2), Vec2(3, 2),
                               Vec2(3, 1), Vec2(1, 1), Vec2(1, 2), Vec2(0, 2)};
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Vec2> out;
  for (const Vec2& p : u) out.push_back(Vec2(c * p.x() - s * p.y() + 7.3, s * p.x() + c * p.y() - 2.1));
  return out;
}

TEST(ValidateSimplePolygon, CollinearEdgesOfANotchedOutlinePassAtAnyAngle) {
  for (int k = 0; k < 2000; ++k) {
    const double angle = 0.0031 * k;
    EXPECT_NO_THROW(validate_simple_polygon(turned_u(angle), "notched block")) << "angle " << angle;
  }
}

// A block found by the randomised cutting tests: a deep, narrow notch whose
// mouth (3.7e-8 m wide) separates two collinear pieces of one joint, edges 2
// and 5. In exact arithmetic they do not cross (checked with rationals), but
// the floating-point orientation signs say they do.
TEST(ValidateSimplePolygon, NarrowNotchBetweenCollinearEdgesPasses) {
  const std::vector<Vec2> block = {Vec2(6.833333333333333, 3.7222222222222223),
                                   Vec2(6.7472793425277882, 3.7509068858240706),
                                   Vec2(5.0000000237545059, 1.7221081552786792),
                                   Vec2(5, 1.3408038829311422),
                                   Vec2(5, 1.7221081276968777),
                                   Vec2(4.3561590595187933, 0.9745323573624094),
                                   Vec2(5.2034214220412691, 0.27786297378714386),
                                   Vec2(6.8656039598678351, 3.6469240936417187)};
  EXPECT_TRUE(segments_cross_properly(block[1], block[2], block[4], block[5]));  // the false alarm
  EXPECT_NO_THROW(validate_simple_polygon(block, "notched block"));
}

TEST(ValidateSimplePolygon, CrossingsAndTouchesStillFail) {
  const std::vector<Vec2> bow_tie = {Vec2(0, 0), Vec2(4, 3), Vec2(4, 0), Vec2(0, 2)};
  EXPECT_THROW(validate_simple_polygon(bow_tie, "bow tie"), Error);
  // The notch closed up: its inner corner touches the opposite side.
  std::vector<Vec2> touching = {Vec2(0, 0), Vec2(4, 0), Vec2(4, 2), Vec2(2, 2), Vec2(2, 0.0), Vec2(1, 2), Vec2(0, 2)};
  EXPECT_THROW(validate_simple_polygon(touching, "touching"), Error);
  // Two edges crossing at a tiny angle near an end point.
  const std::vector<Vec2> thin = {Vec2(0, 0), Vec2(10, 1e-9), Vec2(10, 1), Vec2(5, -1e-6), Vec2(0, 1)};
  EXPECT_THROW(validate_simple_polygon(thin, "thin"), Error);
}

TEST(SegmentsCrossClearly, NeedsEveryEndPointOffTheOtherLine) {
  EXPECT_TRUE(segments_cross_clearly(Vec2(0, 0), Vec2(2, 2), Vec2(0, 2), Vec2(2, 0), 1e-9));
  EXPECT_FALSE(segments_cross_clearly(Vec2(0, 0), Vec2(2, 2), Vec2(1, 1), Vec2(2, 0), 1e-9));  // T-junction
  EXPECT_FALSE(segments_cross_clearly(Vec2(0, 0), Vec2(1, 0), Vec2(2, 1e-17), Vec2(3, -1e-17), 1e-12));
  EXPECT_TRUE(segments_cross_properly(Vec2(0, 0), Vec2(2, 2), Vec2(0, 2), Vec2(2, 0)));
}

}  // namespace
}  // namespace dda
