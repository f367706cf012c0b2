#include "world/world_state.hpp"

#include <algorithm>
#include <cmath>

namespace dda {

double WorldState::measured_half_height() const {
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec2& v : blocks.vertices) {
    lo = std::min(lo, v.y());
    hi = std::max(hi, v.y());
  }
  return blocks.vertices.empty() ? 0 : 0.5 * (hi - lo);
}

}  // namespace dda
