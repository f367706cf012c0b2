// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The exact 2-D answer for a long elastic strip (a bar of height H, plane
// stress or plane strain) loaded at its end x = 0 by a uniform pressure p(t):
// the stress at (x, y), x well inside the bar, by Fourier synthesis of the
// symmetric Rayleigh–Lamb modes (the load is symmetric about mid-height).
// A reference for the tests, not part of the step.
//
// Modes. With fields ∝ exp(i(kx − ωt)), the symmetric modes of a traction-free
// strip −b ≤ y ≤ b (b = H/2) are the roots k(ω) of
//
//   D(k) = (q² − k²)²·cos(pb)·sin(qb)/q + 4k²·p·sin(pb)·cos(qb) = 0,
//   p² = ω²/c_L² − k²,  q² = ω²/c_T² − k²
//
// (Rayleigh–Lamb; D is written even in p and q, so the branch of the roots
// does not matter), c_L² = (λ* + 2μ)/ρ, c_T² = μ/ρ, λ* = Eν/(1 − ν²) in plane
// stress (Eν/((1 + ν)(1 − 2ν)) in plane strain). Every root is found: a
// Chebyshev collocation of the cross-section turns the strip's equations
// into a quadratic eigenvalue problem in k, whose eigenvalues (Eigen's QZ)
// are polished by Newton's method on D.
//
// End condition. The modal expansion is exact, mode by mode, when the end
// carries σxx and u_y (Fraser's bi-orthogonality: for modes m ≠ n,
// ∫(σxx_m·ux_n − σxy_n·uy_m) dy = 0): a uniform pressure on an end held
// against lateral motion (rollers, u_y = 0) excites mode n with
//
//   a_n = −p̂(ω)·∫ux_n dy / ∫(σxx_n·ux_n − σxy_n·uy_n) dy.
//
// A free end (σxy = 0) has no such formula; `EndCondition::Free` fits the
// modes to σxx = −p̂, σxy = 0 by least squares at points of the end (mode
// matching), converged in the number of modes kept (the tests show it).
//
// Synthesis. σ(t) = (1/π)·Re ∫₀^∞ p̂(ω̃)·G(ω̃)·e^{−iω̃t} dω at the complex
// frequency ω̃ = ω + iε (the exponential window: the synthesis is periodic in
// 1/Δf, and e^{−ε/Δf} takes what would wrap round below 1e-8), with p̂ the
// exact transform of the piecewise-linear load and G = Σ a_n·σxx_n(y)·e^{ik_n x}
// over the modes that carry energy to +x or decay towards it (Im k > 0 at
// ω̃). The integral is cut at f_max with a cosine taper over its last 20 %.
#include <complex>
#include <optional>
#include <utility>
#include <vector>

#include "core/material.hpp"

namespace dda::reference {

using Complex = std::complex<double>;

struct Strip {
  double density = 2000;  // kg/m³
  double youngs = 50e9;   // Pa
  double poisson = 0.25;
  double height = 1;  // m (the strip is −height/2 ≤ y ≤ height/2)
  PlaneMode plane = PlaneMode::Stress;
};

// One symmetric mode at frequency ω (complex): its wavenumber and the
// amplitudes of its potentials (φ = A·cos(py), ψ = B·sin(qy)/q).
struct PlateMode {
  Complex k, p, q, a, b;
};

// The fields of a mode at height y (y from mid-height): displacement and
// stress, without the factor exp(i(kx − ωt)).
struct ModeFields {
  Complex ux, uy, sxx, sxy, syy;
};

class PlateModes {
 public:
  explicit PlateModes(const Strip& strip, int collocation_points = 24);

  // The symmetric modes at frequency ω that carry energy to +x or decay
  // towards it (Im k > 0; ω complex with a small positive imaginary part),
  // ordered by Im k (the least decaying first), at most `count`.
  std::vector<PlateMode> right_going(Complex omega, int count) const;
  std::vector<Complex> right_going_wavenumbers(Complex omega, int count) const;
  // The modes near the wavenumbers `predicted` (each polished by Newton's
  // method at ω); none when one is lost (no convergence, a jump, a
  // duplicate, or Im k ≤ 0).
  std::optional<std::vector<Complex>> follow(const std::vector<Complex>& predicted, Complex omega) const;
  PlateMode mode(Complex k, Complex omega) const;
  ModeFields fields(const PlateMode& m, Complex omega, double y) const;
  // D(k) at ω (above); zero at a mode.
  Complex dispersion(Complex k, Complex omega) const;
  double longitudinal_speed() const { return c_l_; }
  double shear_speed() const { return c_t_; }
  double half_height() const { return b_; }

 private:
  std::vector<Complex> eigenvalue_estimates(double omega) const;
  std::optional<Complex> polish(Complex k, Complex omega) const;  // Newton on D; none if it does not converge
  bool contains(const std::vector<Complex>& roots, Complex k) const;

  Strip strip_;
  double lambda_, mu_, c_l_, c_t_, b_;
  int n_;
};

enum class EndCondition { Rollers, Free };

struct PlateBarOptions {
  EndCondition end = EndCondition::Rollers;
  double max_frequency = 20e3;  // Hz: the synthesis is cut (tapered) here
  double frequency_step = 5;    // Hz
  // Modes kept at each frequency: every one that reaches the receiver
  // (decay over x above e^{−40}); a free end's least-squares fit takes at
  // least this many, the least decaying first.
  int modes = 16;
  int collocation_points = 24;  // of the cross-section's half (more at high frequency)
};

// σxx (tension positive) at (x, y) at the times t, under a pressure p(t)
// (compression positive, pushing into the bar) given by the piecewise-linear
// table `load` (zero before its first and after its last point).
std::vector<double> plate_bar_stress(const Strip& strip, const std::vector<std::pair<double, double>>& load, double x,
                                     double y, const std::vector<double>& times, const PlateBarOptions& options = {});

// The piecewise-linear table at t (zero outside it).
double load_at(const std::vector<std::pair<double, double>>& load, double t);

// The exact Fourier transform ∫p(t)·e^{iωt} dt of a piecewise-linear table
// (zero outside it), ω complex.
Complex piecewise_linear_transform(const std::vector<std::pair<double, double>>& load, Complex omega);

}  // namespace dda::reference
