// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
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
// phase, which knows blocks and not nodes, judges it with each element's
// wedge, narrower than the outline's: a facing-edge contact from each element
// whose outline edge faces the other block (each standing for its own share
// of the joint: all kept), and corner contacts (no joint length) that a
// first-order block's corner would not make (the corner where four blocks
// meet: a first-order block's vertex there faces two joints and touches the
// diagonal block only at a point). A corner contact from an element is kept
// only where its node is in no facing-edge contact (as the vertex or an end
// of the edge), and then once per edge.
void drop_contacts_inside_meshes(const Blocks& blocks, std::vector<Contact>& contacts) {
  if (!blocks.has_meshes()) return;
  auto node_at = [&](BlockId b, int k) {
    const int n = blocks.vertex_count(b);
    return blocks.node[blocks.vertex_start[b] + (k % n)];
  };
  std::erase_if(contacts, [&](const Contact& c) {
    if (blocks.inner_edge[blocks.vertex_start[c.eblock] + c.edge]) return true;
    if (!blocks.is_element(c.vblock)) return false;
    const int start = blocks.vertex_start[c.vblock], n = blocks.vertex_count(c.vblock);
    const int before = start + (c.vertex + n - 1) % n, after = start + c.vertex;  // the edges into and out of it
    return blocks.inner_edge[before] && blocks.inner_edge[after];
  });
  std::vector<int> facing;  // the nodes in a facing-edge contact
  for (const Contact& c : contacts) {
    if (c.length <= 0) continue;
    for (const int node : {node_at(c.vblock, c.vertex), node_at(c.eblock, c.edge), node_at(c.eblock, c.edge + 1)})
      if (node >= 0) facing.push_back(node);
  }
  std::sort(facing.begin(), facing.end());
  std::vector<std::tuple<int, int, int>> corners;  // (node, edge block, edge) of the corner contacts kept
  std::erase_if(contacts, [&](const Contact& c) {
    if (!blocks.is_element(c.vblock) || c.length > 0) return false;
    const int node = node_at(c.vblock, c.vertex);
    if (std::binary_search(facing.begin(), facing.end(), node)) return true;
    const auto key = std::make_tuple(node, c.eblock, c.edge);
    if (std::find(corners.begin(), corners.end(), key) != corners.end()) return true;
    corners.push_back(key);
    return false;
  });
}

}  // namespace dda
