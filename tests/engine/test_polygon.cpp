// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Polygon integrals against closed forms; validation of bad outlines.
#include <gtest/gtest.h>

#include "../scenes.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"

using namespace dda;

TEST(Polygon, RectangleMomentsMatchClosedForm) {
  // b × h rectangle: A = bh, centroid at the middle, Ixx = b³h/12 about it.
  const double b = 3, h = 2;
  const auto pm = polygon_moments(test::rectangle(10, 20, b, h));
  EXPECT_NEAR(pm.area, b * h, 1e-12);
  EXPECT_NEAR(pm.centroid.x(), 11.5, 1e-12);
  EXPECT_NEAR(pm.centroid.y(), 21.0, 1e-12);
  EXPECT_NEAR(pm.sxx, b * b * b * h / 12, 1e-11);
  EXPECT_NEAR(pm.syy, b * h * h * h / 12, 1e-11);
  EXPECT_NEAR(pm.sxy, 0, 1e-11);
}

TEST(Polygon, TriangleMomentsMatchClosedForm) {
  // Right triangle (0,0), (b,0), (0,h): A = bh/2, centroid (b/3, h/3),
  // ∫x² about centroid = b³h/36, ∫y² = bh³/36, ∫xy = -b²h²/72.
  const double b = 4, h = 3;
  const std::vector<Vec2> tri = {{0, 0}, {b, 0}, {0, h}};
  const auto pm = polygon_moments(tri);
  EXPECT_NEAR(pm.area, b * h / 2, 1e-12);
  EXPECT_NEAR(pm.centroid.x(), b / 3, 1e-12);
  EXPECT_NEAR(pm.centroid.y(), h / 3, 1e-12);
  EXPECT_NEAR(pm.sxx, b * b * b * h / 36, 1e-12);
  EXPECT_NEAR(pm.syy, b * h * h * h / 36, 1e-12);
  EXPECT_NEAR(pm.sxy, -b * b * h * h / 72, 1e-12);
}

TEST(Polygon, ConcaveLShapeMomentsMatchDecomposition) {
  // L = 2×1 rectangle at the bottom + 1×1 square on its left end.
  const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto pm = polygon_moments(l);
  // Parts: R1 = [0,2]×[0,1] (A=2, c=(1,.5)), R2 = [0,1]×[1,2] (A=1, c=(.5,1.5)).
  const double a = 3, cx = (2 * 1 + 1 * 0.5) / a, cy = (2 * 0.5 + 1 * 1.5) / a;
  const double ixx = (8.0 / 12 + 2 * (1 - cx) * (1 - cx)) + (1.0 / 12 + 1 * (0.5 - cx) * (0.5 - cx));
  const double iyy = (2.0 / 12 + 2 * (0.5 - cy) * (0.5 - cy)) + (1.0 / 12 + 1 * (1.5 - cy) * (1.5 - cy));
  const double ixy = 2 * (1 - cx) * (0.5 - cy) + 1 * (0.5 - cx) * (1.5 - cy);
  EXPECT_NEAR(pm.area, a, 1e-12);
  EXPECT_NEAR(pm.centroid.x(), cx, 1e-12);
  EXPECT_NEAR(pm.centroid.y(), cy, 1e-12);
  EXPECT_NEAR(pm.sxx, ixx, 1e-12);
  EXPECT_NEAR(pm.syy, iyy, 1e-12);
  EXPECT_NEAR(pm.sxy, ixy, 1e-12);
}

TEST(Polygon, ClockwiseOutlineGivesNegativeAreaButPositiveMoments) {
  auto r = test::rectangle(0, 0, 2, 1);
  std::reverse(r.begin(), r.end());
  const auto pm = polygon_moments(r);
  EXPECT_NEAR(pm.area, -2, 1e-12);
  EXPECT_NEAR(pm.sxx, 8.0 / 12, 1e-12);
}

TEST(Polygon, MomentsFarFromOriginKeepTheirDigits) {
  // Exactly representable coordinates: the shoelace sum about the origin would
  // cancel ~1e12-sized products and lose every digit of the 0.0625 m² area.
  const auto pm = polygon_moments(test::rectangle(1e6 + 0.25, -2e6, 0.25, 0.25));
  EXPECT_NEAR(pm.area, 0.0625, 1e-15);
  EXPECT_NEAR(pm.sxx, 0.25 * 0.25 * 0.25 * 0.25 / 12, 1e-15);
}

static std::string error_of(const std::vector<Vec2>& v) {
  try {
    validate_simple_polygon(v, "block 7");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Polygon, DegenerateOutlinesAreRejectedWithTheCause) {
  EXPECT_NE(error_of({{0, 0}, {1, 0}}).find("at least 3 vertices"), std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {1, 0}, {2, 0}}).find("zero area"), std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {1, 0}, {1, 0}, {0, 1}}).find("repeated"), std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {4, 0}, {4, 4}, {1, -1}}).find("self-intersecting"), std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {NAN, 0}, {0, 1}}).find("non-finite"), std::string::npos);
  EXPECT_EQ(error_of({{0, 0}, {1, 0}, {1, 1}}), "");
}
