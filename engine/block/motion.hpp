// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The blocks under a step's solution D (6 unknowns per block): the checks the
// step control needs before accepting it, and the move once it is accepted.
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "block/time_scheme.hpp"

namespace dda {

struct MotionCheck {
  double largest_displacement = 0;  // of any vertex
  BlockId inverted_block = -1;      // the first block whose moved outline has zero or negative area (-1: none)
};

// Moves every vertex with its block's displacement in one pass (the motion
// kept in `vertex_motion`, per vertex, for move_blocks; `inverted` per block
// is scratch). A step whose largest vertex motion exceeds the g2 bound must
// be cut, and so must one in which a block's moved outline has zero or
// negative area (a sliver crushed by stiff springs, say).
MotionCheck check_block_motion(const Blocks& blocks, const VecX& d, std::vector<char>& inverted,
                               std::vector<Vec2>& vertex_motion);

// The accepted step: vertices by the motion check_block_motion computed,
// then the blocks' moments, stresses (elastic[material] times the strains),
// the time scheme's state (velocity, acceleration, unbalanced force) and
// last displacements.
void move_blocks(Blocks& blocks, const VecX& d, std::span<const Vec2> vertex_motion, std::span<const Mat3> elastic,
                 const TimeScheme& scheme);

// Material points move with their blocks under d; call before move_blocks
// (the points move about their block's centroid at the start of the step).
void move_material_points(std::span<MaterialPoint> points, const Blocks& blocks, const VecX& d);

}  // namespace dda
