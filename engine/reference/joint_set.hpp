// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The exact transmission of a harmonic P wave at normal incidence across N
// parallel joints (a reference for the tests, not part of the step).
//
// Each joint is the displacement-discontinuity model (a linear normal
// spring of stiffness k_n, Pa/m: σ continuous, u⁺ − u⁻ = σ/k_n); the rock
// between joints is elastic, impedance Z = ρc, wavenumber k = ω/c. With the
// state (u, σ) of a harmonic wave, a joint is the matrix [1, 1/k_n; 0, 1] and
// a stretch s of rock [cos ks, sin ks/(ωZ); −ωZ sin ks, cos ks]; their
// product over the set carries the incident and reflected waves on one
// side to the transmitted wave on the other (the transfer-matrix method; the
// same answer as Cai & Zhao's (2000) method of characteristics in the
// steady state). One joint: |T| = [1 + (ωZ/2k_n)²]^(−1/2).
#include <complex>

namespace dda::reference {

struct JointSet {
  int count = 1;             // N
  double spacing = 1;        // m, between neighbouring joints
  double stiffness = 1e10;   // k_n, Pa/m
  double impedance = 1e7;    // Z = ρc of the rock, Pa·s/m
  double wave_speed = 5000;  // c, m/s
};

// The complex transmission coefficient T_N (transmitted over incident
// displacement, the phase taken at the last joint) at angular frequency ω
// (complex ω allowed: a damped harmonic wave).
std::complex<double> joint_set_transmission(const JointSet& set, std::complex<double> omega);

}  // namespace dda::reference
