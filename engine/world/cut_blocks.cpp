// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/cut_blocks.hpp"

#include <algorithm>

namespace dda {

std::vector<BlockId> add_cut_blocks(World& world, const geometry::BlockSet& set, const BoundaryJoints& boundary) {
  std::vector<BlockId> ids;
  ids.reserve(set.blocks.size());
  for (const geometry::CutBlock& cb : set.blocks) {
    std::vector<int> joints(cb.edges.size());
    for (std::size_t k = 0; k < cb.edges.size(); ++k) {
      const EdgeTag& t = cb.edges[k];
      switch (t.kind) {
        case EdgeKind::Joint:
          joints[k] = std::max(0, t.joint_material);
          break;
        case EdgeKind::Domain:
          joints[k] = boundary.domain;
          break;
        case EdgeKind::Hole:
          joints[k] = t.hole >= 0 && t.hole < static_cast<int>(boundary.holes.size()) ? boundary.holes[t.hole] : 0;
          break;
        case EdgeKind::Free:
          break;
      }
    }
    // A meshed block adds its elements (block/mesh.hpp): every one is in the set.
    const BlockId first = world.add_block(cb.vertices, cb.rock_material, std::move(joints), cb.edges);
    for (auto b = static_cast<std::size_t>(first); b < world.block_count(); ++b) ids.push_back(static_cast<BlockId>(b));
  }
  return ids;
}

}  // namespace dda
