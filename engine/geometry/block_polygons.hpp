// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A read-only view of every block outline: block b owns
// vertices[start[b] .. start[b+1]), counter-clockwise; inner_edge (indexed
// like vertices, empty when no block is meshed) marks an element's edges
// inside its mesh, which are no part of the block's outline.
#include <span>

#include "core/types.hpp"

namespace dda {

struct BlockPolygons {
  std::span<const int> start;
  std::span<const Vec2> vertices;
  std::span<const char> inner_edge = {};

  int count() const { return start.empty() ? 0 : static_cast<int>(start.size()) - 1; }
  int size(int b) const { return start[b + 1] - start[b]; }
  bool is_inner_edge(int b, int k) const {
    return !inner_edge.empty() && inner_edge[start[b] + ((k % size(b)) + size(b)) % size(b)];
  }
  std::span<const Vec2> of(int b) const { return vertices.subspan(start[b], size(b)); }
  // Vertex k of block b, with k taken modulo the block's vertex count.
  const Vec2& vertex(int b, int k) const {
    const int n = size(b);
    // Callers mostly pass k in [0, n] (an edge's second vertex is k + 1):
    // spare them the integer divisions, which cost more than the lookup.
    if (k >= 0 && k < n) return vertices[start[b] + k];
    if (k == n) return vertices[start[b]];
    return vertices[start[b] + ((k % n) + n) % n];
  }
};

}  // namespace dda
