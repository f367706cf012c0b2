// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Earthquake input: reading accelerograms, resampling, baseline correction
// and integration (engine/loading/ground_motion.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "../source_dir.hpp"
#include "core/error.hpp"
#include "loading/ground_motion.hpp"

using namespace dda;

namespace {
const std::string kElCentro = std::string(DDA_SOURCE_DIR) + "/data/imperial_valley_1979_el_centro_array7_S50W.dat";

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}
}  // namespace

TEST(GroundMotion, ElCentroArray7PeaksMatchTheHeaderAfterBaselineCorrection) {
  // Reference: the record's own header (data/README.md): PGA 450.322 cm/s²
  // at 4.98 s, PGV 112.543 cm/s at 5.92 s, PGD 47.460 cm at 6.84 s. The
  // header gives the peaks as negative; the values in the file have the
  // opposite polarity (largest sample +450.322), so magnitudes are compared.
  // Tolerance 3 % on PGV and PGD after the default correction (a degree-2
  // polynomial off the velocity), the time of each peak
  // exactly on its sample.
  const GroundMotion raw = GroundMotion::read_accelerogram(kElCentro);
  EXPECT_EQ(raw.size(), 1848u);  // 1,845 values and three trailing zeros
  EXPECT_DOUBLE_EQ(raw.dt(), 0.02);
  EXPECT_NEAR(raw.peak_acceleration().value, 4.50322, 1e-12);
  EXPECT_NEAR(raw.peak_acceleration().time, 4.98, 1e-12);

  const GroundMotion g = raw.baseline_corrected(2);
  const auto pgv = g.peak_velocity(), pgd = g.peak_displacement();
  EXPECT_NEAR(std::abs(pgv.value), 1.12543, 0.03 * 1.12543) << pgv.value;
  EXPECT_NEAR(std::abs(pgd.value), 0.47460, 0.03 * 0.47460) << pgd.value;
  EXPECT_NEAR(pgv.time, 5.92, 1e-9);
  EXPECT_NEAR(pgd.time, 6.84, 1e-9);
  // What the correction is for: the uncorrected record drifts to 24 cm at
  // its end; corrected, the ground comes back to within 2 cm of its start.
  EXPECT_GT(std::abs(raw.displacement().back()), 0.2);
  EXPECT_LT(std::abs(g.displacement().back()), 0.02);
}

TEST(GroundMotion, IntegrationIsExactForPiecewiseLinearAcceleration) {
  // Reference: a = k·t integrates to v = k t²/2, u = k t³/6 exactly (the
  // scheme is exact for acceleration linear between samples).
  const double k = 3.0, dt = 0.01;
  std::vector<double> a(201);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = k * static_cast<double>(i) * dt;
  const GroundMotion g(dt, a);
  const double t = 2.0;
  EXPECT_NEAR(g.velocity().back(), k * t * t / 2, 1e-12);
  EXPECT_NEAR(g.displacement().back(), k * t * t * t / 6, 1e-12);
}

TEST(GroundMotion, BaselineCorrectionRemovesAPolynomialDriftExactly) {
  // A clean pulse plus a shifted zero line c0 and a tilt c1·t: the drift's
  // velocity c0·t + c1·t²/2 is in the fitted space, so the corrected
  // contaminated record equals the corrected clean one (least squares is
  // linear), to round-off.
  const double dt = 0.005;
  std::vector<double> clean(2001), dirty(2001);
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const double t = static_cast<double>(i) * dt;
    clean[i] = 2.0 * std::sin(2 * M_PI * 1.3 * t) * std::exp(-0.4 * t);
    dirty[i] = clean[i] + 0.05 - 0.01 * t;
  }
  const GroundMotion a = GroundMotion(dt, clean).baseline_corrected(2);
  const GroundMotion b = GroundMotion(dt, dirty).baseline_corrected(2);
  for (std::size_t i = 0; i < clean.size(); i += 97) {
    EXPECT_NEAR(a.velocity()[i], b.velocity()[i], 1e-10);
    EXPECT_NEAR(a.displacement()[i], b.displacement()[i], 1e-10);
  }
  // Uncorrected, the drift moves the ground by c0 T²/2 − c1 T³/6 = 0.833 m
  // (T = 10 s; exact: the drift is linear in t).
  EXPECT_NEAR(GroundMotion(dt, dirty).displacement().back() - GroundMotion(dt, clean).displacement().back(),
              0.05 * 100 / 2 - 0.01 * 1000 / 6, 1e-9);
  EXPECT_EQ(GroundMotion(dt, dirty).baseline_corrected(0).acceleration(), dirty);
}

