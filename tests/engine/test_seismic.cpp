// Shaking a model: Newmark's sliding block on a rigid shaken base, and the
// compliant (quiet) base with an incident wave (docs/seismic.md).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "../scenes.hpp"
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
  ShakenIncline(double alpha_deg, double phi_deg, const History& ground_displacement, double dt) {
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
      w.set_target_history(targets.back(), ground_displacement);
      w.set_target_displacement(w.add_displacement_target(base, p, Vec2(0, 1)), Vec2::Zero());
    }
    Controls& c = w.controls();
    c.gravity = Vec2(0, -kG);
    c.g1 = dt;
    c.g2 = 0.01;
    c.gg = 1;
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

}  // namespace

TEST(NewmarkSlidingBlock, SineAboveAndBelowYield) {
  // Reference: newmark_slip above, the rigid-plastic integration of the
  // same (piecewise linear) base acceleration. α = 20°, φ = 30°: yield
  // acceleration a_y = g tan(φ − α) = 1.730 m/s². A 2 Hz sine of 2 a_y for
  // 1 s after 0.1 s at rest: slip within 5 % (measured 0.3 %); of 0.8 a_y:
  // no slip (below 10 µm, 0.02 % of the slip above yield; measured 0.3 µm,
  // the contact's elastic give). Conditions: Shi's scheme with gg = 1,
  // Δt = 1 ms (held: g1), contact stiffness g0 = 50E.
  const double alpha = 20, phi = 30, dt = 1e-3, t_end = 1.6;
  const double a_y = kG * std::tan((phi - alpha) * M_PI / 180);
  for (const double ratio : {2.0, 0.8}) {
    const GroundMotion g = sine_motion(ratio * a_y, 2.0, 0.1, 1.1, dt);
    ShakenIncline model(alpha, phi, g.displacement_history(), dt);
    model.run_to(t_end);
    const History a = g.acceleration_history();
    const double reference =
        newmark_slip([&](double t) { return a.value(t); }, alpha * M_PI / 180, phi * M_PI / 180, t_end);
    if (ratio > 1) {
      EXPECT_GT(reference, 0.05);  // it does slide: 6.3 cm
      EXPECT_NEAR(model.slip(), reference, 0.05 * reference);
    } else {
      EXPECT_EQ(reference, 0);
      EXPECT_LT(std::abs(model.slip()), 1e-5);
    }
  }
}

TEST(NewmarkSlidingBlock, ElCentroRecord) {
  // Reference: newmark_slip of the same record (data/, baseline-corrected,
  // resampled to the step). The same incline (a_y = 0.176 g under a PGA of
  // 0.46 g), the first 12 s (the strong motion): slip within 5 % (measured
  // 0.05 %, 20.8 cm). Conditions as above.
  const double alpha = 20, phi = 30, dt = 1e-3, t_end = 12;
  const GroundMotion g = GroundMotion::read_accelerogram(std::string(DDA_SOURCE_DIR) +
                                                         "/data/imperial_valley_1979_el_centro_array7_S50W.dat")
                             .baseline_corrected(2)
                             .resampled(dt);
  ShakenIncline model(alpha, phi, g.displacement_history(), dt);
  model.run_to(t_end);
  const History a = g.acceleration_history();
  const double reference =
      newmark_slip([&](double t) { return a.value(t); }, alpha * M_PI / 180, phi * M_PI / 180, t_end);
  EXPECT_GT(reference, 0.1);
  EXPECT_NEAR(model.slip(), reference, 0.05 * reference);
}
