// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Inputs the fuzz targets (fuzz/, docs/robustness.md, "Fuzzing") found crashing or
// tripping a sanitizer, kept as plain tests: each must now be cut, or
// refused with a dda::Error naming the item.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "cutting_support.hpp"

using namespace dda;
using namespace dda::geometry;

namespace {

std::string error_of(const CutInput& in) {
  try {
    cut_blocks(in);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

CutInput unit_square() {
  CutInput in;
  in.domain = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  return in;
}

// dda_fuzz_geometry: a joint set whose origin lies at 1.2e308 overflowed the
// line numbers (double → long long, UBSan: outside the range of long long).
TEST(FuzzRegression, JointSetOriginFarFromTheDomainIsRefused) {
  for (double x : {1.2e308, 1e20, -1e17}) {
    CutInput in = unit_square();
    in.sets.push_back(geometry::test::persistent_set(0, 0.25, Vec2(0, x)));
    EXPECT_NE(error_of(in).find("joint set 1: its origin lies about"), std::string::npos) << x << ": " << error_of(in);
  }
  CutInput near = unit_square();
  near.sets.push_back(geometry::test::persistent_set(0, 0.25, Vec2(0, 1e6)));  // far, but the line numbers are exact
  EXPECT_EQ(cut_blocks(near).blocks.size(), 4u);
}

// dda_fuzz_geometry: a non-persistent set whose origin lies at x = -1.8e308
// along its joints hung laying traces (t + period == t never reached the box).
TEST(FuzzRegression, NonPersistentSetOriginFarAlongItsJointsIsRefused) {
  CutInput in;
  in.domain = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  JointSet s = geometry::test::persistent_set(0, 1.25, Vec2(-1.7976931348623027e+308, 2), 1);
  s.trace_length = 0.86986831568412226;
  s.bridge_length = 2.6791512940408211;
  s.seed = 781548;
  in.sets.push_back(s);
  EXPECT_NE(error_of(in).find("joint set 1: its origin lies about"), std::string::npos) << error_of(in);
  in.sets[0].origin = Vec2(-1e6, 2);  // far, but positions stay exact: it cuts
  EXPECT_NO_THROW(cut_blocks(in));
}

// dda_fuzz_geometry: an explicit joint reaching to x = -1.6e308 overflowed
// the arrangement's cell numbers (UBSan: -inf outside the range of long).
// Its far part lies outside the domain and is dropped: it ends inside the
// rock, so it cuts nothing.
TEST(FuzzRegression, JointLineReachingFarOutIsClipped) {
  CutInput in;
  in.domain = {{-2, -2}, {2, -2}, {2, -0.5}, {-2, -0.5}};
  in.lines.push_back({Vec2(-0.5, -1.5), Vec2(-1.6496300525252463e+308, -2), 1});
  in.sliver_policy = SliverPolicy::Error;
  const BlockSet set = cut_blocks(in);
  ASSERT_EQ(set.blocks.size(), 1u);
  EXPECT_NEAR(set.blocks[0].area, 6.0, 1e-12);  // exact: 4 m × 1.5 m

  // Crossing the domain, from far left to far right: two blocks of 3 m².
  in.lines = {{Vec2(-1e300, -1.25), Vec2(1e300, -1.25), 1}};
  const BlockSet two = cut_blocks(in);
  ASSERT_EQ(two.blocks.size(), 2u);
  EXPECT_NEAR(two.blocks[0].area, 3.0, 1e-12);
  EXPECT_NEAR(two.blocks[1].area, 3.0, 1e-12);

  in.lines = {{Vec2(-1e308, -1.25), Vec2(1e308, -1.25), 1}};  // b - a overflows
  EXPECT_NE(error_of(in).find("joint line 1: end points"), std::string::npos) << error_of(in);
}

}  // namespace
