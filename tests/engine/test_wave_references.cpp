// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The exact references of the wave tests (engine/reference/), checked against
// what is known of them independently: closed forms, limits, and their own
// mathematical properties.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "core/types.hpp"
#include "reference/joint_set.hpp"
#include "reference/plate_bar.hpp"

using namespace dda;
using namespace dda::reference;

namespace {

// One sine period of amplitude a at f (compression first), sampled finely
// enough that the piecewise-linear table is the sine within 1e-7 of a.
std::vector<std::pair<double, double>> sine_period(double f, double a = 5e6) {
  std::vector<std::pair<double, double>> load;
  const int n = 2000;
  for (int i = 0; i <= n; ++i) {
    const double t = i / (n * f);
    load.emplace_back(t, a * std::sin(2 * kPi * f * t));
  }
  return load;
}

}  // namespace

TEST(WaveReferences, PlateModesMeetTheSurfaceConditionsAndFrasersBiorthogonality) {
  // Each mode leaves the strip's faces free (σyy = σxy = 0 at y = ±b) and
  // any two satisfy ∫(σxx_m·ux_n − σxy_n·uy_m) dy = 0 (the relation the
  // roller end's coefficients rest on; derived from reciprocity in
  // plate_bar.hpp). 2 kHz, ν = 0.25, plane stress: S0, the first complex
  // pair and the next modes.
  const PlateModes modes(Strip{});
  const Complex omega(2 * kPi * 2000, 30);
  const std::vector<PlateMode> ms = modes.right_going(omega, 6);
  ASSERT_GE(ms.size(), 5u);
  const double b = modes.half_height();
  auto product = [&](const PlateMode& m, const PlateMode& n) {
    Complex s = 0;
    const int g = 2000;
    for (int i = 0; i < g; ++i) {  // midpoint rule, smooth integrand: error ~1e-7
      const double y = (i + 0.5) * b / g;
      const ModeFields fm = modes.fields(m, omega, y), fn = modes.fields(n, omega, y);
      s += fm.sxx * fn.ux - fn.sxy * fm.uy;
    }
    return s;
  };
  for (std::size_t m = 0; m < 5; ++m) {
    const ModeFields face = modes.fields(ms[m], omega, b), middle = modes.fields(ms[m], omega, 0);
    EXPECT_LT(std::abs(face.syy), 1e-9 * std::abs(middle.sxx)) << m;
    EXPECT_LT(std::abs(face.sxy), 1e-9 * std::abs(middle.sxx)) << m;
    for (std::size_t n = 0; n < 5; ++n) {
      if (m == n) continue;
      EXPECT_LT(std::abs(product(ms[m], ms[n])),
                1e-5 * std::sqrt(std::abs(product(ms[m], ms[m]) * product(ms[n], ms[n]))))
          << m << ", " << n;
    }
  }
}

TEST(WaveReferences, PlateBarIsTheOneDimensionalBarWithoutPoissonsRatio) {
  // ν = 0: the strip's first mode is u_x uniform, u_y = 0, k = ω/c0 at every
  // frequency, and the end load excites it alone: σxx(x, t) = −p(t − x/c0),
  // c0 = sqrt(E/ρ) = 5000 m/s. The synthesis must give it to round-off.
  Strip strip;
  strip.poisson = 0;
  const PlateModes modes(strip);
  for (double f : {100.0, 1500.0, 4000.0}) {
    const Complex omega(2 * kPi * f, 10);
    EXPECT_NEAR(std::abs(modes.right_going(omega, 1).front().k - omega / 5000.0), 0, 1e-10 * f) << f;
  }
  const auto load = sine_period(1000);
  std::vector<double> times;
  for (double t = 1.9e-3; t < 3.2e-3; t += 1e-5) times.push_back(t);
  PlateBarOptions o;
  o.max_frequency = 5000;
  const std::vector<double> s = plate_bar_stress(strip, load, 10.1, 0.0, times, o);
  for (std::size_t i = 0; i < times.size(); ++i)
    EXPECT_NEAR(s[i], -load_at(load, times[i] - 10.1 / 5000), 1e-6 * 5e6) << times[i];
}

