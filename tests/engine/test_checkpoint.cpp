// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Checkpoint and restart (world/checkpoint.hpp): a World saved after N steps
// and loaded into a fresh one continues bit for bit (reference: the same
// World stepped N + M times straight; tolerance: none, the state hashes are
// equal), for any thread count; a file that is not a checkpoint, or is
// truncated, damaged or of another format, is refused with a message that
// says so.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "../scenes.hpp"
#include "core/error.hpp"
#include "world/checkpoint.hpp"

namespace dda {
namespace {

using Scene = std::function<World()>;

// The kicked bar of 1 m blocks with cohesionless joints: contacts open and
// close behind the wave, the list is reused between searches (Verlet), and
// the solver re-solves on patches.
World bar() {
  World w = test::kicked_bar(30, 2, 1.0);
  w.joint_material(0) = JointMaterial{30, 0, 0};
  return w;
}

// A blast in small: 12 × 4 blocks of 1 m with weak joints; a pressure pulse
// (5 MPa over 0.2 ms, a history) on the left edges, viscous boundaries (VBC)
// on the right edges, a fixed point under each bottom block and gravity.
World blast() {
  World w;
  const int rock = w.add_rock_material(RockMaterial{2600, 30e9, 0.25});
  w.joint_material(0) = JointMaterial{35, 0.5e6, 0.2e6};
  const int cols = 12, rows = 4;
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r < rows; ++r) w.add_block(test::rectangle(c, r, 1, 1), rock);
  std::vector<EdgeRef> left, right;
  for (int r = 0; r < rows; ++r) {
    left.push_back({r, 3});                       // x = 0 edges (rectangle: bottom, right, top, left)
    right.push_back({(cols - 1) * rows + r, 1});  // x = cols edges
  }
  const int p = w.add_pressure_load(left, 0);
  w.set_pressure_history(p, History({{0, 0}, {1e-4, 5e6}, {2e-4, 0}}));
  w.add_viscous_boundary(right);
  for (int c = 0; c < cols; ++c) w.add_fixed_point(c * rows, Vec2(c + 0.5, 0.05));
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g0 = 20 * 30e9;
  w.controls().g1 = 1e-5;
  w.controls().mesh_size = 0;  // first-order blocks under the pulse (docs/waves.md)
  return w;
}

// A 1 m × 0.5 m block sliding down a fixed 30° incline (φ = 20°).
World slope() {
  World w;
  const double a = deg_to_rad(30);
  const int rock = w.add_rock_material(test::granite());
  w.joint_material(0) = JointMaterial{20, 0, 0};
  test::add_fixed_base(w, test::rotated(test::rectangle(-10, -1, 20, 1), a), rock);
  w.add_block(test::rotated(test::rectangle(2, 0, 1, 0.5), a), rock);
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g1 = 1e-3;
  return w;
}

std::uint64_t straight(const Scene& make, int steps, int threads) {
  World w = make();
  w.controls().threads = threads;
  for (int i = 0; i < steps; ++i) w.step();
  return w.state_hash();
}

// n steps, a checkpoint, a fresh World from it, m more steps.
std::uint64_t restarted(const Scene& make, int n, int m, int threads) {
  World w = make();
  w.controls().threads = threads;
  for (int i = 0; i < n; ++i) w.step();
  const std::string bytes = checkpoint_bytes(w);
  w = World();  // nothing of the first World survives
  Checkpoint c = checkpoint_from_bytes(bytes, "checkpoint");
  EXPECT_EQ(c.world.step_count(), n);
  for (int i = 0; i < m; ++i) c.world.step();
  return c.world.state_hash();
}

void expect_restart_exact(const Scene& make, int n, int m) {
  const std::uint64_t reference = straight(make, n + m, 1);
  for (int threads : {1, 2}) {
    EXPECT_EQ(straight(make, n + m, threads), reference) << threads << " threads";
    EXPECT_EQ(restarted(make, n, m, threads), reference)
        << "restart after " << n << " steps, " << threads << " threads";
  }
}

}  // namespace

TEST(Checkpoint, BarContinuesBitForBit) {
  // The restart falls between two contact searches (the list is reused).
  expect_restart_exact(bar, 37, 60);
}

TEST(Checkpoint, BlastContinuesBitForBit) {
  World w = blast();
  for (int i = 0; i < 60; ++i) w.step();
  int failed = 0;
  for (const Contact& c : w.contacts()) failed += !c.intact && c.state != ContactState::Open;
  ASSERT_GT(failed, 0) << "no joint failed: the test would not carry failure state over";
  expect_restart_exact(blast, 25, 35);
}

