// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The time integrators (block/time_scheme.hpp) against closed forms on a
// mass on a spring: one square block held at its centroid by a fixed point,
// whose translation is then an undamped oscillator m·ẍ = −k·x (k =
// fixed_point_factor × g0; the fixed point acts on the translation only, and
// nothing loads the rotation or the strains).
#include <gtest/gtest.h>

#include <cmath>

#include "../scenes.hpp"
#include "core/error.hpp"

using namespace dda;

namespace {

struct Oscillator {
  World w;
  BlockId b = 0;
  double omega = 0;  // rad/s
};

// A 1 m block of 2600 kg moving at `speed` along x through its rest point,
// ωΔt = omega_dt with Δt = 1e-3 s.
Oscillator oscillator(Integrator integrator, double omega_dt, double speed = 0.1) {
  Oscillator o;
  World& w = o.w;
  const int rock = w.add_rock_material(test::granite());
  o.b = w.add_block(test::rectangle(0, 0, 1, 1), rock);
  w.add_fixed_point(o.b, Vec2(0.5, 0.5));
  Vec6 v = Vec6::Zero();
  v[0] = speed;
  w.set_block_velocity(o.b, v);
  const double dt = 1e-3, m = w.block_mass(o.b);
  o.omega = omega_dt / dt;
  Controls& c = w.controls();
  c.g1 = dt;
  c.g0 = o.omega * o.omega * m / c.fixed_point_factor;
  c.g2 = 1;  // no cuts: the motion is the scheme's alone
  c.integrator = integrator;
  return o;
}

double x_of(const Oscillator& o) { return o.w.block_displacement(o.b).x(); }

}  // namespace

TEST(TimeIntegration, NewmarkAverageAccelerationIsTheExactDiscreteRotation) {
  // Reference: for m·ẍ = −k·x the average-acceleration rule maps (ωx, v) by a
  // rotation through ω̄Δt = 2·atan(ωΔt/2) (the Cayley transform of the
  // exact flow): from x = 0, v = V, x_n = (V/ω)·sin(n·ω̄Δt) and v_n =
  // V·cos(n·ω̄Δt), no decay over any number of steps. Tolerance 1e-9 of the
  // amplitude: the solve's (cg_tolerance 1e-10) and round-off.
  const double omega_dt = 0.2, speed = 0.1;
  Oscillator o = oscillator(Integrator::Newmark, omega_dt, speed);
  const double amplitude = speed / o.omega, bar = 2 * std::atan(omega_dt / 2);
  for (int n = 1; n <= 400; ++n) {  // 13 periods
    ASSERT_EQ(o.w.step().step_cuts, 0);
    ASSERT_NEAR(x_of(o), amplitude * std::sin(n * bar), 1e-9 * amplitude) << "step " << n;
    ASSERT_NEAR(o.w.block_velocity(o.b)[0], speed * std::cos(n * bar), 1e-9 * speed) << "step " << n;
  }
}

TEST(TimeIntegration, ShiSchemeDampsAsNewmarkHalfOne) {
  // Reference: Shi's scheme is Newmark β = ½, γ = 1; on m·ẍ = −k·x its
  // amplification matrix [[1, Δt], [−ω²Δt, 1 − ω²Δt²/2]]/(1 + ω²Δt²/2) (in
  // (x, v), from d = Δt·v0 + Δt²/2·a1, v1 = v0 + Δt·a1) has determinant
  // 1/(1 + ω²Δt²/2), its complex eigenvalues that modulus squared: the
  // energy falls by 1/(1 + ω²Δt²/2) per step (about exp(−ω²Δt·t/2), the
  // amplitude as exp(−ω²Δt·t/4)).
  const double omega_dt = 0.2;
  Oscillator o = oscillator(Integrator::Shi, omega_dt);
  const double m = o.w.block_mass(o.b), k = m * o.omega * o.omega;
  auto energy = [&] {
    const double x = x_of(o), v = o.w.block_velocity(o.b)[0];
    return 0.5 * m * v * v + 0.5 * k * x * x;
  };
  std::vector<double> e;
  for (int n = 1; n <= 400; ++n) {
    o.w.step();
    e.push_back(energy());
  }
  const double per_step = 1 / (1 + omega_dt * omega_dt / 2);
  // The energy of Shi's step oscillates within the step's phase; its mean
  // over a period decays by per_step each step. Compare means over 31 steps
  // (one period: 2π/ω̄Δt ≈ 31.4) 100 steps apart.
  auto mean = [&](int from) {
    double s = 0;
    for (int i = from; i < from + 31; ++i) s += e[i];
    return s / 31;
  };
  EXPECT_NEAR(mean(300) / mean(200), std::pow(per_step, 100), 0.02 * std::pow(per_step, 100));
}

