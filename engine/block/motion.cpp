// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "block/motion.hpp"

#include <algorithm>

#include "block/displacement.hpp"
#include "core/parallel.hpp"
#include "geometry/polygon.hpp"

namespace dda {

MotionCheck check_block_motion(const Blocks& blocks, const VecX& d, std::vector<char>& inverted,
                               std::vector<Vec2>& vertex_motion) {
  const std::size_t n = blocks.count();
  inverted.resize(n);
  vertex_motion.resize(blocks.vertices.size());
  const double largest = parallel_max<double>(n, 0.0, [&](std::size_t b) {
    const BlockMotion motion = blocks.is_element(b) ? BlockMotion::linear(d.segment<6>(6 * b), blocks.centroid[b])
                                                    : BlockMotion(d.segment<6>(6 * b), blocks.centroid[b]);
    const int first = blocks.vertex_start[b], count = blocks.vertex_start[b + 1] - first;
    const auto& v = blocks.vertices;
    const Vec2 moved_first = motion(v[first]), moved_second = motion(v[first + 1]);
    vertex_motion[first] = moved_first;
    vertex_motion[first + 1] = moved_second;
    double worst = std::max(moved_first.norm(), moved_second.norm());
    const Vec2 o = v[first] + moved_first;
    Vec2 p = v[first + 1] + moved_second - o;
    double twice = 0;  // twice the moved outline's area, as a fan from its first vertex
    for (int k = 1; k + 1 < count; ++k) {
      const Vec2 moved = motion(v[first + k + 1]);
      vertex_motion[first + k + 1] = moved;
      worst = std::max(worst, moved.norm());
      const Vec2 q = v[first + k + 1] + moved - o;
      twice += cross(p, q);
      p = q;
    }
    inverted[b] = !(twice > 0);
    return worst;
  });
  const auto it = std::find(inverted.begin(), inverted.end(), 1);
  return {largest, it == inverted.end() ? -1 : static_cast<BlockId>(it - inverted.begin())};
}

void move_block(Blocks& blocks, std::size_t b, const Vec6& d, std::span<const Vec2> vertex_motion, const Mat3& elastic,
                const TimeScheme& scheme, const IntegratedTt& mass) {
  const BlockEndState next = scheme.end_state(d, blocks.scheme_state(static_cast<BlockId>(b)), mass);
  const int first = blocks.vertex_start[b], end = blocks.vertex_start[b + 1];
  for (int v = first; v < end; ++v) blocks.vertices[v] += vertex_motion[v];
  const PolygonMoments pm = polygon_moments(std::span<const Vec2>(blocks.vertices).subspan(first, end - first));
  blocks.centroid[b] = pm.centroid;
  blocks.area[b] = pm.area;
  blocks.sxx[b] = pm.sxx;
  blocks.syy[b] = pm.syy;
  blocks.sxy[b] = pm.sxy;
  blocks.stress[b] += elastic * d.tail<3>();
  blocks.velocity[b] = next.velocity;
  blocks.acceleration[b] = next.acceleration;
  blocks.out_of_balance[b] = next.out_of_balance;
  blocks.last_displacement[b] = d;
}

void move_material_points(std::span<MaterialPoint> points, const Blocks& blocks, const VecX& d) {
  for (MaterialPoint& p : points)
    p.point += point_displacement(p.point, blocks.centroid[p.block], d.segment<6>(6 * p.block));
}

}  // namespace dda
