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

double WorldState::suggested_time_step() const {
  if (blocks.count() == 0) return 0;
  const BlockPolygons polys = blocks.polygons();
  double h_min = INFINITY, m_min = INFINITY, cp_max = 0, e_max = 0;
  for (std::size_t b = 0; b < blocks.count(); ++b) {
    double longest = 0;
    const auto v = polys.of(static_cast<int>(b));
    for (std::size_t k = 0; k < v.size(); ++k) longest = std::max(longest, (v[(k + 1) % v.size()] - v[k]).norm());
    h_min = std::min(h_min, blocks.area[b] / longest);  // the block's height across its longest edge
    m_min = std::min(m_min, blocks.mass[b]);
    cp_max = std::max(cp_max, p_wave_speed(rocks[blocks.material[b]], controls.plane));
    e_max = std::max(e_max, rocks[blocks.material[b]].youngs);
  }
  const double g0 = controls.g0 > 0 ? controls.g0 : 50 * e_max;
  // Eqs. 1–3 with the paper's a = 0.05 and b = 0.177.
  return std::min(0.05 * h_min / cp_max, 2 * 0.177 * std::sqrt(m_min / g0));
}

}  // namespace dda
