// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The landing law (control `restitution`; contact/landing.hpp,
// docs/landings.md) against the rigid-body impact
// law's closed forms: a block that lands leaves its face at e times its
// approach speed, and its contact points stop if Coulomb's bound on the
// impulse, μ·(1 + e)·m·v_n, allows, else slide on at v_t − μ(1 + e)v_n; the
// same at every Δt. The blocks are elastic granite (E = 5 GPa, 2600 kg/m³)
// on springs of g0 = 50 E: the references are a rigid block's, the
// tolerances the step's own error where it shows.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../scenes.hpp"
#include "core/error.hpp"
#include "world/checkpoint.hpp"

using namespace dda;

namespace {

constexpr double kG = 9.81;

// A 1 m × 0.5 m block whose bottom starts `height` above the flat top of a
// fixed 8 m base (y = 0), moving at vx along it; friction φ; gravity.
struct Drop {
  World w;
  BlockId block = -1;
  double height;

  double vy0;  // its normal velocity at the start (down: negative)

  Drop(double height_, double vx, double phi_deg, double restitution, double dt, ContactLaw law = ContactLaw::Holding,
       double vy = 0)
      : height(height_), vy0(vy) {
    const int rock = w.add_rock_material(test::granite());
    w.joint_material(0) = JointMaterial{phi_deg, 0, 0};
    test::add_fixed_block(w, test::rectangle(-4, -1, 8, 1), rock);
    block = w.add_block(test::rectangle(-2, height, 1, 0.5), rock);
    w.set_block_velocity(block, Vec6(vx, vy, 0, 0, 0, 0));
    w.controls().gravity = Vec2(0, -kG);
    w.controls().g1 = dt;
    w.controls().contact_law = law;
    w.controls().restitution = restitution;
  }
  // The closed form's landing: time and normal speed.
  double landing_speed() const { return std::sqrt(vy0 * vy0 + 2 * kG * height); }
  double landing_time() const { return (landing_speed() + vy0) / kG; }
  Vec2 centroid() const { return w.block_centroid(block); }
  Vec6 velocity() const { return w.block_velocity(block); }
  void run_to(double t) {
    while (w.time() < t - 1e-9 * w.controls().g1) w.step();
  }
};

std::string at(double dt) { return "Δt " + std::to_string(dt) + " s"; }

}  // namespace

// A flat block dropped flat (from 1 m, v_n = 4.43 m/s) onto a frictionless
// face leaves it at e·v_n. Reference: the rigid block's flight after the
// landing, v_y(t) = e·v_n − g(t − t_L) and its height above its resting
// place e·v_n(t − t_L) − ½g(t − t_L)², sampled at half the time to the apex.
// Tolerance: 1e-3 of v_n in speed and 1e-3 of the rebound's height (the
// landing is solved exactly: t_L from the step's gap and approach).
TEST(Landing, FlatBlockOnAFrictionlessFaceReboundsAtEVn) {
  for (const double dt : {1e-2, 1e-3, 1e-4, 1e-5})
    for (const double e : {0.5, 1.0}) {
      Drop s(1.0, 0, 0, e, dt);
      const double y_rest = s.centroid().y() - s.height;  // the centroid's height resting on the face
      const double t_land = s.landing_time(), v_n = s.landing_speed();
      const double flight = e * v_n / kG;  // to the apex
      s.run_to(t_land + 0.5 * flight);
      const double t = s.w.time() - t_land;
      const std::string name = at(dt) + ", e " + std::to_string(e);
      EXPECT_NEAR(s.velocity()[1], e * v_n - kG * t, 1e-3 * v_n) << name;
      const double rise = e * v_n * t - 0.5 * kG * t * t;
      EXPECT_NEAR(s.centroid().y() - y_rest, rise, 1e-3 * rise) << name;
      EXPECT_NEAR(s.velocity()[0], 0, 1e-9) << name;
    }
}

