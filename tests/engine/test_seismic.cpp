// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Shaking a model: Newmark's sliding block on a rigid shaken base, and the
// compliant (quiet) base with an incident wave (docs/seismic.md).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "../scenes.hpp"
#include "../source_dir.hpp"
#include "loading/ground_motion.hpp"

using namespace dda;

namespace {

constexpr double kG = 9.81;

// Newmark's rigid-plastic sliding block (Newmark 1965), integrated on its
// own as the reference: the slip s down an incline of angle alpha (rising
// towards +x) with friction angle phi, under a horizontal base acceleration
// a(t) (+x pushes the block, in the base's frame, downhill). Driving and
// normal accelerations per unit mass: A = g sin α + a cos α,
// N = g cos α − a sin α; the block slides when |A| > N tan φ and stops when
// its relative velocity comes back to zero. Semi-analytic small steps h.
double newmark_slip(const std::function<double(double)>& a_base, double alpha, double phi, double t_end,
                    double h = 2e-6) {
  const double mu = std::tan(phi);
  double s = 0, v = 0;
  for (double t = 0; t < t_end; t += h) {
    const double a = a_base(t + h / 2);
    const double drive = kG * std::sin(alpha) + a * std::cos(alpha);
    const double resist = mu * std::max(0.0, kG * std::cos(alpha) - a * std::sin(alpha));
    double acc = 0;
    if (v > 0 || (v == 0 && drive > resist)) acc = drive - resist;
    if (v < 0 || (v == 0 && drive < -resist)) acc = drive + resist;
    double v1 = v + acc * h;
    if (v * v1 < 0) v1 = 0;  // friction stops the block; it does not reverse it
    s += 0.5 * (v + v1) * h;
    v = v1;
  }
  return s;
}

// A block on an incline (alpha, friction phi) on a base held by stiff
// springs that follow the ground's displacement along x (and hold it in y):
// the rigid shaken base. Returns the block's slip down the slope.
struct ShakenIncline {
  World w;
  BlockId base, block;
  std::vector<int> targets;
  double alpha;
  // The base follows the ground's displacement history, or with
  // by_acceleration the acceleration history integrated twice by the engine.
  ShakenIncline(double alpha_deg, double phi_deg, const GroundMotion& ground, double dt, ContactLaw law,
                bool by_acceleration = false) {
    alpha = alpha_deg * M_PI / 180;
    const RockMaterial rock = test::granite();
    const int r = w.add_rock_material(rock);
    w.joint_material(0) = JointMaterial{phi_deg, 0, 0};
    const Vec2 s(std::cos(alpha), std::sin(alpha)), n(-std::sin(alpha), std::cos(alpha));
    const double L = 4;
    base = w.add_block({{0, 0}, {0, -1}, {L * s.x(), -1}, {L * s.x(), L * s.y()}}, r);
    // The block starts a micrometre above the slope (rounded corners must not overlap).
    const double d0 = 1.75, size = 0.5, gap = 1e-6;
    auto on_slope = [&](double d, double h) -> Vec2 { return d * s + h * n; };
    block = w.add_block(
        {on_slope(d0, gap), on_slope(d0 + size, gap), on_slope(d0 + size, gap + size), on_slope(d0, gap + size)}, r);
    for (const Vec2& p : std::vector<Vec2>{{0.2, -0.8}, {L * s.x() - 0.2, -0.8}, {L * s.x() - 0.2, L * s.y() - 0.5}}) {
      targets.push_back(w.add_displacement_target(base, p, Vec2(1, 0)));
      if (by_acceleration)
        w.set_target_acceleration_history(targets.back(), ground.acceleration_history());
      else
        w.set_target_history(targets.back(), ground.displacement_history());
      w.set_target_displacement(w.add_displacement_target(base, p, Vec2(0, 1)), Vec2::Zero());
    }
    Controls& c = w.controls();
    c.gravity = Vec2(0, -kG);
    if (dt == 0) return;  // everything else the engine's default
    c.g1 = dt;
    c.g2 = 0.01;
    c.gg = 1;
    c.contact_law = law;
  }
  double slip() const {
    const Vec2 relative = w.block_displacement(block) - w.target_point_displacement(targets[0]);
    return -relative.dot(Vec2(std::cos(alpha), std::sin(alpha)));
  }
  void run_to(double t_end) {
    while (w.time() < t_end - 1e-12) w.step();
  }
};

GroundMotion sine_motion(double amplitude, double frequency, double t_start, double t_end, double dt) {
  std::vector<double> a(static_cast<std::size_t>(std::round(t_end / dt)) + 1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = static_cast<double>(i) * dt - t_start;
    a[i] = t > 0 ? amplitude * std::sin(2 * M_PI * frequency * t) : 0;
  }
  return GroundMotion(dt, a, "sine");
}

// Under both contact laws (docs/contacts.md): the holding law's friction
// band follows the spread of the blocks' translations, not the translation
// the shaken base shares with the block (with the largest translation it slid
// 0.29 µm of the 6.3 cm here, 0.31 µm of El Centro's 20.8 cm).
void sine_above_and_below_yield(ContactLaw law) {
  // Reference: newmark_slip above, the rigid-plastic integration of the
  // same (piecewise linear) base acceleration. α = 20°, φ = 30°: yield
  // acceleration a_y = g tan(φ − α) = 1.730 m/s². A 2 Hz sine of 2 a_y for
  // 1 s after 0.1 s at rest: slip within 5 % (measured: shi +0.26 %,
  // holding +0.02 %); of 0.8 a_y: no slip (below 10 µm, 0.02 % of the slip above
  // yield; measured 0.3 µm, the contact's elastic give). Conditions: Shi's
  // scheme with gg = 1, Δt = 1 ms (held: g1), contact stiffness g0 = 50E.
  const double alpha = 20, phi = 30, dt = 1e-3, t_end = 1.6;
  const double a_y = kG * std::tan((phi - alpha) * M_PI / 180);
  for (const double ratio : {2.0, 0.8}) {
    const GroundMotion g = sine_motion(ratio * a_y, 2.0, 0.1, 1.1, dt);
    ShakenIncline model(alpha, phi, g, dt, law);
    model.run_to(t_end);
    const History a = g.acceleration_history();
    const double reference =
        newmark_slip([&](double t) { return a.value(t); }, alpha * M_PI / 180, phi * M_PI / 180, t_end);
    if (ratio > 1) {
      EXPECT_GT(reference, 0.05);  // it does slide: 6.3 cm
      EXPECT_NEAR(model.slip(), reference, 0.05 * reference);
      // The base driven by the acceleration itself (target acceleration = h).
      ShakenIncline by_acceleration(alpha, phi, g, dt, law, true);
      by_acceleration.run_to(t_end);
      EXPECT_NEAR(by_acceleration.slip(), reference, 0.05 * reference);
    } else {
      EXPECT_EQ(reference, 0);
      EXPECT_LT(std::abs(model.slip()), 1e-5);
    }
  }
}

// The incline above under the El Centro record (data/, baseline-corrected,
// resampled at 1 ms; a_y = 0.176 g under a PGA of 0.46 g), the first 12 s
// (the strong motion), against newmark_slip of the same record: the slip
// within `tolerance` of it. g1 = dt as above, or with dt = 0 nothing set but
// gravity (the engine's default law, integrator, time step and g2).
void expect_el_centro_slip(ContactLaw law, double dt, double tolerance) {
  const double alpha = 20, phi = 30, t_end = 12;
  const GroundMotion g = GroundMotion::read_accelerogram(std::string(DDA_SOURCE_DIR) +
                                                         "/data/imperial_valley_1979_el_centro_array7_S50W.dat")
                             .baseline_corrected(2)
                             .resampled(1e-3);
  ShakenIncline model(alpha, phi, g, dt, law);
  model.run_to(t_end);
  const History a = g.acceleration_history();
  const double reference =
      newmark_slip([&](double t) { return a.value(t); }, alpha * M_PI / 180, phi * M_PI / 180, t_end);
  EXPECT_GT(reference, 0.1);
  EXPECT_NEAR(model.slip(), reference, tolerance * reference);
  std::printf("El Centro, g1 = %g: slip %.6f m, rigid-plastic %.6f m (%+.3f %%), %ld steps\n", dt, model.slip(),
              reference, 100 * (model.slip() / reference - 1), model.w.step_count());
}

}  // namespace

