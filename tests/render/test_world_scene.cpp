// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The adapter from dda::World: snapshots carry the World's state, remember
// the start for magnified deformation, and drive a FrameSequence.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

#include "output/frame_sequence.hpp"
#include "scene/world_scene.hpp"
#include "world/world.hpp"

namespace fs = std::filesystem;
using dda::Vec2;
using namespace dda::render;

namespace {

// Two 1 m blocks falling freely under gravity (no contacts between them).
dda::World falling_world() {
  dda::Controls c;
  c.gravity = Vec2(0, -9.81);
  c.g1 = 1e-3;
  dda::World w(c);
  const int rock = w.add_rock_material({});
  w.add_block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, rock);
  w.add_block({{3, 0}, {4, 0}, {4, 1}, {3, 1}}, rock);
  return w;
}

}  // namespace

TEST(WorldScene, SnapshotTakenLateStillKnowsTheStart) {
  // Magnified deformation needs the starting outline, even when the first
  // snapshot is taken after the run has begun.
  dda::World w = falling_world();
  for (int i = 0; i < 5; ++i) w.step();
  WorldSnapshot snap;
  const Scene s = snap.take(w);
  EXPECT_LT(s.vertices[0].y(), 0.0);
  EXPECT_EQ(s.initial_vertices[0], Vec2(0, 0));
  EXPECT_EQ(s.initial_vertices[s.offsets[1]], Vec2(3, 0));
}

TEST(WorldScene, SnapshotCopiesTheWorld) {
  dda::World w = falling_world();
  const int tp = w.add_tracked_point(0, {0.5, 0.5});
  WorldSnapshot snap;
  snap.record_initial(w);
  snap.add_monitor(tp, "P");
  for (int i = 0; i < 5; ++i) w.step();
  const Scene s = snap.take(w);
  ASSERT_EQ(s.block_count(), w.block_count());
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.step, w.step_count());
  EXPECT_DOUBLE_EQ(s.time, w.time());
  for (std::size_t b = 0; b < s.block_count(); ++b) {
    const auto v = w.block_vertices(static_cast<dda::BlockId>(b));
    const auto sv = s.block_vertices(b);
    ASSERT_EQ(sv.size(), v.size());
    for (std::size_t k = 0; k < v.size(); ++k) EXPECT_EQ(sv[k], v[k]);
    EXPECT_EQ(s.stress[b], w.block_stress(static_cast<dda::BlockId>(b)));
    EXPECT_EQ(s.velocity[b], w.block_velocity(static_cast<dda::BlockId>(b)).head<2>());
    EXPECT_EQ(s.displacement[b], w.block_displacement(static_cast<dda::BlockId>(b)));
  }
  // The blocks fell; the snapshot remembers where they started.
  EXPECT_LT(s.vertices[0].y(), 0.0);
  EXPECT_EQ(s.initial_vertices[0], Vec2(0, 0));
  ASSERT_EQ(s.monitors.size(), 1u);
  EXPECT_EQ(s.monitors[0].name, "P");
  EXPECT_EQ(s.monitors[0].position, w.tracked_position(tp));
}

TEST(WorldScene, FrameSequenceFromAWorldRun) {
  const fs::path dir = fs::temp_directory_path() / ("dda_render_world_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  dda::World w = falling_world();
  SequenceOptions so;
  so.folder = dir;
  so.every_steps = 2;
  so.frame.width = 320, so.frame.height = 200;
  so.frame.field = Field::Velocity;
  so.frame.magnify = 100;
  FrameSequence seq(so);
  seq.maybe_capture(w);  // step 0: also records the start
  for (int i = 0; i < 6; ++i) {
    w.step();
    seq.maybe_capture(w);
  }
  seq.flush();
  EXPECT_EQ(seq.frame_count(), 4);  // steps 0, 2, 4, 6
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(fs::exists(dir / ("velocity_0000" + std::to_string(i) + ".png"))) << i;
  // One frame now, on the caller's thread.
  write_frame(w, dir / "now.png", so.frame, &seq.snapshot());
  EXPECT_TRUE(fs::exists(dir / "now.png"));
  fs::remove_all(dir);
}
