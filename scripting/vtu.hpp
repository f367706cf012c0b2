// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// ParaView output: the model's state as VTK XML unstructured grids (.vtu),
// one file of blocks and one of contacts per frame, and a ParaView data
// collection (.pvd) per kind listing every frame with its time, rewritten
// after each frame so it is valid at any moment of a run.
//
//   blocks:   one VTK_POLYGON per block (its current outline); cell data
//             block_id, material, area (m²), sigma_xx, sigma_yy, tau_xy (Pa,
//             tension +), velocity (m/s, centroid, 3 components), angular_velocity
//             (rad/s), displacement (m, centroid since the start, 3 components)
//   contacts: one VTK_LINE per vertex-edge contact, from the centroid of the
//             vertex's block to the centroid of the edge's block (a force
//             chain); cell data normal_force and shear_force (N per unit
//             thickness, compression +), state (0 open, 1 sliding, 2 locked),
//             intact (1 while the joint keeps its cohesion and tensile
//             strength, 0 once failed), penetration (m), vblock, eblock, joint
//             (joint material), contact_point (the vertex, 3 components)
//
// Arrays are base64 binary (Float64, Int32), read by VTK and ParaView as they
// are. Each file is written whole or not at all (output_file.hpp): a failure
// is a dda::Error naming the file.
#include <filesystem>
#include <string>
#include <vector>

#include "world/world.hpp"

namespace dda::script {

std::string blocks_vtu(const World& world);
std::string contacts_vtu(const World& world);

struct VtuOptions {
  std::filesystem::path folder = "vtu";
  std::string prefix;     // file names: <prefix>_blocks_00012.vtu (no prefix: blocks_00012.vtu)
  long every_steps = 0;   // a frame when step % every_steps == 0
  double every_time = 0;  // or each time simulated time passes a multiple of this (s)
  bool contacts = true;   // also the contacts files
};

// A numbered series written during a run (or on demand with write()).
class VtuSeries {
 public:
  explicit VtuSeries(VtuOptions options);  // creates the folder; dda::Error if it cannot
  bool due(long step, double time) const;
  void maybe_write(const World& world);
  // Writes frame count() now; returns the blocks file.
  std::filesystem::path write(const World& world);
  // dda run --restart: the series goes on from the world's (restored) step:
  // the frames the folder's .pvd lists up to its time are kept, numbering
  // continues after them, and the .pvd files list them again.
  void continue_from(const World& world);
  int count() const { return static_cast<int>(times_.size()); }
  std::filesystem::path pvd(const std::string& kind = "blocks") const;
  const VtuOptions& options() const { return options_; }

 private:
  std::string name(const std::string& kind) const;
  void write_pvd(const std::string& kind) const;
  VtuOptions options_;
  std::vector<double> times_;
  long last_step_ = -1;
  double next_time_ = 0;
};

}  // namespace dda::script