TEST(TimeIntegration, GeneralizedAlphaFollowsChungHulbertOnTheOscillator) {
  // Reference: Chung & Hulbert's (1993) equations stepped for the scalar
  // oscillator ẍ = −ω²x, x0 = 0, v0 = V, a0 = 0:
  //   (1 − αm)·a1 + αm·a0 = −ω²[(1 − αf)·x1 + αf·x0],
  //   x1 = x0 + Δt·v0 + Δt²[(½ − β)·a0 + β·a1],  v1 = v0 + Δt[(1 − γ)·a0 + γ·a1],
  // αm = (2ρ∞ − 1)/(ρ∞ + 1), αf = ρ∞/(ρ∞ + 1), γ = ½ − αm + αf,
  // β = ¼(1 − αm + αf)². The engine (DDA's step displacement, block mass
  // matrices, the unbalanced-force recursion) must give the same x and v
  // within 1e-8 of the amplitude (its solve's tolerance), at ωΔt = 0.5
  // (a resolved frequency, lightly damped) and 1e4 (the stiff limit, where
  // each step multiplies the motion by about −ρ∞).
  for (const double omega_dt : {0.5, 1e4})
    for (const double rho_inf : {0.0, 0.5, 0.8, 1.0}) {
      const double speed = 1.0;
      Oscillator o = oscillator(Integrator::GeneralizedAlpha, omega_dt, speed);
      o.w.controls().rho_inf = rho_inf;
      const double am = (2 * rho_inf - 1) / (rho_inf + 1), af = rho_inf / (rho_inf + 1);
      const double gamma = 0.5 - am + af, beta = 0.25 * (1 - am + af) * (1 - am + af);
      const double dt = 1e-3, w2 = o.omega * o.omega;
      double x = 0, v = speed, a = 0;
      for (int n = 1; n <= 40; ++n) {
        const double a1 = -(am * a + w2 * (x + (1 - af) * (dt * v + dt * dt * (0.5 - beta) * a))) /
                          ((1 - am) + w2 * (1 - af) * beta * dt * dt);
        x += dt * v + dt * dt * ((0.5 - beta) * a + beta * a1);
        v += dt * ((1 - gamma) * a + gamma * a1);
        a = a1;
        const std::string where = msg("ωΔt ", omega_dt, ", ρ∞ ", rho_inf, ", step ", n);
        ASSERT_NO_THROW(o.w.step()) << where;
        ASSERT_NEAR(x_of(o), x, 1e-8 * speed / o.omega) << where;
        ASSERT_NEAR(o.w.block_velocity(o.b)[0], v, 1e-8 * speed) << where;
      }
      // The stiff limit: damped unless ρ∞ = 1.
      if (omega_dt > 1 && rho_inf < 1) {
        EXPECT_LT(std::abs(o.w.block_velocity(o.b)[0]), 0.02 * speed);
      } else if (omega_dt > 1) {
        EXPECT_GT(std::abs(o.w.block_velocity(o.b)[0]), 0.5 * speed);
      }
    }
}

