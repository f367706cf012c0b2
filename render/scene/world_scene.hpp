// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The adapter from the engine: copies what a frame needs out of a dda::World
// into a Scene. Cheap (a copy of the vertex and per-block arrays), so it can
// run on the simulation thread between steps while drawing happens elsewhere.
#include <filesystem>
#include <string>
#include <vector>

#include "frame/renderer.hpp"
#include "scene/scene.hpp"
#include "world/world.hpp"

namespace dda::render {

// Takes Scenes from a World and remembers where the blocks started, for
// magnified deformation (the World keeps only the current outlines).
class WorldSnapshot {
 public:
  // Records every block's current outline as its start. Call it once the model
  // is built, before the first step; otherwise the first take() does it, and
  // magnified deformation then counts from that frame. Blocks added later are
  // recorded the first time a snapshot sees them.
  void record_initial(const World& world);
  bool has_initial() const { return !initial_offsets_.empty(); }

  // Monitor points drawn on frames: a World tracked point (add_tracked_point)
  // and the name to print beside it.
  void add_monitor(int tracked_point, std::string name);
  void clear_monitors() { monitors_.clear(); }

  // The World's blocks (outlines, stresses, centroid velocities and
  // displacements), contacts (when `with_contacts`), monitors, time and step.
  Scene take(const World& world, bool with_contacts = true);

 private:
  struct Monitor {
    int tracked_point;
    std::string name;
  };
  void extend_initial(const World& world);

  std::vector<std::int32_t> initial_offsets_;  // like Scene::offsets
  std::vector<Vec2> initial_vertices_;
  std::vector<Monitor> monitors_;
};

// A one-off Scene (no remembered start: magnify moves blocks rigidly by their
// centroid displacement only).
Scene snapshot(const World& world, bool with_contacts = true);

// Renders one frame of the World now and writes it, on the calling thread,
// with a Renderer shared by the process (serialised by a mutex). Pass the
// WorldSnapshot used for a run to get magnified deformation right. Throws
// dda::Error (bad option, no OpenGL context, file not writable, naming it).
void write_frame(const World& world, const std::filesystem::path& path, const FrameOptions& options = {},
                 WorldSnapshot* snapshot = nullptr);

}  // namespace dda::render
