// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "block/remeshing.hpp"

#include <algorithm>

#include "block/displacement.hpp"
#include "core/error.hpp"

namespace dda {

namespace {

// Appends block b of `from` to `to` as it is.
void copy_block(const Blocks& from, BlockId b, Blocks& to, double density, bool mesh_arrays) {
  const int start = from.vertex_start[b], n = from.vertex_count(b);
  const auto slots = [&](const auto& v) { return std::span(v).subspan(start, n); };
  const BlockId id = append_block(to, from.outline(b), from.material[b], density, slots(from.edge_joint),
                                  slots(from.edge_tag), mesh_arrays);
  const int to_start = to.vertex_start[id];
  std::copy_n(from.initial_vertices.begin() + start, n, to.initial_vertices.begin() + to_start);
  to.initial_centroid[id] = from.initial_centroid[b];
  to.mass[id] = from.mass[b];
  to.stress[id] = from.stress[b];
  to.velocity[id] = from.velocity[b];
  to.last_displacement[id] = from.last_displacement[b];
  to.acceleration[id] = from.acceleration[b];
  to.out_of_balance[id] = from.out_of_balance[b];
  if (from.has_meshes()) {
    std::copy_n(from.node.begin() + start, n, to.node.begin() + to_start);
    std::copy_n(from.inner_edge.begin() + start, n, to.inner_edge.begin() + to_start);
    to.mesh[id] = from.mesh[b];
  }
}

struct PendingMesh {
  BlockId block;  // in the blocks before (and its id after: its first element)
  TriangleMesh mesh;
  int first_node, id;
  std::vector<BlockId> elements;  // per triangle, its id after
};

}  // namespace

// The joint of an element edge along a first-order edge of length l: the
// edge's own, or, for a joint without a stiffness of its own, a copy with
// the stiffness the first-order edge had (two contacts of g0 over l).
class KeptJoints {
 public:
  KeptJoints(std::vector<JointMaterial>& joints, double g0) : joints_(joints), g0_(g0) {}
  int operator()(int joint, double l) {
    if (joints_[joint].normal_stiffness > 0) return joint;
    for (const Copy& c : copies_)
      if (c.joint == joint && c.length == l) return c.id;
    JointMaterial copy = joints_[joint];
    copy.normal_stiffness = 2 * g0_ / l;
    copy.shear_stiffness = 0;  // shear_ratio·k_n, as g0 and shear_ratio·g0 were
    joints_.push_back(copy);
    copies_.push_back({joint, l, static_cast<int>(joints_.size()) - 1});
    return copies_.back().id;
  }

 private:
  struct Copy {
    int joint;
    double length;
    int id;
  };
  std::vector<JointMaterial>& joints_;
  double g0_;
  std::vector<Copy> copies_;
};

Remeshing mesh_in_place(Blocks& blocks, std::span<const double> size, std::span<const RockMaterial> rocks,
                        std::vector<JointMaterial>& joints, double g0) {
  const std::size_t count = blocks.count();
  // Every mesh first (a mesher error leaves the blocks untouched).
  std::vector<PendingMesh> meshes;
  int next_node = mesh_node_count(blocks), next_mesh = 0;
  for (const int m : blocks.mesh) next_mesh = std::max(next_mesh, m + 1);
  for (std::size_t b = 0; b < count; ++b) {
    if (!(size[b] > 0)) continue;
    const BlockId id = static_cast<BlockId>(b);
    const auto outline = blocks.outline(id);
    PendingMesh p{id, mesh_polygon(outline, size[b], msg("block ", b)), next_node, next_mesh++, {}};
    next_node += static_cast<int>(p.mesh.nodes.size());
    meshes.push_back(std::move(p));
  }
  Blocks old = std::move(blocks);
  blocks = Blocks{};
  Remeshing r;
  r.blocks = &blocks;
  r.old_vertex_start = old.vertex_start;
  r.pieces.resize(old.vertices.size());
  KeptJoints kept(joints, g0);
  // The elements of a pending mesh: triangle t as a block of its own.
  auto add_element = [&](PendingMesh& p, std::size_t t) {
    const BlockId b = p.block;
    const int old_start = old.vertex_start[b];
    const auto outline = old.outline(b);
    std::vector<Vec2> corners(3);
    std::vector<int> edge_joints(3, 0);
    std::vector<EdgeTag> tags(3);
    for (int k = 0; k < 3; ++k) {
      corners[k] = p.mesh.nodes[p.mesh.triangles[t][k]];
      const int edge = p.mesh.outline_edge[t][k];
      if (edge < 0) continue;
      const double l = (outline[(edge + 1) % outline.size()] - outline[edge]).norm();
      edge_joints[k] = kept(old.edge_joint[old_start + edge], l);
      tags[k] = old.edge_tag[old_start + edge];
    }
    const BlockId e =
        append_block(blocks, corners, old.material[b], rocks[old.material[b]].density, edge_joints, tags, true);
    const int start = blocks.vertex_start[e];
    blocks.mesh[e] = p.id;
    for (int k = 0; k < 3; ++k) {
      blocks.node[start + k] = p.first_node + p.mesh.triangles[t][k];
      blocks.inner_edge[start + k] = p.mesh.outline_edge[t][k] < 0;
    }
    // The block's stress and motion (its rates about its own centroid).
    blocks.stress[e] = old.stress[b];
    blocks.velocity[e] = old.velocity[b];
    blocks.velocity[e].head<2>() = displacement_matrix(blocks.centroid[e], old.centroid[b]) * old.velocity[b];
    p.elements[t] = e;
  };
  std::size_t next = 0;
  for (std::size_t b = 0; b < count; ++b) {
    const BlockId id = static_cast<BlockId>(b);
    if (next < meshes.size() && meshes[next].block == id) {
      meshes[next].elements.resize(meshes[next].mesh.triangles.size());
      add_element(meshes[next++], 0);
    } else {
      copy_block(old, id, blocks, rocks[old.material[b]].density, !meshes.empty());
      for (int k = 0; k < old.vertex_count(id); ++k) r.pieces[old.vertex_start[b] + k] = {{id, k}};
    }
  }
  for (PendingMesh& p : meshes)
    for (std::size_t t = 1; t < p.mesh.triangles.size(); ++t) add_element(p, t);
  // The element edges along each old edge, in order from its first vertex.
  for (const PendingMesh& p : meshes) {
    const int old_start = old.vertex_start[p.block];
    const auto outline = old.outline(p.block);
    for (std::size_t t = 0; t < p.mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        if (const int edge = p.mesh.outline_edge[t][k]; edge >= 0)
          r.pieces[old_start + edge].push_back({p.elements[t], k});
    for (int edge = 0; edge < static_cast<int>(outline.size()); ++edge) {
      const Vec2 a = outline[edge];
      auto& pieces = r.pieces[old_start + edge];
      std::sort(pieces.begin(), pieces.end(), [&](const EdgeRef& x, const EdgeRef& y) {
        return (blocks.outline(x.block)[x.edge] - a).squaredNorm() <
               (blocks.outline(y.block)[y.edge] - a).squaredNorm();
      });
    }
  }
  return r;
}

}  // namespace dda
