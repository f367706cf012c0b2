// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Waves across joints against exact solutions, with the second-order time
// integrator (docs/time_integration.md) and joints given their own
// stiffness (JointMaterial::normal_stiffness, Pa/m).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "../scenes.hpp"

using namespace dda;

namespace {

// A 1-D bar (ν = 0, plane stress: c = sqrt(E/ρ) = 5000 m/s, Z = ρc = 1e7
// Pa·s/m) of one row of square blocks, loaded at its left end by a Gaussian
// pressure pulse (centre 0.8 ms, width 0.2 ms: its spectrum covers 0-2 kHz).
// The joints between the blocks are near-intact (k_n = 2e14 Pa/m), except,
// when soft_kn > 0, the one at x = soft_at. Returns σxx (tension +) of the
// block centred at `receiver` at every step up to t_end.
std::vector<double> bar_record(double soft_kn, double soft_at, double receiver, double t_end, double dt,
                               double block = 0.1, double length = 20) {
  World w;
  const int rock = w.add_rock_material(RockMaterial{2000, 50e9, 0.0});
  const int intact = w.add_joint_material(JointMaterial{30, 1e9, 1e9, 2e14, 0});
  const int soft = w.add_joint_material(JointMaterial{30, 1e9, 1e9, soft_kn, 0});
  const int n = static_cast<int>(std::lround(length / block));
  const int soft_joint =
      static_cast<int>(std::lround(soft_at / block));  // between blocks soft_joint - 1 and soft_joint
  for (int i = 0; i < n; ++i) {
    // Edges: bottom, right, top, left (counter-clockwise from the lower left).
    const int right = soft_kn > 0 && i + 1 == soft_joint ? soft : intact;
    const int left = soft_kn > 0 && i == soft_joint ? soft : intact;
    w.add_block(test::rectangle(i * block, 0, block, block), rock, {intact, right, intact, left});
  }
  std::vector<std::pair<double, double>> pulse;
  for (double t = 0; t <= 2e-3; t += 1e-5) pulse.emplace_back(t, 1e6 * std::exp(-std::pow((t - 0.8e-3) / 0.2e-3, 2)));
  const int load = w.add_pressure_load({EdgeRef{0, 3}});
  w.set_pressure_history(load, History(pulse));
  Controls& c = w.controls();
  c.integrator = Integrator::Newmark;
  c.g1 = dt;
  c.g0 = 2e14 * block / 2;  // corner contacts: the intact joints' stiffness
  c.g2 = 0.01;
  const BlockId probe = static_cast<BlockId>(receiver / block);
  std::vector<double> sigma;
  while (w.time() < t_end - dt / 2) {
    const StepStats s = w.step();
    EXPECT_EQ(s.step_cuts, 0);
    sigma.push_back(w.block_stress(probe).x());
  }
  return sigma;
}

// |Σ σ(t_n)·exp(−iωt_n)| over the record (t_n = (n + 1)·Δt).
double spectrum(const std::vector<double>& sigma, double dt, double frequency) {
  std::complex<double> s = 0;
  for (std::size_t k = 0; k < sigma.size(); ++k)
    s += sigma[k] * std::exp(std::complex<double>(0, -2 * kPi * frequency * (k + 1) * dt));
  return std::abs(s);
}

}  // namespace

TEST(JointWaves, OneSoftJointTransmitsAsTheLinearSlipModel) {
  // Reference: a linear elastic joint of normal stiffness k_n between two
  // half-spaces of impedance Z = ρc transmits a normally incident harmonic
  // wave with |T| = [1 + (ωZ/2k_n)²]^(−1/2) (Pyrak-Nolte et al. 1990; the
  // displacement-discontinuity model). Measured as the ratio of the
  // spectra at x = 12.05 m of the bar with a soft joint at 10 m (k_n =
  // 3e10 Pa/m: |T| = 0.967, 0.886, 0.690 at 250, 500 and 1000 Hz) to the bar
  // without it (near-intact joints, 2e14 Pa/m), the record ending before
  // any reflection from an end reaches the receiver (5.2 ms). Within 1 %,
  // the newmark scheme at the paper's Δt = 2e-6 s, 0.1 m blocks.
  const double dt = 2e-6, kn = 3e10, z = 2000 * 5000.0;
  const std::vector<double> soft = bar_record(kn, 10, 12.05, 5.2e-3, dt);
  const std::vector<double> intact = bar_record(0, 10, 12.05, 5.2e-3, dt);
  for (const double f : {250.0, 500.0, 1000.0}) {
    const double omega = 2 * kPi * f;
    const double exact = 1 / std::sqrt(1 + std::pow(omega * z / (2 * kn), 2));
    const double measured = spectrum(soft, dt, f) / spectrum(intact, dt, f);
    std::printf("%g Hz: |T| = %.4f, closed form %.4f\n", f, measured, exact);
    EXPECT_NEAR(measured, exact, 0.01 * exact) << f << " Hz";
  }
}
