// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "block/blocks.hpp"

#include <limits>

#include "block/displacement.hpp"
#include "core/error.hpp"
#include "core/load_check.hpp"
#include "geometry/polygon.hpp"

namespace dda {

IntegratedTt block_tt(const Blocks& blocks, std::size_t b, MeshMass mesh_mass) {
  if (mesh_mass == MeshMass::Consistent || !blocks.is_element(static_cast<BlockId>(b)))
    return integrated_tt(blocks.area[b], blocks.sxx[b], blocks.syy[b], blocks.sxy[b]);
  // An element is a triangle: its corner-lumped ∫TᵀT has the second moments
  // × 4 (time_scheme.hpp).
  const double f = element_moment_factor(mesh_mass);
  return integrated_tt(blocks.area[b], f * blocks.sxx[b], f * blocks.syy[b], f * blocks.sxy[b]);
}

BlockId append_block(Blocks& bl, std::span<const Vec2> vertices, int material, double density,
                     std::span<const int> edge_joints, std::span<const EdgeTag> edge_tags, bool with_mesh_arrays) {
  const BlockId id = static_cast<BlockId>(bl.count());
  const PolygonMoments m = polygon_moments(vertices);
  bl.vertices.insert(bl.vertices.end(), vertices.begin(), vertices.end());
  bl.initial_vertices.insert(bl.initial_vertices.end(), vertices.begin(), vertices.end());
  bl.edge_joint.insert(bl.edge_joint.end(), edge_joints.begin(), edge_joints.end());
  bl.edge_tag.insert(bl.edge_tag.end(), edge_tags.begin(), edge_tags.end());
  bl.vertex_start.push_back(static_cast<int>(bl.vertices.size()));
  bl.centroid.push_back(m.centroid);
  bl.initial_centroid.push_back(m.centroid);
  bl.area.push_back(m.area);
  bl.sxx.push_back(m.sxx);
  bl.syy.push_back(m.syy);
  bl.sxy.push_back(m.sxy);
  bl.mass.push_back(density * m.area);
  bl.material.push_back(material);
  bl.stress.push_back(Vec3::Zero());
  bl.velocity.push_back(Vec6::Zero());
  bl.last_displacement.push_back(Vec6::Zero());
  bl.acceleration.push_back(Vec6::Constant(std::numeric_limits<double>::quiet_NaN()));
  bl.out_of_balance.push_back(Vec6::Zero());
  // The mesh arrays exist once a block is meshed; first-order blocks then
  // stand on no node and are no mesh's element.
  if (bl.has_meshes() || with_mesh_arrays) {
    bl.node.resize(bl.vertices.size(), -1);
    bl.inner_edge.resize(bl.vertices.size(), 0);
    bl.mesh.resize(bl.count(), -1);
  }
  return id;
}

void check_edges(const Blocks& blocks, const std::vector<EdgeRef>& edges, const std::string& what) {
  if (edges.empty()) throw Error(msg(what, ": no edges given"));
  for (const EdgeRef& e : edges) {
    if (e.block < 0 || static_cast<std::size_t>(e.block) >= blocks.count())
      throw Error(msg(what, ": no block ", e.block));
    const int n = blocks.vertex_count(e.block);
    if (e.edge < 0 || e.edge >= n)
      throw Error(msg(what, ": block ", e.block, " has no edge ", e.edge, " (it has ", n, ")"));
  }
}

void Blocks::check_loaded(const LoadCheck& check, std::size_t rocks, std::size_t joints) const {
  // The outlines first: everything else is sized by them.
  check.require(!vertex_start.empty() && vertex_start[0] == 0, "the blocks' first outline does not start at 0");
  const std::size_t n = count();
  for (std::size_t b = 0; b < n; ++b) {
    const long long start = vertex_start[b], end = vertex_start[b + 1];
    check.require(end - start >= 3 && end <= static_cast<long long>(vertices.size()), "block ", b,
                  "'s outline runs from vertex ", start, " to ", end, " of ", vertices.size());
  }
  check.size(vertices.size(), static_cast<std::size_t>(vertex_start[n]), "vertices", "the blocks' outlines");
  const std::size_t nv = vertices.size();
  auto per_block = [&](std::size_t size, const char* name) { check.size(size, n, "blocks", "the blocks' ", name); };
  per_block(centroid.size(), "centroids");
  per_block(area.size(), "areas");
  per_block(sxx.size(), "moments sxx"), per_block(syy.size(), "moments syy"), per_block(sxy.size(), "moments sxy");
  per_block(mass.size(), "masses");
  per_block(material.size(), "materials");
  per_block(stress.size(), "stresses");
  per_block(velocity.size(), "velocities");
  per_block(last_displacement.size(), "last displacements");
  per_block(acceleration.size(), "accelerations");
  per_block(out_of_balance.size(), "out-of-balance forces");
  per_block(initial_centroid.size(), "initial centroids");
  auto per_vertex = [&](std::size_t size, const char* name) { check.size(size, nv, "vertices", "the blocks' ", name); };
  per_vertex(initial_vertices.size(), "initial vertices");
  per_vertex(edge_joint.size(), "edge joints");
  per_vertex(edge_tag.size(), "edge tags");

  check.all_finite(vertices, "vertex"), check.all_finite(initial_vertices, "initial vertex");
  check.all_finite(centroid, "centroid of block"), check.all_finite(initial_centroid, "initial centroid of block");
  check.all_finite(sxx, "moment sxx of block"), check.all_finite(syy, "moment syy of block");
  check.all_finite(sxy, "moment sxy of block");
  check.all_finite(stress, "stress of block"), check.all_finite(velocity, "velocity of block");
  check.all_finite(last_displacement, "last displacement of block");
  for (std::size_t b = 0; b < n; ++b) {
    check.require(area[b] > 0 && std::isfinite(area[b]) && signed_area(outline(static_cast<BlockId>(b))) > 0, "block ",
                  b, " has no positive area (", area[b], ")");
    check.require(mass[b] > 0 && std::isfinite(mass[b]), "block ", b, "'s mass is not positive (", mass[b], ")");
    check.index(material[b], rocks, "rock materials", "block ", b, "'s material");
  }
  for (std::size_t v = 0; v < nv; ++v) {
    check.index(edge_joint[v], joints, "joint materials", "edge ", v, "'s joint material");
    check.index_or_none(edge_tag[v].joint_material, joints, "joint materials", "edge ", v, "'s tag's joint material");
    check.require(edge_tag[v].hole >= -1, "edge ", v, "'s tag names hole ", edge_tag[v].hole);
  }

  // Meshes (block/mesh.hpp): all three arrays empty, or every element a
  // triangle on mesh nodes, numbered from 0 without gaps beyond the elements'
  // corners, and every vertex of a first-order block on none.
  if (mesh.empty() && node.empty() && inner_edge.empty()) return;
  per_block(mesh.size(), "meshes");
  per_vertex(node.size(), "mesh nodes");
  per_vertex(inner_edge.size(), "inner edges");
  for (std::size_t b = 0; b < n; ++b) {
    check.index_or_none(mesh[b], n, "blocks", "block ", b, "'s mesh");
    const bool element = mesh[b] >= 0;
    check.require(!element || vertex_count(static_cast<BlockId>(b)) == 3, "element ", b, " of mesh ", mesh[b], " has ",
                  vertex_count(static_cast<BlockId>(b)), " corners");
    for (int v = vertex_start[b]; v < vertex_start[b + 1]; ++v) {
      if (element)
        check.index(node[v], 3 * n, "element corners", "vertex ", v, "'s mesh node");
      else
        check.require(node[v] == -1, "vertex ", v, " of first-order block ", b, " stands on mesh node ", node[v]);
    }
  }
}

void check_loaded(const LoadCheck& check, const MaterialPoint& p, const Blocks& blocks, const std::string& what) {
  check.index(p.block, blocks.count(), "blocks", what, "'s block");
  check.finite(p.point, what, "'s point");
  check.finite(p.origin, what, "'s origin");
}

}  // namespace dda
