// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The blocks' state in flat arrays indexed by block id (Box2D's b2BodyState
// against b2Body): what every step reads and writes first, then what only
// model building and output read. Block b owns
// vertices[vertex_start[b] .. vertex_start[b + 1]), counter-clockwise; edge k
// of a block runs from its vertex k to k + 1.
#include <span>
#include <string>
#include <vector>

#include "block/displacement.hpp"
#include "block/time_scheme.hpp"
#include "core/types.hpp"
#include "geometry/block_polygons.hpp"
#include "geometry/edge.hpp"

namespace dda {

class LoadCheck;

struct Blocks {
  // Hot: the step's arrays.
  std::vector<int> vertex_start{0};
  std::vector<Vec2> vertices;
  std::vector<Vec2> centroid;
  std::vector<double> area, sxx, syy, sxy;  // area and second moments about the centroid
  std::vector<double> mass;
  std::vector<int> material;            // rock material
  std::vector<Vec3> stress;             // (σxx, σyy, τxy), tension positive
  std::vector<Vec6> velocity;           // rates of (u0, v0, r0, εx, εy, γxy)
  std::vector<Vec6> last_displacement;  // the previous step's solution (the warm start)
  // The time integrator's state besides the velocity (block/time_scheme.hpp),
  // at the end of the last step, written in Update only (a checkpoint saves
  // these with the velocity): the acceleration and the generalised force
  // not balanced by springs and stresses. NaN until the first step derives
  // them from the block's loads (start_time_scheme_state, block_terms.hpp).
  std::vector<Vec6> acceleration;
  std::vector<Vec6> out_of_balance;
  // Cold: parallel to vertices, and per block.
  std::vector<Vec2> initial_vertices;  // where each vertex started
  std::vector<int> edge_joint;         // joint material of edge k → k + 1
  std::vector<EdgeTag> edge_tag;       // what edge k → k + 1 was made from
  std::vector<Vec2> initial_centroid;
  // Meshed blocks (block/mesh.hpp), all three empty while no block is
  // meshed: per vertex the mesh node it stands on (-1 on a first-order
  // block), per edge whether it lies inside its mesh (no contact acts on it),
  // per block the meshed block it is an element of (-1: first-order).
  std::vector<int> node;
  std::vector<char> inner_edge;
  std::vector<int> mesh;

  // What a checkpoint holds (core/archive.hpp): every array.
  template <class Archive>
  void fields(Archive& ar) {
    ar(vertex_start, vertices, centroid, area, sxx, syy, sxy, mass, material, stress, velocity, acceleration,
       out_of_balance, last_displacement, initial_vertices, edge_joint, edge_tag, initial_centroid, node, inner_edge,
       mesh);
  }

  // Read from a checkpoint (core/load_check.hpp): the outlines, every array
  // sized for the blocks or their vertices, every material, joint, node and
  // mesh in range, the geometry finite. Throws dda::Error naming the damage.
  void check_loaded(const LoadCheck& check, std::size_t rocks, std::size_t joints) const;

  std::size_t count() const { return vertex_start.empty() ? 0 : vertex_start.size() - 1; }
  int vertex_count(BlockId b) const { return vertex_start[b + 1] - vertex_start[b]; }
  std::span<const Vec2> outline(BlockId b) const {
    return std::span<const Vec2>(vertices).subspan(vertex_start[b], vertex_count(b));
  }
  BlockPolygons polygons() const { return {vertex_start, vertices, inner_edge}; }
  bool has_meshes() const { return !mesh.empty(); }
  bool is_element(BlockId b) const { return !mesh.empty() && mesh[b] >= 0; }
  // Block b's time-scheme state at the start of a step.
  BlockState scheme_state(BlockId b) const { return {velocity[b], acceleration[b], out_of_balance[b]}; }
};

// A material point of a block (a load, a fixed point, a monitor): where it is
// now, moving with its block, and where it started.
struct MaterialPoint {
  BlockId block;
  Vec2 point;
  Vec2 origin;
  template <class Archive>
  void fields(Archive& ar) {
    ar(block, point, origin);
  }
};

// ∫TᵀT dA of block b (its mass over the density, the time scheme's M/ρ):
// exact for a first-order block, for an element of a meshed block as
// `mesh_mass` says (MeshMass, block/time_scheme.hpp).
IntegratedTt block_tt(const Blocks& blocks, std::size_t b, MeshMass mesh_mass);

// Appends a counter-clockwise polygon as a first-order block at rest (its
// mass from `density`); the mesh arrays grow with it when they exist or
// `with_mesh_arrays`. Returns its id. (No checks: World's.)
BlockId append_block(Blocks& blocks, std::span<const Vec2> vertices, int material, double density,
                     std::span<const int> edge_joints, std::span<const EdgeTag> edge_tags, bool with_mesh_arrays);

// Throws dda::Error, naming `what`, unless every edge exists (and there is one).
void check_edges(const Blocks& blocks, const std::vector<EdgeRef>& edges, const std::string& what);

// Read from a checkpoint: the block exists and the points are finite.
void check_loaded(const LoadCheck& check, const MaterialPoint& p, const Blocks& blocks, const std::string& what);

}  // namespace dda
