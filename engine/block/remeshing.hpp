// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What meshing first-order blocks in place changed (world/wave_model.hpp:
// the wave model meshes a model's blocks before its first step, after its
// loads and boundaries were given on the blocks as they were). Every block
// keeps its id, as the first element of its mesh; the other elements come
// after the last block. Loads, boundaries and followed points given on the
// old blocks ask this for where they now are.
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "block/mesh.hpp"
#include "core/material.hpp"

namespace dda {

struct Remeshing {
  const Blocks* blocks = nullptr;     // the blocks after meshing
  std::vector<int> old_vertex_start;  // the blocks' vertex_start before
  // Per edge of the blocks before (its vertex slot there): the element edges
  // that lie along it now, in order from its first vertex; the edge itself
  // where its block was not meshed.
  std::vector<std::vector<EdgeRef>> pieces;

  // The element of block b's mesh under the material point p.
  BlockId element_at(BlockId b, const Vec2& p) const { return element_under(*blocks, b, p); }
  // The edges that stand where `old` stood.
  std::vector<EdgeRef> edges(const std::vector<EdgeRef>& old) const {
    std::vector<EdgeRef> now;
    for (const EdgeRef& e : old) {
      const auto& p = pieces[old_vertex_start[e.block] + e.edge];
      now.insert(now.end(), p.begin(), p.end());
    }
    return now;
  }
  template <class Archive>
  void fields(Archive& ar) {
    ar(old_vertex_start, pieces);
  }
};

// Meshes in place every block b with size[b] > 0 (first-order blocks at
// the model's start, at rest or moving as a whole, with their stresses):
// block b becomes the first element of its mesh and keeps its id, the
// others follow the last block; the elements take the block's stress, its
// motion (the rates about its centroid, as World::set_block_velocity) and
// each outline edge's tag and joint. A joint keeps its physical stiffness:
// one without a stiffness of its own had, on a first-order edge of length l,
// two contacts of g0 (the paper's Eq. 4, k_n = 2·g0/l), which the mesh's
// many contacts along the edge would multiply; its element edges get a copy
// of it (appended to `joints`) with k_n = 2·g0/l given, shared by the edges
// of one length. Blocks with size 0 stay as they are. Throws dda::Error
// (from the mesher) naming a block that cannot be meshed; the blocks and
// joints are then left as they were.
Remeshing mesh_in_place(Blocks& blocks, std::span<const double> size, std::span<const RockMaterial> rocks,
                        std::vector<JointMaterial>& joints, double g0);

}  // namespace dda