TEST(Checkpoint, SlidingSlopeContinuesBitForBit) {
  World w = slope();
  for (int i = 0; i < 120; ++i) w.step();
  int sliding = 0;
  for (const Contact& c : w.contacts()) sliding += c.state == ContactState::Sliding;
  ASSERT_GT(sliding, 0) << "the block does not slide: the test would not carry friction state over";
  expect_restart_exact(slope, 80, 80);
}

// Friction that lags the normal force (friction_lag) carries each closed
// contact's lagged normal force from step to step: the sliding block
// checkpointed while that force still trails N (gravity on at once, 1 ms
// in) continues bit for bit.
TEST(Checkpoint, LaggedFrictionContinuesBitForBit) {
  const auto scene = [] {
    World w = slope();
    w.controls().contact_law = ContactLaw::Holding;
    w.controls().friction_lag = 3e-3;
    w.controls().g1 = 1e-4;
    return w;
  };
  World w = scene();
  for (int i = 0; i < 10; ++i) w.step();
  double trailing = 0;
  for (std::size_t i = 0; i < w.contacts().size(); ++i) {
    const FrictionMemory& m = test::friction_memory(w, i);
    if (m.age > 0) trailing = std::max(trailing, std::abs(m.normal - w.contacts()[i].normal_force));
  }
  ASSERT_GT(trailing, 100) << "the lagged force does not trail N: the test would not carry it over";
  expect_restart_exact(scene, 10, 40);
}

// The aligned edges the contact search watches (narrow_phase.hpp) are part of
// what the list's staleness is measured from: a block sliding past an
// aligned corner, checkpointed between two of the searches they cause.
TEST(Checkpoint, SlidePastAnAlignedCornerContinuesBitForBit) {
  expect_restart_exact([] { return test::block_sliding_past_aligned_corner(ContactLaw::Shi); }, 12, 40);
}

TEST(Checkpoint, SecondOrderIntegratorsContinueBitForBit) {
  // Newmark and generalized-α carry the blocks' accelerations (and the
  // out-of-balance force) from step to step; the energy budget is cumulative.
  for (Integrator scheme : {Integrator::Newmark, Integrator::GeneralizedAlpha}) {
    const auto scene = [scheme] {
      World w = blast();
      w.controls().integrator = scheme;
      if (scheme == Integrator::GeneralizedAlpha) w.controls().rho_inf = 0.6;  // (only it reads ρ∞)
      return w;
    };
    expect_restart_exact(scene, 25, 35);
    World a = scene();
    for (int i = 0; i < 60; ++i) a.step();
    World b = scene();
    for (int i = 0; i < 25; ++i) b.step();
    Checkpoint c = checkpoint_from_bytes(checkpoint_bytes(b), "checkpoint");
    for (int i = 0; i < 35; ++i) c.world.step();
    EXPECT_EQ(c.world.energy().total.residual, a.energy().total.residual);
    EXPECT_EQ(c.world.energy().total.viscous, a.energy().total.viscous);
  }
}

TEST(Checkpoint, BeforeTheFirstStepAsAfter) {
  // A model saved before it stepped (a branch point set up by a script).
  expect_restart_exact(slope, 0, 30);
}

TEST(Checkpoint, QuasiStaticWallContinuesBitForBit) {
  // Long solves (the stored-product regime) and multigrid, chosen from the
  // iteration counts of the steps before.
  expect_restart_exact([] { return test::brick_wall(10); }, 6, 6);
}

TEST(Checkpoint, MultigridPreconditionedWallContinuesBitForBit) {
  // The multigrid hierarchy is kept while the matrix pattern holds: it is
  // part of the state.
  expect_restart_exact(
      [] {
        World w = test::brick_wall(10);
        w.controls().solver.pcg.preconditioner = Preconditioning::Multigrid;
        return w;
      },
      6, 6);
}

TEST(Checkpoint, WallOnTheKeptFactorContinuesBitForBit) {
  // The CHOLMOD factor is kept across steps: the checkpoint stores the matrix
  // it was made from and the restored run factorises it again.
  const auto wall = [] {
    World w = test::brick_wall(10);
    w.controls().solver.kind = SolverKind::Cholmod;
    return w;
  };
  World w = wall();
  for (int i = 0; i < 6; ++i) w.step();
  EXPECT_STREQ(w.last_stats().solver, "cholmod");
  expect_restart_exact(wall, 6, 6);
}

