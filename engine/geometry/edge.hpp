#pragma once
// A block edge, named by its block and its index: edge k runs from vertex k
// to k + 1 of the block's counter-clockwise outline. Cutting, the World and
// the Lua layer all name edges this way.
#include "core/types.hpp"

namespace dda {

struct EdgeRef {
  BlockId block = -1;
  int edge = -1;
  friend bool operator==(const EdgeRef&, const EdgeRef&) = default;
};

}  // namespace dda
