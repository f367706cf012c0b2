// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The example scripts in scripts/ run through `dda run` (short versions), and
// their CSV outputs are checked against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "script_helpers.hpp"

using namespace dda::test;

namespace {

std::string script(const std::string& name) { return quote((source_dir() / "scripts" / name).string()); }

}  // namespace

// Free fall: DDA's integrator is exact for constant acceleration, so the
// drop is 1/2 g t^2 and the velocity −g t to round-off.
TEST(ExampleScripts, FreeFallMatchesHalfGTSquared) {
  TempDir dir("free_fall");
  const auto r = run_dda("run " + script("free_fall.lua") + " --quiet --out out --set t_end=0.5", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(dir / "out/free_fall.csv");
  ASSERT_TRUE(csv.complete);
  ASSERT_EQ(csv.header, (std::vector<std::string>{"step", "time", "uy", "vy"}));
  ASSERT_EQ(csv.rows.size(), 51u);  // step 0 and 50 steps of 0.01 s
  const double g = 9.81;
  for (const auto& row : csv.rows) {
    const double t = row[1];
    EXPECT_NEAR(-row[2], 0.5 * g * t * t, 1e-9 * std::max(1.0, 0.5 * g * t * t)) << "t = " << t;
    EXPECT_NEAR(-row[3], g * t, 1e-9 * std::max(1.0, g * t)) << "t = " << t;
  }
  EXPECT_NEAR(csv.rows.back()[1], 0.5, 1e-12);
}

// Incline: alpha = 30 deg, phi = 20 deg slides with a = g (sin a − cos a tan phi)
// = 1.81281 m/s^2; the distance slid after t is 1/2 a t^2 (within 1 %).
TEST(ExampleScripts, InclineSlidesWithTheFrictionAcceleration) {
  TempDir dir("incline");
  const auto r = run_dda("run " + script("incline.lua") + " --quiet --out out --set t_end=0.5", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(dir / "out/incline.csv");
  ASSERT_TRUE(csv.complete);
  ASSERT_EQ(csv.header, (std::vector<std::string>{"step", "time", "ux", "uy", "vx", "vy"}));
  const double a = 9.81 * (std::sin(M_PI / 6) - std::cos(M_PI / 6) * std::tan(M_PI / 9));
  EXPECT_NEAR(a, 1.81281, 1e-5);
  const auto& last = csv.rows.back();
  const double t = last[1];
  EXPECT_NEAR(t, 0.5, 1e-9);
  const double slid = -(last[2] * std::cos(M_PI / 6) + last[3] * std::sin(M_PI / 6));
  EXPECT_NEAR(2 * slid / (t * t), a, 0.01 * a);
  const double speed = -(last[4] * std::cos(M_PI / 6) + last[5] * std::sin(M_PI / 6));
  EXPECT_NEAR(speed / t, a, 0.01 * a);
}

// With phi = 35 deg > alpha the block stays put.
TEST(ExampleScripts, InclineWithHighFrictionStaysPut) {
  TempDir dir("incline35");
  const auto r = run_dda("run " + script("incline.lua") + " --quiet --out out --set t_end=0.5 --set phi=35", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(dir / "out/incline.csv");
  ASSERT_TRUE(csv.complete);
  const auto& last = csv.rows.back();
  EXPECT_LT(std::hypot(last[2], last[3]), 1e-5);
}

// The main example, a short run: one CSV row per step, time advancing by g1.
TEST(ExampleScripts, RockBarShortRunWritesTheCentreHistory) {
  TempDir dir("rock_bar");
  const auto r = run_dda("run " + script("rock_bar.lua") + " --quiet --out out --set t_end=2e-5", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("500 blocks"), std::string::npos) << r.out;
  const Csv csv = read_csv(dir / "out/rock_bar_centre.csv");
  ASSERT_TRUE(csv.complete);
  ASSERT_EQ(csv.header, (std::vector<std::string>{"step", "time", "sxx", "vx"}));
  ASSERT_EQ(csv.rows.size(), 11u);
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    EXPECT_EQ(csv.rows[i][0], double(i));
    EXPECT_NEAR(csv.rows[i][1], 2e-6 * double(i), 1e-15);
    // The wave has not reached the centre yet (10 m at 5000 m/s takes 2 ms).
    EXPECT_LT(std::fabs(csv.rows[i][2]), 1e3);
  }
}

// Models 1-6 of the paper: block counts that follow from the geometry.
TEST(ExampleScripts, PaperBarGeometries) {
  TempDir dir("geometry");
  const auto r = run_dda("run " + script("paper/geometry_models.lua") + " --quiet --out out", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(dir / "out/paper_geometry.csv");
  ASSERT_TRUE(csv.complete);
  ASSERT_EQ(csv.rows.size(), 6u);
  const int blocks = csv.column("blocks"), area = csv.column("area"), left = csv.column("left_edges"),
            right = csv.column("right_edges"), right_length = csv.column("right_length");
  for (const auto& row : csv.rows) {
    EXPECT_NEAR(row[area], 20.0, 1e-9) << "model " << row[0];
    EXPECT_NEAR(row[right_length],
                row[0] == 5   ? 1 / std::sin(M_PI / 3)
                : row[0] == 6 ? 2.0
                              : 1.0,
                1e-8)
        << "model " << row[0];
  }
  EXPECT_EQ(csv.rows[0][blocks], 500);  // Model 1: 100 x 5 squares
  EXPECT_EQ(csv.rows[0][left], 5);
  EXPECT_EQ(csv.rows[0][right], 5);
  EXPECT_EQ(csv.rows[3][blocks], 498);  // Model 4: 99 x 5 + 3
  EXPECT_EQ(csv.rows[3][right], 3);
}

// Section 4: 100 m square, sets at 45 and 135 deg, 2 m spacing, 8 x 4 m chamber.
TEST(ExampleScripts, BlastGeometry) {
  TempDir dir("blast");
  const auto r = run_dda("run " + script("paper/blast_geometry.lua") + " --quiet --out out", dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv csv = read_csv(dir / "out/blast_geometry.csv");
  ASSERT_TRUE(csv.complete);
  ASSERT_EQ(csv.rows.size(), 1u);
  const auto& row = csv.rows[0];
  EXPECT_EQ(row[csv.column("size")], 100);
  EXPECT_NEAR(row[csv.column("area")], 100.0 * 100.0 - 8 * 4, 1e-6);
  EXPECT_NEAR(row[csv.column("chamber_wall_length")], 24, 1e-9);
  EXPECT_GT(row[csv.column("blocks")], 2400);  // about 10000 m^2 / 4 m^2 per diamond
  EXPECT_GE(row[csv.column("mp1_block")], 0);
  EXPECT_GE(row[csv.column("mp2_block")], 0);
  EXPECT_GE(row[csv.column("mp3_block")], 0);
}