TEST(Checkpoint, WallThroughTheAutomaticChoicesTrialContinuesBitForBit) {
  // The automatic choice makes the trial's factor as step 1 ends, tries it
  // in step 2 and measures PCG in step 3 (solver_choice.hpp): a checkpoint
  // after step 1 holds that factor, one after step 2 the trial's work.
  const auto wall = [] { return test::brick_wall(10); };
  expect_restart_exact(wall, 1, 4);
  expect_restart_exact(wall, 2, 3);
}

TEST(Checkpoint, FileRoundTripAndAtomicWrite) {
  const auto dir = std::filesystem::temp_directory_path() / "dda_checkpoint_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "slope.ckpt";
  World w = slope();
  for (int i = 0; i < 10; ++i) w.step();
  save_checkpoint(w, path, "extra bytes");
  EXPECT_FALSE(std::filesystem::exists(dir / "slope.ckpt.part"));
  Checkpoint c = load_checkpoint(path);
  EXPECT_EQ(c.extra, "extra bytes");
  EXPECT_EQ(c.world.state_hash(), w.state_hash());
  // A write that fails names the file and the cause, and leaves the old file.
  try {
    save_checkpoint(w, dir / "no such folder" / "x.ckpt");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x.ckpt': No such file or directory"), std::string::npos) << e.what();
  }
  try {
    load_checkpoint(dir / "missing.ckpt");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.ckpt': No such file or directory"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

namespace {
void expect_refused(const std::string& bytes, const std::string& words) {
  try {
    checkpoint_from_bytes(bytes, "checkpoint 'x'");
    ADD_FAILURE() << "accepted; expected: " << words;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("checkpoint 'x' ", 0), 0u) << e.what();
  }
}
}  // namespace

TEST(Checkpoint, WrongTruncatedDamagedOrNewerFilesAreRefused) {
  World w = slope();
  for (int i = 0; i < 3; ++i) w.step();
  const std::string good = checkpoint_bytes(w);
  EXPECT_NO_THROW(checkpoint_from_bytes(good, "checkpoint 'x'"));

  expect_refused("-- a Lua script\nlocal m = dda.model{}\n", "is not a dda checkpoint");
  expect_refused("", "is not a dda checkpoint");
  expect_refused(good.substr(0, 5), "is truncated");
  expect_refused(good.substr(0, 20), "is truncated");
  expect_refused(good.substr(0, good.size() - 1), "is truncated");
  expect_refused(good + "x", "bytes after its end");
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  expect_refused(flipped, "is damaged: its checksum does not match");
  std::string header = good;
  header[9] ^= 0x01;  // the format number, without fixing the header's checksum
  expect_refused(header, "is damaged: its header's checksum");

  // Another format, with a consistent header: refused by its number.
  auto with_format = [&](std::uint32_t format) {
    std::string b = good;
    std::memcpy(b.data() + 8, &format, 4);
    const auto crc = static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(b.data()), 28));
    std::memcpy(b.data() + 28, &crc, 4);
    return b;
  };
  expect_refused(with_format(kCheckpointFormat + 1), "written by a newer dda");
  if (kCheckpointFormat > 1) expect_refused(with_format(kCheckpointFormat - 1), "written by an older dda");
  EXPECT_NO_THROW(checkpoint_from_bytes(with_format(kCheckpointFormat), "checkpoint 'x'"));
}

TEST(Checkpoint, MeshedBlocksContinueBitForBit) {
  // A meshed block (its nodes, inner edges and mesh ids; docs/meshed_blocks.md)
  // dropped onto a fixed base under the second-order scheme.
  const auto scene = [] {
    World w;
    w.controls().gravity = Vec2(0, -9.81);
    w.controls().g1 = 1e-3;
    w.controls().integrator = Integrator::Newmark;
    const int base = w.add_rock_material(test::granite());
    RockMaterial meshed = test::granite();
    meshed.mesh_size = 0.25;
    const int rock = w.add_rock_material(meshed);
    test::add_fixed_base(w, test::rectangle(-1, -1, 3, 1), base);
    w.add_block(test::rectangle(0, 0.001, 1, 0.5), rock);
    return w;
  };
  expect_restart_exact(scene, 12, 12);
}

}  // namespace dda