TEST(GroundMotion, CsvInUnitsOfGResampledToTheStep) {
  // Uneven times, acceleration in g, a heading line; resampled to 0.05 s by
  // linear interpolation: a(0.15) = (0.1 + 0.3)/2 g between (0.1, 0.1 g) and
  // (0.2, 0.3 g).
  const std::string path = write_file("dda_gm_test.csv", "time,acc\n0,0\n0.1,0.1\n0.2,0.3\n0.25,0\n");
  const GroundMotion g = GroundMotion::read_csv(path, AccelerationUnit::G, 0.05);
  ASSERT_EQ(g.size(), 6u);
  EXPECT_NEAR(g.acceleration()[3], 0.2 * 9.80665, 1e-12);
  EXPECT_NEAR(g.acceleration()[5], 0.0, 1e-12);
  // dt = 0: the smallest spacing in the file (0.05 s).
  EXPECT_EQ(GroundMotion::read_csv(path, AccelerationUnit::G).size(), 6u);
}

TEST(GroundMotion, CsvOfTheRecordReadsAsTheRecord) {
  // The same record written as a (time, cm/s²) CSV reads to the same samples
  // (to the 12 digits the times are written with).
  const GroundMotion dat = GroundMotion::read_accelerogram(kElCentro);
  std::string text = "# El Centro Array 7, time (s), acceleration (cm/s2)\n";
  for (std::size_t i = 0; i < dat.size(); ++i) text += msg(i * 0.02, ", ", dat.acceleration()[i] * 100, "\n");
  const GroundMotion csv =
      GroundMotion::read_csv(write_file("dda_gm_record.csv", text), AccelerationUnit::CentimetrePerSecond2);
  ASSERT_EQ(csv.size(), dat.size());
  for (std::size_t i = 0; i < dat.size(); ++i) EXPECT_NEAR(csv.acceleration()[i], dat.acceleration()[i], 1e-9);
}

TEST(GroundMotion, BadInputNamesTheCause) {
  auto message = [](auto f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { parse_acceleration_unit("ft/s2"); }).find("give \"m/s2\""), std::string::npos);
  EXPECT_NE(message([] { GroundMotion::read_accelerogram("/nonexistent/record.dat"); }).find("cannot open"),
            std::string::npos);
  const std::string bad = write_file("dda_gm_bad.dat", "% INTERVALS OF .01 SEC\n1.0 2.0 x3\n");
  EXPECT_NE(message([&] { GroundMotion::read_accelerogram(bad); }).find("line 2: 'x3' is not a number"),
            std::string::npos);
  const std::string no_dt = write_file("dda_gm_nodt.dat", "% no spacing here\n1.0 2.0 3.0\n");
  EXPECT_NE(message([&] { GroundMotion::read_accelerogram(no_dt); }).find("give dt"), std::string::npos);
  EXPECT_EQ(GroundMotion::read_accelerogram(no_dt, AccelerationUnit::MetrePerSecond2, 0.01).size(), 3u);
  const std::string back = write_file("dda_gm_back.csv", "0,1\n0.2,1\n0.1,1\n");
  EXPECT_NE(message([&] { GroundMotion::read_csv(back, AccelerationUnit::G); }).find("line 3: times must increase"),
            std::string::npos);
  EXPECT_NE(message([] { GroundMotion(0.01, {1.0}); }).find("at least two"), std::string::npos);
  EXPECT_NE(message([&] { GroundMotion::read_accelerogram(kElCentro).baseline_corrected(9); }).find("0 (none) to 6"),
            std::string::npos);
}

TEST(GroundMotion, HistoryDoubleIntegralIsExactForPiecewiseLinear) {
  // Reference: by hand for 0 → 2 (t = 1) → 0 (t = 3): t³/3 up to t = 1, then
  // 1/3 + s + s² − s³/6 (s = t − 1), then 5 + 3(t − 3). A shaken base driven
  // by an acceleration history (target acceleration = h) follows it.
  const History h({{0, 0}, {1, 2}, {3, 0}});
  EXPECT_NEAR(h.double_integral(0.5), 0.125 / 3, 1e-15);
  EXPECT_NEAR(h.double_integral(1), 1.0 / 3, 1e-15);
  EXPECT_NEAR(h.double_integral(2), 1.0 / 3 + 1 + 1 - 1.0 / 6, 1e-14);
  EXPECT_NEAR(h.double_integral(3), 5, 1e-14);
  EXPECT_NEAR(h.double_integral(4), 8, 1e-14);
  // And the ground motion's displacement at its samples.
  const GroundMotion g = GroundMotion::read_accelerogram(kElCentro);
  const History a = g.acceleration_history();
  for (std::size_t i = 0; i < g.size(); i += 101)
    EXPECT_NEAR(a.double_integral(static_cast<double>(i) * g.dt()), g.displacement()[i], 1e-12);
}
