#pragma once
// Small scenes shared by the engine tests.
#include <cmath>
#include <vector>

#include "world/world.hpp"

namespace dda::test {

inline std::vector<Vec2> rectangle(double x0, double y0, double w, double h) {
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}

// Rectangle with lower-left corner at `origin` (before rotation), rotated by
// `angle` radians about the global origin.
inline std::vector<Vec2> rotated(const std::vector<Vec2>& pts, double angle) {
  std::vector<Vec2> out;
  const double c = std::cos(angle), s = std::sin(angle);
  for (const Vec2& p : pts) out.emplace_back(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  return out;
}

inline RockMaterial granite() { return RockMaterial{2600, 5e9, 0.25}; }

// A base block held by three fixed points along its length.
inline BlockId add_fixed_base(World& w, const std::vector<Vec2>& outline, int rock) {
  const BlockId b = w.add_block(outline, rock);
  const auto v = w.block_vertices(b);
  w.add_fixed_point(b, v[0] * 0.75 + v[1] * 0.25);
  w.add_fixed_point(b, v[0] * 0.5 + v[1] * 0.5);
  w.add_fixed_point(b, v[0] * 0.25 + v[1] * 0.75);
  return b;
}

}  // namespace dda::test
