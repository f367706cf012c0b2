#include "block/blocks.hpp"

#include <limits>

#include "block/displacement.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace dda {

Mat6 block_tt(const Blocks& blocks, std::size_t b, MeshMass mesh_mass) {
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

}  // namespace dda