TEST(TimeIntegration, GeneralizedAlphaIsSecondOrderAtLowFrequency) {
  // Reference: the exact x(t) = (V/ω)·sin(ωt). A second-order scheme's
  // error after a fixed time falls 4× when Δt halves. After 2 periods at
  // ωΔt = 0.1 and 0.05: error ratio within [3.6, 4.4] for generalized-α
  // (ρ∞ = 0.8) and Newmark.
  auto error_after = [](Integrator integrator, double omega_dt) {
    Oscillator o = oscillator(integrator, omega_dt);
    if (integrator == Integrator::GeneralizedAlpha) o.w.controls().rho_inf = 0.8;  // (only it reads ρ∞)
    const int steps = static_cast<int>(std::lround(4 * kPi / omega_dt));
    const double t_end = steps * 1e-3;
    for (int n = 0; n < steps; ++n) o.w.step();
    return std::abs(x_of(o) - 0.1 / o.omega * std::sin(o.omega * t_end)) / (0.1 / o.omega);
  };
  for (const Integrator i : {Integrator::GeneralizedAlpha, Integrator::Newmark}) {
    const double ratio = error_after(i, 0.1) / error_after(i, 0.05);
    EXPECT_GT(ratio, 3.6) << static_cast<int>(i);
    EXPECT_LT(ratio, 4.4) << static_cast<int>(i);
  }
}

TEST(TimeIntegration, ARedoneStepFindsTheSchemeStateUntouched) {
  // A step cut once (Δt/3) and redone must give the step a model with g1 =
  // Δt/3 takes from the same state: the integrator's state is written in
  // Update only. Two oscillators, 20 steps with the newmark scheme, then one
  // step each: one whose g2 bound forces a cut, one at the cut Δt. Equal
  // within the solve's tolerance (the rejected attempt's solve is gone).
  for (const Integrator integrator : {Integrator::Newmark, Integrator::GeneralizedAlpha}) {
    Oscillator a = oscillator(integrator, 0.2), b = oscillator(integrator, 0.2);
    for (int n = 0; n < 20; ++n) a.w.step(), b.w.step();
    // The next step moves the block by about v·Δt; a bound of half that cuts once.
    const double dt = a.w.current_dt(), v = a.w.block_velocity(a.b)[0];
    a.w.controls().g2 = 0.5 * std::abs(v) * dt / a.w.half_height();
    b.w.controls().g1 = dt / 3;
    const StepStats sa = a.w.step();
    const StepStats sb = b.w.step();
    ASSERT_EQ(sa.step_cuts, 1);
    ASSERT_EQ(sb.step_cuts, 0);
    ASSERT_EQ(a.w.time(), b.w.time());
    EXPECT_NEAR(x_of(a), x_of(b), 1e-12);
    EXPECT_NEAR(a.w.block_velocity(a.b)[0], b.w.block_velocity(b.b)[0], 1e-10);
  }
}

TEST(TimeIntegration, RhoInfOutsideTheUnitIntervalIsAnError) {
  Oscillator o = oscillator(Integrator::GeneralizedAlpha, 0.2);
  o.w.controls().rho_inf = 1.5;
  try {
    o.w.step();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "controls: rho_inf must lie in [0, 1], got 1.5");
  }
}

TEST(TimeIntegration, TheDefaultSchemeHoldsABlockOnAnInclineItsFrictionHolds) {
  // Reference: Coulomb friction holds a block on an incline at α when
  // tan φ ≥ tan α; here α = 30°, φ = 35°, 0.5 s at the quasi-static step
  // Δt = 1e-3 s. A model without dynamic loads steps with Shi's scheme by
  // default (integrator "auto": docs/waves.md) because of this case
  // (docs/time_integration.md, "The default"): under it the block creeps
  // 2.2e-5 m in 0.5 s (Shi's contact law; 9e-6 m at 0.1 s), bound 1e-4 m;
  // the second-order schemes leave the contact springs' own oscillation
  // (ωΔt ≫ 1) undamped or little damped, the normal force swings through
  // zero and the block slides: 0.052 m here under newmark (bound: over
  // 1e-2 m, or the reason for the default has gone).
  const double a = deg_to_rad(30), phi = 35;
  auto slip_of = [&](Integrator integrator) {
    World w;
    const BlockId b = test::block_on_incline(w, a, phi);
    w.controls().integrator = integrator;
    const Vec2 start = w.block_centroid(b), down(-std::cos(a), -std::sin(a));
    while (w.time() < 0.5 - 1e-9) w.step();
    if (integrator == Integrator::Auto) {
      EXPECT_EQ(w.integrator_in_use(), Integrator::Shi);
    }
    return (w.block_centroid(b) - start).dot(down);
  };
  EXPECT_LT(std::abs(slip_of(Controls{}.integrator)), 1e-4);
  EXPECT_GT(slip_of(Integrator::Newmark), 1e-2) << "the reason for the default has gone: measure again";
}