// With nothing set: tolerance 0.5 % (measured +0.013 %, 1239 steps: the
// model moves as bodies, docs/time_step.md; under the paper's rule for waves
// in the blocks it took 1.7e-5 s steps and slid 12.9 % too far, its contacts
// chattering).
TEST(NewmarkSlidingBlock, ElCentroRecordUnderTheDefaults) { expect_el_centro_slip(ContactLaw::Holding, 0, 0.005); }
TEST(NewmarkSlidingBlock, SineAboveAndBelowYield) { sine_above_and_below_yield(ContactLaw::Shi); }
TEST(NewmarkSlidingBlock, SineAboveAndBelowYieldHoldingLaw) { sine_above_and_below_yield(ContactLaw::Holding); }
// At Δt = 1 ms: within 5 % (measured: shi −0.05 %, holding +0.02 %, of 20.8 cm).
TEST(NewmarkSlidingBlock, ElCentroRecord) { expect_el_centro_slip(ContactLaw::Shi, 1e-3, 0.05); }
TEST(NewmarkSlidingBlock, ElCentroRecordHoldingLaw) { expect_el_centro_slip(ContactLaw::Holding, 1e-3, 0.05); }

namespace {

enum class Wave { S, P };

// A soil or rock layer as a column of `n` glued square blocks (thickness H,
// density rho1, S-wave speed vs1) on a compliant base whose dashpots are
// those of a half-space (rho2, vs2), with a vertically incident S wave
// (particle velocity v_in(t) along x) or P wave (along y) brought in
// through it. Poisson's ratio 0.25, plane strain.
struct LayerOnHalfSpace {
  World w;
  std::vector<BlockId> column;
  Wave wave;
  LayerOnHalfSpace(Wave wave, int n, double H, double rho1, double vs1, double rho2, double vs2, const History& v_in,
                   double dt, Integrator integrator)
      : wave(wave) {
    const double nu = 0.25;
    const int layer = w.add_rock_material(RockMaterial{rho1, 2 * rho1 * vs1 * vs1 * (1 + nu), nu});
    const int half_space = w.add_rock_material(RockMaterial{rho2, 2 * rho2 * vs2 * vs2 * (1 + nu), nu});
    w.joint_material(0) = JointMaterial{45, 1e12, 1e12};  // glued: the layer is one body
    const double h = H / n;
    // The 1-D column (a layer of infinite extent): the sides' mid-height
    // points keep y under an S wave (simple shear leaves them there; bending
    // of the slender column would not) and keep x under a P wave (no
    // lateral strain: the constrained modulus of an infinite layer).
    const Vec2 held = wave == Wave::S ? Vec2(0, 1) : Vec2(1, 0);
    for (int i = 0; i < n; ++i) {
      column.push_back(w.add_block(test::rectangle(0, i * h, h, h), layer));
      for (const double x : {0.0, h})
        w.set_target_displacement(w.add_displacement_target(column.back(), Vec2(x, (i + 0.5) * h), held), Vec2::Zero());
    }
    const int base = w.add_viscous_boundary({{column[0], 0}}, half_space);  // edge 0: the bottom
    if (wave == Wave::S)
      w.set_incident_velocity(base, v_in, History());
    else
      w.set_incident_velocity(base, History(), v_in);
    Controls& c = w.controls();
    c.gravity = Vec2::Zero();
    c.g1 = dt;
    c.g2 = 0.01;
    c.gg = 1;
    c.plane = PlaneMode::Strain;
    c.integrator = integrator;
    // The 1-D column is made by holding each first-order block's sides (one
    // constant strain per block): the wave model's meshing for the pulse
    // would free the elements between the held points.
    c.mesh_size = 0;
  }
  double surface_velocity() const {
    const BlockId top = column.back();
    const auto v = w.block_vertices(top);
    const Vec2 u = w.velocity_at(top, 0.5 * (v[2] + v[3]));
    return wave == Wave::S ? u.x() : u.y();
  }
};

// |Σ x(t_i) e^{−iωt_i}|: the amplitude of a sampled series at frequency f.
double spectrum(const std::vector<double>& x, double dt, double f) {
  double re = 0, im = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double phase = 2 * M_PI * f * static_cast<double>(i) * dt;
    re += x[i] * std::cos(phase);
    im -= x[i] * std::sin(phase);
  }
  return std::hypot(re, im);
}

