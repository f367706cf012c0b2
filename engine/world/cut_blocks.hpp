// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A World from cut blocks: every block of a BlockSet (geometry/cutting.hpp)
// added to the World with its edges' joint materials and tags.
#include <vector>

#include "geometry/cutting.hpp"
#include "world/world.hpp"

namespace dda {

// The joint materials of the cut domain's boundary edges: what a block added
// later (not cut) slides on where it touches them.
struct BoundaryJoints {
  int domain = 0;
  std::vector<int> holes;  // per hole (0 where not given)
};

// Adds the blocks in the set's order; returns their ids. A joint edge takes
// its joint set's material (0 when the set named none).
std::vector<BlockId> add_cut_blocks(World& world, const geometry::BlockSet& set, const BoundaryJoints& joints);

}  // namespace dda