TEST(WaveReferences, PlateBarLongWavesTravelAtTheBarSpeedWithLoveCorrection) {
  // ν = 0.25 at low frequency: the first mode's phase speed is
  // c0·(1 − ν²k²r²/2 + O(k⁴)), r² = H²/12 (Rayleigh–Love's lateral inertia).
  const PlateModes modes(Strip{});
  for (double f : {50.0, 200.0}) {
    const Complex omega(2 * kPi * f, 0.01);
    const double k = modes.right_going(omega, 1).front().k.real();
    const double c = omega.real() / k, k0 = omega.real() / 5000, love = 5000 * (1 - 0.0625 * k0 * k0 / 12 / 2);
    EXPECT_NEAR(c, love, 5000 * 0.2 * std::pow(k0 * 0.5, 4)) << f;
  }
}

TEST(WaveReferences, PlateBarFreeEndIsConvergedInTheModesKept) {
  // At x = 10.1 m (10 heights from the end) under a free end (least squares
  // of the modes' end tractions), 1500 Hz, ν = 0.25: 16 modes against 32
  // agree to 1e-4 of the first peak. (The free end differs from rollers,
  // Fraser's exact coefficients, by up to 0.22 % of the peak there: the
  // end's near field.)
  const auto load = sine_period(1500);
  std::vector<double> times;
  for (double t = 2.0e-3; t < 2.5e-3; t += 2e-6) times.push_back(t);
  PlateBarOptions o;
  o.max_frequency = 10000;
  o.end = EndCondition::Free;
  const std::vector<double> free16 = plate_bar_stress(Strip{}, load, 10.1, 0.0, times, o);
  o.modes = 32;
  const std::vector<double> free32 = plate_bar_stress(Strip{}, load, 10.1, 0.0, times, o);
  const double peak = *std::min_element(free32.begin(), free32.end());
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(free16[i], free32[i], 1e-4 * std::abs(peak)) << times[i];
}

TEST(WaveReferences, OneJointTransmitsAsTheLinearSlipModel) {
  // N = 1: |T| = [1 + (ωZ/2k_n)²]^(−1/2) (Pyrak-Nolte et al. 1990).
  for (double ratio : {0.5, 1.0, 2.0, 20.0}) {
    const double omega = 2 * kPi * 1000, z = 1e7;
    JointSet set;
    set.stiffness = ratio * omega * z / 2;
    EXPECT_NEAR(std::abs(joint_set_transmission(set, omega)), 1 / std::sqrt(1 + 1 / (ratio * ratio)), 1e-14) << ratio;
  }
}

TEST(WaveReferences, TwoJointsAreTheMultipleReflectionSeries) {
  // N = 2, independently of the transfer matrices: the wave that crosses
  // both joints after 2m reflections between them sums to
  // T₂ = T₁²·e^{iks}/(1 − R₁²·e^{2iks}) (T₁ = 1/(1 − a), R₁ = −a/(1 − a),
  // a = iωZ/2k_n; the phase of T₂ taken at the second joint drops e^{iks}).
  // And no energy is lost: |T_N|² + |R_N|² = 1 (checked through |T_N| ≤ 1).
  const double z = 1e7, c = 5000;
  for (double f : {200.0, 1000.0, 3000.0})
    for (double ratio : {0.5, 2.0}) {
      const double omega = 2 * kPi * f, s = 1.7;
      JointSet set;
      set.count = 2;
      set.spacing = s;
      set.stiffness = ratio * 2 * kPi * 1000 * z / 2;
      const Complex a(0, omega * z / (2 * set.stiffness)), t1 = 1.0 / (1.0 - a), r1 = -a / (1.0 - a);
      const Complex phase = std::exp(Complex(0, omega / c * s));
      const Complex series = t1 * t1 * phase / (1.0 - r1 * r1 * phase * phase);
      EXPECT_NEAR(std::abs(joint_set_transmission(set, omega)), std::abs(series), 1e-12) << f << " " << ratio;
      for (int n = 1; n <= 10; ++n) {
        set.count = n;
        EXPECT_LE(std::abs(joint_set_transmission(set, omega)), 1 + 1e-12);
      }
    }
}