// e = 0: the block stays down. Reference: at rest on the face after the
// landing; bounds: its centroid never rises more than 1 µm above its
// resting place after the landing, and at 0.2 s after it moves slower than
// 1 mm/s.
TEST(Landing, FlatBlockWithZeroRestitutionStaysDown) {
  for (const double dt : {1e-2, 1e-3, 1e-4, 1e-5}) {
    Drop s(1.0, 0, 0, 0, dt);
    const double y_rest = s.centroid().y() - s.height;
    const double t_land = s.landing_time();
    s.run_to(t_land + dt);
    double highest = -1;
    int landings = 0;
    while (s.w.time() < t_land + 0.2 - 1e-9 * dt) {
      landings += s.w.step().landings;
      highest = std::max(highest, s.centroid().y() - y_rest);
    }
    EXPECT_LT(highest, 1e-6) << at(dt);
    EXPECT_LT(s.velocity().head<2>().norm(), 1e-3) << at(dt);
    EXPECT_EQ(landings, 0) << at(dt) << ": landed again";
  }
}

// The hard landing of docs/landings.md's Known limits: a block moving at
// 2 m/s along a flat face lands on it at v_n = 7.67 m/s (a 3 m drop; here it
// starts 5 cm above the face at the speed it would have there), φ = 45°,
// e = 0. Coulomb's bound on the landing's impulse, μ·m·v_n = 7.67 m·m/s,
// exceeds its 2 m/s along the face: a rigid block stops where it lands.
// Reference: the landing point x_L = x₀ + v_t·t_L; bounds: the centroid ends
// within 1 mm of it, moves back from its furthest point by less than
// 0.1 mm, and at 0.3 s after the landing moves slower than 1 mm/s; under
// both contact laws. Before (restitution off) it left the landing at
// −1.42 m/s (Δt = 1e-3 s).
void expect_hard_landing_stops(double dt, ContactLaw law) {
  const double v_drop = -std::sqrt(2 * kG * 2.95);
  Drop s(0.05, 2, 45, 0, dt, law, v_drop);
  const std::string name = at(dt) + (law == ContactLaw::Shi ? ", shi" : ", holding");
  const double x0 = s.centroid().x(), t_land = s.landing_time();
  ASSERT_NEAR(s.landing_speed(), std::sqrt(2 * kG * 3.0), 1e-12);
  double furthest = 0;
  while (s.w.time() < t_land + 0.3 - 1e-9 * dt) {
    s.w.step();
    furthest = std::max(furthest, s.centroid().x() - x0);
  }
  const double x = s.centroid().x() - x0;
  EXPECT_NEAR(x, 2 * t_land, 1e-3) << name;
  EXPECT_LT(furthest - x, 1e-4) << name;
  EXPECT_LT(s.velocity().head<2>().norm(), 1e-3) << name;
}

TEST(Landing, HardLandingOnARoughFaceEndsWhereItLands) {
  for (const ContactLaw law : {ContactLaw::Holding, ContactLaw::Shi})
    for (const double dt : {1e-2, 1e-3, 1e-4, 1e-5}) expect_hard_landing_stops(dt, law);
}

// A low-friction landing: 2 m/s along the face, v_n = 1.40 m/s (a 0.1 m
// drop), φ = 10°, e = 0: μ(1 + e)v_n = 0.247 m/s < v_t, so the block slides
// on at v_t − μ(1 + e)v_n = 1.753 m/s, decelerating at μg from the landing
// on. Reference: v_x(t) = v_t − μ(1 + e)v_n − μg(t − t_L), at the end of the
// landing step (both laws) and at t_L + 0.1 s (`"holding"`: under `"shi"`
// a block sliding on a face decelerates several times too fast at first,
// docs/landings.md, Known limits); tolerance 1e-3 of v_t; v_y below 1 mm/s.
TEST(Landing, LowFrictionLandingSlidesOnAtVtLessMuVn) {
  const double mu = std::tan(deg_to_rad(10));
  for (const ContactLaw law : {ContactLaw::Holding, ContactLaw::Shi})
    for (const double dt : {1e-2, 1e-3, 1e-4, 1e-5}) {
      Drop s(0.1, 2, 10, 0, dt, law);
      const double t_land = s.landing_time(), v_n = s.landing_speed();
      ASSERT_LT(mu * v_n, 2);
      const std::string name = at(dt) + (law == ContactLaw::Shi ? ", shi" : ", holding");
      auto expect_slide = [&](const char* when) {
        const double t = s.w.time() - t_land;
        EXPECT_NEAR(s.velocity()[0], 2 - mu * v_n - mu * kG * t, 1e-3 * 2) << name << when;
        EXPECT_LT(std::abs(s.velocity()[1]), 1e-3) << name << when;
      };
      int landings = 0;
      while (landings == 0) landings = s.w.step().landings;
      expect_slide(", landing step");
      if (law == ContactLaw::Shi || dt < 1e-4) continue;
      s.run_to(t_land + 0.1);
      expect_slide(", 0.1 s on");
    }
}

