// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Everything in the renderer that reads a dda::World lives in this file, so
// the rest of the library (and its tests) builds without the engine's World.
#include "scene/world_scene.hpp"

#include <mutex>

#include "core/error.hpp"
#include "output/frame_sequence.hpp"

namespace dda::render {

void WorldSnapshot::record_initial(const World& world) {
  initial_offsets_.assign(1, 0);
  initial_vertices_.clear();
  extend_initial(world);
}

void WorldSnapshot::extend_initial(const World& world) {
  if (initial_offsets_.empty()) initial_offsets_.push_back(0);
  const std::size_t n = world.block_count();
  for (std::size_t b = initial_offsets_.size() - 1; b < n; ++b) {
    // Where the block started, whenever the snapshot is first taken.
    const auto v = world.block_initial_vertices(static_cast<BlockId>(b));
    initial_vertices_.insert(initial_vertices_.end(), v.begin(), v.end());
    initial_offsets_.push_back(static_cast<std::int32_t>(initial_vertices_.size()));
  }
}

void WorldSnapshot::add_monitor(int tracked_point, std::string name) {
  monitors_.push_back({tracked_point, std::move(name)});
}

Scene WorldSnapshot::take(const World& world, bool with_contacts) {
  extend_initial(world);
  Scene s = snapshot(world, with_contacts);
  // Start outlines, block by block; a block whose vertex count changed since
  // (not expected in DDA) counts as not moved.
  s.initial_vertices.resize(s.vertices.size());
  for (std::size_t b = 0; b < s.block_count(); ++b) {
    const std::int32_t n = s.offsets[b + 1] - s.offsets[b];
    const bool same = b + 1 < initial_offsets_.size() && initial_offsets_[b + 1] - initial_offsets_[b] == n;
    for (std::int32_t i = 0; i < n; ++i)
      s.initial_vertices[s.offsets[b] + i] =
          same ? initial_vertices_[initial_offsets_[b] + i] : s.vertices[s.offsets[b] + i];
  }
  for (const Monitor& m : monitors_)
    s.monitors.push_back(
        {m.name, world.tracked_position(m.tracked_point), world.tracked_displacement(m.tracked_point)});
  return s;
}

Scene snapshot(const World& world, bool with_contacts) {
  Scene s;
  const std::size_t n = world.block_count();
  s.offsets.reserve(n + 1);
  s.centroids.reserve(n), s.stress.reserve(n), s.velocity.reserve(n), s.displacement.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto b = static_cast<BlockId>(i);
    const auto v = world.block_vertices(b);
    s.vertices.insert(s.vertices.end(), v.begin(), v.end());
    s.offsets.push_back(static_cast<std::int32_t>(s.vertices.size()));
    s.centroids.push_back(world.block_centroid(b));
    s.stress.push_back(world.block_stress(b));
    const Vec6 vel = world.block_velocity(b);
    s.velocity.emplace_back(vel[0], vel[1]);
    s.displacement.push_back(world.block_displacement(b));
  }
  if (with_contacts) {
    s.contacts.reserve(world.contacts().size());
    for (const Contact& c : world.contacts()) {
      const JointMaterial& joint = world.joint_material(c.joint);
      const bool had_strength = joint.cohesion > 0 || joint.tensile_strength > 0;
      s.contacts.push_back({c.vblock, c.vertex, c.state, c.eblock, c.edge, c.bonded && !c.intact && had_strength});
    }
  }
  s.time = world.time();
  s.step = world.step_count();
  return s;
}

void write_frame(const World& world, const std::filesystem::path& path, const FrameOptions& options,
                 WorldSnapshot* snap) {
  static std::mutex mutex;
  // Never destroyed: tearing an OpenGL context down during static
  // destruction, after Mesa's own exit handlers, is asking for a crash.
  static Renderer* renderer = new Renderer;
  const Scene scene = snap ? snap->take(world) : snapshot(world);
  std::lock_guard lock(mutex);
  renderer->render_to_png(scene, options, path);
}

// FrameSequence's World entry points (here so frame_sequence.cpp needs no World).
bool FrameSequence::maybe_capture(const World& world) {
  if (!due(world.step_count(), world.time())) return false;
  capture(world);
  return active_;
}

void FrameSequence::capture(const World& world) {
  if (!active_) return;
  if (!snapshot_.has_initial()) snapshot_.record_initial(world);
  capture(snapshot_.take(world, options_.with_contacts));
}

}  // namespace dda::render
