// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Block edges: how cutting, the World and the Lua layer name an edge (its
// block and index: edge k runs from vertex k to k + 1 of the block's
// counter-clockwise outline), and what an edge was made from.
#include <cstdint>

#include "core/types.hpp"

namespace dda {

struct EdgeRef {
  BlockId block = -1;
  int edge = -1;
  friend bool operator==(const EdgeRef&, const EdgeRef&) = default;
  template <class Archive>
  void fields(Archive& ar) {
    ar(block, edge);
  }
};

enum class EdgeKind : std::uint8_t {
  Joint,   // a joint between two cut blocks
  Domain,  // the outer boundary of the cut domain
  Hole,    // the boundary of hole `hole`
  Free,    // an edge of a block added explicitly
};
constexpr EdgeKind enum_last(EdgeKind) { return EdgeKind::Free; }  // (core/archive.hpp)

struct EdgeTag {
  EdgeKind kind = EdgeKind::Free;
  int joint_material = -1;  // for Joint edges from cutting, else -1
  int hole = -1;            // 0-based hole index for Hole edges, else -1
  friend bool operator==(const EdgeTag&, const EdgeTag&) = default;
  template <class Archive>
  void fields(Archive& ar) {
    ar(kind, joint_material, hole);
  }
};

}  // namespace dda