// Surface over outcrop (twice the incident wave) amplification of the
// layer, from a Gaussian velocity pulse broad enough to reach past the
// second resonance f2; returns {frequency, peak} near f1 and f2 (the largest
// amplification on a grid of steps of 0.1 % within ±10 % of each).
std::vector<std::pair<double, double>> resonances(Wave wave, double H, double rho1, double vs1, double rho2, double vs2,
                                                  double wave_speed, double dt, double t_end,
                                                  Integrator integrator = Integrator::Shi) {
  const double f1 = wave_speed / (4 * H), f2 = 3 * f1;
  const double tau = 1 / (2 * M_PI * f2), t0 = 4 * tau;
  std::vector<std::pair<double, double>> pulse;
  for (double t = 0; t <= 10 * tau; t += dt) pulse.emplace_back(t, 0.01 * std::exp(-std::pow((t - t0) / tau, 2)));
  const History v_in(pulse);
  LayerOnHalfSpace model(wave, 20, H, rho1, vs1, rho2, vs2, v_in, dt, integrator);
  std::vector<double> surface, outcrop;
  while (model.w.time() < t_end - 1e-12) {
    model.w.step();
    surface.push_back(model.surface_velocity());
    outcrop.push_back(2 * v_in.value(model.w.time()));
  }
  std::vector<std::pair<double, double>> peaks;
  for (const double fn : {f1, f2}) {
    std::pair<double, double> best{0, 0};
    for (double f = 0.9 * fn; f <= 1.1 * fn; f += 0.001 * fn)
      if (const double a = spectrum(surface, dt, f) / spectrum(outcrop, dt, f); a > best.second) best = {f, a};
    peaks.push_back(best);
  }
  return peaks;
}