// The knife-edge of Friction.BlockLandingOnAFlatFaceFromOneMetreEndsWhereItLands
// (2 m/s along the face, φ = 45°, Δt = 1e-3 s) with the landing law, e = 0:
// dropped from 0.98 to 1.02 m it ends where it lands. Reference: no motion
// back; bounds as that test's: 0.1 mm back from its furthest point, below
// 1 mm/s at 1 s. (Without the law: 0.06 to 0.77 m back.)
TEST(Landing, BlockDroppedFromAboutOneMetreEndsWhereItLands) {
  for (const ContactLaw law : {ContactLaw::Holding, ContactLaw::Shi})
    for (const double height : {0.98, 0.99, 1.0, 1.01, 1.02}) {
      World w;
      const int rock = w.add_rock_material(test::granite());
      w.joint_material(0) = JointMaterial{45, 0, 0};
      test::add_fixed_block(w, test::rectangle(-4, -1, 8, 1), rock);
      const BlockId block = w.add_block(test::rectangle(0, height, 1, 0.5), rock);
      w.set_block_velocity(block, Vec6(2, 0, 0, 0, 0, 0));
      w.controls().gravity = Vec2(0, -kG);
      w.controls().g1 = 1e-3;
      w.controls().contact_law = law;
      w.controls().restitution = 0;
      const double x0 = w.block_centroid(block).x();
      double furthest = 0;
      while (w.time() < 1.0 - 1e-9) {
        w.step();
        furthest = std::max(furthest, w.block_centroid(block).x() - x0);
      }
      const std::string name = std::to_string(height) + " m, " + (law == ContactLaw::Shi ? "shi" : "holding");
      ASSERT_GT(furthest, 0.85) << name;
      EXPECT_LT(furthest - (w.block_centroid(block).x() - x0), 1e-4) << name;
      EXPECT_LT(std::abs(w.block_velocity(block)[0]), 1e-3) << name;
    }
}

// The energy budget books the impact: a flat block dropped 1 m onto a
// frictionless face with e = 0 loses its landing's kinetic energy,
// ½·m·v_n², to the impact term (tolerance 1e-3 of it), and the residual
// over the run stays the integrator's: below 1e-4 of that energy.
TEST(Landing, EnergyBudgetBooksTheImpact) {
  for (const double dt : {1e-2, 1e-3, 1e-4, 1e-5}) {
    Drop s(1.0, 0, 0, 0, dt);
    s.run_to(s.landing_time() + 0.02);
    const double lost = 0.5 * s.w.block_mass(s.block) * s.landing_speed() * s.landing_speed();
    EXPECT_NEAR(s.w.energy().total.impact, -lost, 1e-3 * lost) << at(dt);
    EXPECT_LT(std::abs(s.w.energy().total.residual), 1e-4 * lost) << at(dt);
  }
}