TEST(TimeIntegration, ADashpotDoesNotDampNewmarksUnresolvedMode) {
  // The cure for Newmark's ringing contact springs at quasi-static steps
  // (docs/time_integration.md, "A contact dashpot does not cure Newmark's
  // ringing"): the oscillator at ωΔt = 340 (the incline's contact mode at
  // Δt = 1e-2 s) with a critical dashpot, c = 2·m·ω (ζ = 1: the exact motion
  // is gone within a step, e^(−ωΔt)), made by a viscous boundary on the
  // block's right edge whose medium has ρ·C_P = c. Reference: the spectral
  // radius of the average-acceleration rule on m·ẍ + c·ẋ + k·x = 0 at ωΔt =
  // 340, ζ = 1, is 0.993 a step (it maps every mode to −1 as ωΔt → ∞,
  // whatever the damping): after 40 steps at least half the speed is left
  // (measured 0.86; 0.993⁴⁰ = 0.75). Generalized-α at ρ∞ = 0.5 without any
  // dashpot damps it by 0.52 a step: under 1e-3 of the speed after 40 steps
  // (0.52⁴⁰ = 4e-12). Shi's scheme, undamped, takes the displacement at once
  // but keeps the velocity: its amplification's eigenvalues at ωΔt = 340 are
  // about 0 and −(1 − 3/(ω²Δt²/2)), so after 40 steps |v| is 0.998 of the
  // speed (bound: over half) with the displacement that mode's, 2V/(ω²Δt) =
  // 1.7e-5 of V·Δt (bound 1e-4 of V·Δt).
  const double omega_dt = 340, speed = 1;
  Oscillator newmark = oscillator(Integrator::Newmark, omega_dt, speed);
  const double m = newmark.w.block_mass(newmark.b), c = 2 * m * newmark.omega, rho = 2600;
  const double modulus = c * c / rho;  // ρ·C_P = √(M·ρ) = c; M = E(1 − ν)/((1 + ν)(1 − 2ν)) = 1.2·E at ν = ¼
  const int medium = newmark.w.add_rock_material(RockMaterial{rho, modulus / 1.2, 0.25});
  newmark.w.add_viscous_boundary({{newmark.b, 1}}, medium);
  Oscillator alpha = oscillator(Integrator::GeneralizedAlpha, omega_dt, speed);
  alpha.w.controls().rho_inf = 0.5;
  Oscillator shi = oscillator(Integrator::Shi, omega_dt, speed);
  for (int n = 0; n < 40; ++n) {
    ASSERT_EQ(newmark.w.step().step_cuts, 0);
    ASSERT_EQ(alpha.w.step().step_cuts, 0);
    ASSERT_EQ(shi.w.step().step_cuts, 0);
  }
  EXPECT_GT(std::abs(shi.w.block_velocity(shi.b)[0]), 0.5 * speed);
  EXPECT_LT(std::abs(x_of(shi)), 1e-4 * speed * 1e-3);
  EXPECT_GT(std::abs(newmark.w.block_velocity(newmark.b)[0]), 0.5 * speed);
  EXPECT_LT(std::abs(alpha.w.block_velocity(alpha.b)[0]), 1e-3 * speed);
}
