// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The blocks under a step's solution D (6 unknowns per block): the checks the
// step control needs before accepting it, and the move once it is accepted.
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "block/time_scheme.hpp"
#include "core/parallel.hpp"

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

// The accepted step, block by block: vertices by the motion
// check_block_motion computed, then the block's moments, stress
// (elastic[material] times the strains), the time scheme's state (velocity,
// acceleration, unbalanced force) and last displacement. Before a block
// changes, before_move(b, mass) is called with its mass ρ∫TᵀT as the step's
// system had it, for what the caller books of the step from the block as it
// was (the energy budget): one pass over the blocks, each mass made once.
void move_block(Blocks& blocks, std::size_t b, const Vec6& d, std::span<const Vec2> vertex_motion, const Mat3& elastic,
                const TimeScheme& scheme, const IntegratedTt& mass);
template <class BeforeMove>
void move_blocks(Blocks& blocks, const VecX& d, std::span<const Vec2> vertex_motion, std::span<const Mat3> elastic,
                 const TimeScheme& scheme, BeforeMove&& before_move) {
  parallel_for_each(
      blocks.count(),
      [&](std::size_t b) {
        const IntegratedTt mass = block_tt(blocks, b, scheme.mesh_mass).scaled(blocks.mass[b] / blocks.area[b]);
        before_move(b, mass);
        move_block(blocks, b, d.segment<6>(6 * b), vertex_motion, elastic[blocks.material[b]], scheme, mass);
      },
      32);
}

// Material points move with their blocks under d; call before move_blocks
// (the points move about their block's centroid at the start of the step).
void move_material_points(std::span<MaterialPoint> points, const Blocks& blocks, const VecX& d);

}  // namespace dda