// A block put down on a face does not land: touching at the start, gravity
// switched on at once, it rings on its springs (at up to g/ω, and its
// strains at mm/s at its corners), and no contact of it counts as landing:
// the run is the one without the law, bit for bit (reference: the state
// hash without it). On a 15° incline that friction holds (φ = 20°) over
// 0.3 s and on a flat face over 0.05 s, at Δt = 1e-2 to 1e-5 s.
TEST(Landing, BlockPutDownOnAFaceDoesNotLand) {
  for (const double angle : {15.0, 0.0})
    for (const double dt : {1e-2, 1e-3, 1e-4, 1e-5}) {
      World with, without;
      for (World* w : {&with, &without}) {
        test::block_on_incline(*w, deg_to_rad(angle), 20);
        w->controls().g1 = dt;
        w->controls().contact_law = ContactLaw::Holding;
      }
      with.controls().restitution = 0;
      int landings = 0;
      const double t_end = angle == 0 ? 0.05 : dt < 1e-4 ? 0.02 : 0.3;
      while (with.time() < t_end - 1e-9 * dt) {
        landings += with.step().landings;
        without.step();
      }
      EXPECT_EQ(landings, 0) << angle << "°, " << at(dt);
      EXPECT_EQ(with.state_hash(), without.state_hash()) << angle << "°, " << at(dt);
    }
}

// Blocks landing on the base and on each other: three blocks dropped
// (e = 0.3, φ = 30°; landings of a block another contact holds are left to
// the springs) give the same bits with 1 and 2 threads (the impacts are
// solved serially, in the contact list's order), and a run restored from a
// checkpoint taken mid-way (after the first landings) continues bit for bit.
struct Pile {
  World w;
  explicit Pile(int threads) {
    const int rock = w.add_rock_material(test::granite());
    w.joint_material(0) = JointMaterial{30, 0, 0};
    test::add_fixed_block(w, test::rectangle(-4, -1, 8, 1), rock);
    w.add_block(test::rectangle(-0.5, 0.2, 1, 0.5), rock);
    w.add_block(test::rectangle(-0.2, 0.9, 1, 0.5), rock);
    w.add_block(test::rectangle(0.6, 1.6, 0.8, 0.4), rock);
    w.set_block_velocity(3, Vec6(-0.5, 0, 0, 0, 0, 0));
    w.controls().gravity = Vec2(0, -kG);
    w.controls().g1 = 1e-3;
    w.controls().contact_law = ContactLaw::Holding;
    w.controls().restitution = 0.3;
    w.controls().threads = threads;
  }
};

TEST(Landing, SameBitsForAnyThreadCountAndThroughACheckpoint) {
  Pile one(1), two(2);
  int landings = 0;
  for (int k = 0; k < 300; ++k) {
    landings += one.w.step().landings;
    two.w.step();
  }
  ASSERT_GT(landings, 2);
  EXPECT_EQ(one.w.state_hash(), two.w.state_hash());
  Checkpoint restored = checkpoint_from_bytes(checkpoint_bytes(one.w), "pile");
  for (int k = 0; k < 300; ++k) {
    one.w.step();
    restored.world.step();
  }
  EXPECT_EQ(restored.world.state_hash(), one.w.state_hash());
  EXPECT_EQ(restored.world.energy().total.impact, one.w.energy().total.impact);
}

// The control: -1 (off) or 0 ≤ e ≤ 1, and Shi's integrator only, first-order
// blocks only, each refused with its cause and cure.
TEST(Landing, ControlIsValidatedWithItsCauseAndCure) {
  auto message = [](auto&& set) {
    Drop s(0.1, 0, 0, 0, 1e-3);
    set(s.w);
    try {
      s.w.step();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const double e : {-0.5, 1.5, -2.0})
    EXPECT_NE(message([&](World& w) { w.controls().restitution = e; }).find("must be -1 (off) or lie in [0, 1]"),
              std::string::npos)
        << e;
  for (const Integrator integrator : {Integrator::Newmark, Integrator::GeneralizedAlpha}) {
    const std::string refused = message([&](World& w) { w.controls().integrator = integrator; });
    EXPECT_NE(refused.find("restitution (the landing law) works with integrator = \"shi\" only"), std::string::npos)
        << refused;
  }
  EXPECT_TRUE(message([](World& w) { w.controls().restitution = -1; }).empty());
}