// The tolerances: resonances f1 and 3·f1 within 3 %, their
// peaks within 5 % of 1/α.
void expect_resonances(const std::vector<std::pair<double, double>>& peaks, double f1, double alpha) {
  EXPECT_NEAR(peaks[0].first, f1, 0.03 * f1);
  EXPECT_NEAR(peaks[1].first, 3 * f1, 0.03 * 3 * f1);
  EXPECT_NEAR(peaks[0].second, 1 / alpha, 0.05 / alpha);
  EXPECT_NEAR(peaks[1].second, 1 / alpha, 0.05 / alpha);
}

}  // namespace

TEST(SiteResponse, LayerOnHalfSpaceThroughTheCompliantBaseS) {
  // Reference: the closed form for a damping-free layer on an elastic
  // half-space, |A(f)| = 1/sqrt(cos²(kH) + α² sin²(kH)), k = 2πf/Vs1,
  // α = ρ1·Vs1/(ρ2·Vs2): resonances at f1 = Vs1/4H and f2 = 3·f1 with peaks
  // 1/α. H = 20 m, Vs1 = 200 m/s, Vs2 = 400 m/s, ρ1 = ρ2 (α = 0.5): f1 =
  // 2.5 Hz, f2 = 7.5 Hz. Tolerances: frequencies 3 %, peaks 5 %.
  // Measured: f1 and f2 within 0.1 % (the search grid's step); peaks
  // −0.09 % and −1.83 % (Shi's scheme with gg = 1 damps the second;
  // Δt = 0.2 ms, 20 blocks).
  const double H = 20, rho = 2000, vs1 = 200, vs2 = 400, alpha = vs1 / vs2;
  const auto peaks = resonances(Wave::S, H, rho, vs1, rho, vs2, vs1, 2e-4, 4);
  const double f1 = vs1 / (4 * H);
  expect_resonances(peaks, f1, alpha);
}

TEST(SiteResponse, LayerOnHalfSpaceThroughTheCompliantBaseP) {
  // The same layer under a vertically incident P wave: the same closed form
  // with the P-wave speeds (plane strain, ν = 0.25: Vp = √3·Vs), α the same
  // 0.5; f1 = √3·2.5 Hz. Δt = 0.1 ms. Measured: f1 and f2 within 0.1 %,
  // peaks −0.04 % and −1.52 %.
  const double H = 20, rho = 2000, vs1 = 200, vs2 = 400, alpha = vs1 / vs2;
  const double vp1 = std::sqrt(3.0) * vs1;
  const auto peaks = resonances(Wave::P, H, rho, vs1, rho, vs2, vp1, 1e-4, 2.5);
  const double f1 = vp1 / (4 * H);
  expect_resonances(peaks, f1, alpha);
}

TEST(SiteResponse, LayerOnHalfSpaceUnderTheSecondOrderIntegrator) {
  // The site response with the second-order integrator:
  // the same closed form and tolerances as the two tests above (f1, f2
  // within 3 %, peaks within 5 % of 1/α = 2), the same models and steps,
  // under Newmark's average acceleration (no numerical damping, so the
  // second peak is no longer lowered by the scheme). Measured: S f1, f2
  // 2.4975, 7.5075 Hz (−0.1 %, +0.1 %), peaks 2.0030, 2.0071 (+0.15 %,
  // +0.36 %); P 4.3258, 13.0034 Hz (−0.1 %, +0.1 %), peaks 2.0035, 2.0076.
  const double H = 20, rho = 2000, vs1 = 200, vs2 = 400, alpha = vs1 / vs2;
  const auto s = resonances(Wave::S, H, rho, vs1, rho, vs2, vs1, 2e-4, 4, Integrator::Newmark);
  expect_resonances(s, vs1 / (4 * H), alpha);
  const double vp1 = std::sqrt(3.0) * vs1;
  const auto p = resonances(Wave::P, H, rho, vs1, rho, vs2, vp1, 1e-4, 2.5, Integrator::Newmark);
  expect_resonances(p, vp1 / (4 * H), alpha);
}

