#include "block/blocks.hpp"

#include "block/displacement.hpp"
#include "core/error.hpp"

namespace dda {

IntegratedTt block_tt(const Blocks& blocks, std::size_t b, MeshMass mesh_mass) {
  if (mesh_mass == MeshMass::Consistent || !blocks.is_element(static_cast<BlockId>(b)))
    return integrated_tt(blocks.area[b], blocks.sxx[b], blocks.syy[b], blocks.sxy[b]);
  // An element is a triangle: its corner-lumped ∫TᵀT has the second moments
  // × 4 (time_scheme.hpp).
  const double f = element_moment_factor(mesh_mass);
  return integrated_tt(blocks.area[b], f * blocks.sxx[b], f * blocks.syy[b], f * blocks.sxy[b]);
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
