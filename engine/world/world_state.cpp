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

double WorldState::contact_spring() const {
  double e_max = 0;
  for (const RockMaterial& r : rocks) e_max = std::max(e_max, r.youngs);
  return controls.g0 > 0 ? controls.g0 : 50 * e_max;
}

}  // namespace dda