namespace {

// A flat-topped model: a rectangle of glued square blocks (5 columns × 10
// rows of 2 m) on a compliant base with a vertically incident S-wave pulse,
// its sides free-field sides, or free. Returns the horizontal velocity of
// every top vertex at every step, and (free-field sides) the left column's
// surface velocity at every step.
struct FlatTopRun {
  std::vector<std::vector<double>> top;  // [step][vertex]
  std::vector<double> column;            // [step]
};
FlatTopRun run_flat_top(bool free_field_sides) {
  const int columns = 5, rows = 10;
  const double h = 2, rho = 2000, vs = 200, nu = 0.25, dt = 2e-4, t_end = 0.8;
  World w;
  const int rock = w.add_rock_material(RockMaterial{rho, 2 * rho * vs * vs * (1 + nu), nu});
  const int bedrock = w.add_rock_material(RockMaterial{rho, 2 * rho * 400 * 400 * (1 + nu), nu});
  w.joint_material(0) = JointMaterial{45, 1e12, 1e12};  // glued
  std::vector<std::vector<BlockId>> grid(rows, std::vector<BlockId>(columns));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) grid[r][c] = w.add_block(test::rectangle(c * h, r * h, h, h), rock);
  Controls& ctl = w.controls();
  ctl.gravity = Vec2::Zero();
  ctl.g1 = dt;
  ctl.g2 = 0.01;
  ctl.gg = 1;
  ctl.plane = PlaneMode::Strain;
  // First-order blocks: the top is read at each block's corners, and the
  // free-field column is checked against the blocks it borders.
  ctl.mesh_size = 0;
  // A Gaussian pulse of the incident velocity, mostly below 10 Hz (20 m
  // wavelength, 10 blocks).
  const double tau = 0.03, t0 = 0.1;
  std::vector<std::pair<double, double>> pulse;
  for (double t = 0; t <= 0.2; t += dt) pulse.emplace_back(t, 0.01 * std::exp(-std::pow((t - t0) / tau, 2)));
  std::vector<EdgeRef> bottom, left, right;
  for (int c = 0; c < columns; ++c) bottom.push_back({grid[0][c], 0});
  for (int r = 0; r < rows; ++r) {
    left.push_back({grid[r][0], 3});
    right.push_back({grid[r][columns - 1], 1});
  }
  const int base = w.add_viscous_boundary(bottom, bedrock);
  w.set_incident_velocity(base, History(pulse), History());
  int ff_left = -1;
  if (free_field_sides) {
    ff_left = w.add_free_field(left, base);
    w.add_free_field(right, base);
  }
  FlatTopRun run;
  while (w.time() < t_end - 1e-12) {
    w.step();
    if (ff_left >= 0) run.column.push_back(w.free_field_velocity(ff_left, rows * h).x());
    run.top.emplace_back();
    for (int c = 0; c < columns; ++c) {
      const auto v = w.block_vertices(grid[rows - 1][c]);
      for (int k : {2, 3}) run.top.back().push_back(w.velocity_at(grid[rows - 1][c], v[k]).x());
    }
  }
  return run;
}

// The largest difference between the top's velocity and the column's,
// over the column's peak.
double worst_against(const FlatTopRun& run, const std::vector<double>& column) {
  double worst = 0, peak = 0;
  for (std::size_t i = 0; i < column.size(); ++i) {
    peak = std::max(peak, std::abs(column[i]));
    for (const double v : run.top[i]) worst = std::max(worst, std::abs(v - column[i]));
  }
  return worst / peak;
}

}  // namespace

TEST(FreeField, FlatTopMovesAsTheColumn) {
  // Reference: the 1-D column's surface velocity (its own computation,
  // driven by the same incident wave). A flat-topped model with free-field
  // sides must move as the column all along its top, within 2 % of the
  // column's peak at every vertex and step. Measured 0.11 %.
  // With free sides the same model is off by far more (measured 56 %; with
  // the free field's dashpots but not its stresses, 13 %).
  const FlatTopRun with = run_flat_top(true);
  const FlatTopRun free = run_flat_top(false);
  ASSERT_EQ(with.top.size(), free.top.size());  // the same steps (no cut)
  EXPECT_LT(worst_against(with, with.column), 0.02);
  EXPECT_GT(worst_against(free, with.column), 0.05);
}
