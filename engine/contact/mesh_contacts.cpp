#include "contact/mesh_contacts.hpp"

#include <algorithm>
#include <tuple>

namespace dda {

void drop_pairs_inside_meshes(const Blocks& blocks, std::vector<std::pair<int, int>>& pairs) {
  if (!blocks.has_meshes()) return;
  std::erase_if(pairs, [&](const std::pair<int, int>& p) {
    return blocks.mesh[p.first] >= 0 && blocks.mesh[p.first] == blocks.mesh[p.second];
  });
}

// A node of a mesh's outline is a corner of several elements, and the narrow
// phase, which knows blocks and not nodes, may find it once per element: a
// facing-edge contact from each element whose outline edge faces the other
// block (each standing for its own share of the joint: both kept), and a
// corner contact (no joint length) from an element that meets that block
// only at the node. A corner contact is kept only where the node has no
// facing-edge contact on the same block, and then once per edge.
void drop_contacts_inside_meshes(const Blocks& blocks, std::vector<Contact>& contacts) {
  if (!blocks.has_meshes()) return;
  auto node_of = [&](const Contact& c) { return blocks.node[blocks.vertex_start[c.vblock] + c.vertex]; };
  std::erase_if(contacts, [&](const Contact& c) {
    if (blocks.inner_edge[blocks.vertex_start[c.eblock] + c.edge]) return true;
    if (!blocks.is_element(c.vblock)) return false;
    const int start = blocks.vertex_start[c.vblock], n = blocks.vertex_count(c.vblock);
    const int before = start + (c.vertex + n - 1) % n, after = start + c.vertex;  // the edges into and out of it
    return blocks.inner_edge[before] && blocks.inner_edge[after];
  });
  std::vector<std::pair<int, int>> facing;  // (node, edge block) of the facing-edge contacts
  for (const Contact& c : contacts)
    if (blocks.is_element(c.vblock) && c.length > 0) facing.emplace_back(node_of(c), c.eblock);
  std::sort(facing.begin(), facing.end());
  std::vector<std::tuple<int, int, int>> corners;  // (node, edge block, edge) of the corner contacts kept
  std::erase_if(contacts, [&](const Contact& c) {
    if (!blocks.is_element(c.vblock) || c.length > 0) return false;
    const int node = node_of(c);
    if (std::binary_search(facing.begin(), facing.end(), std::make_pair(node, c.eblock))) return true;
    const auto key = std::make_tuple(node, c.eblock, c.edge);
    if (std::find(corners.begin(), corners.end(), key) != corners.end()) return true;
    corners.push_back(key);
    return false;
  });
}

}  // namespace dda
