// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace dda::render {

Vec2 polygon_centroid(std::span<const Vec2> p) {
  const std::size_t n = p.size();
  if (n == 0) return Vec2::Zero();
  double a = 0, cx = 0, cy = 0;
  const Vec2 o = p[0];  // about the first vertex, for accuracy far from the origin
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 u = p[i] - o, v = p[(i + 1) % n] - o;
    const double c = u.x() * v.y() - v.x() * u.y();
    a += c, cx += (u.x() + v.x()) * c, cy += (u.y() + v.y()) * c;
  }
  if (std::abs(a) < 1e-300) {
    Vec2 mean = Vec2::Zero();
    for (const Vec2& q : p) mean += q;
    return mean / static_cast<double>(n);
  }
  return o + Vec2(cx, cy) / (3 * a);
}

BlockId Scene::add_block(std::span<const Vec2> outline, const Vec3& s, const Vec2& v, const Vec2& d,
                         std::span<const Vec2> initial) {
  if (outline.size() < 3)
    throw Error(msg("scene block ", block_count(), ": needs at least 3 vertices, got ", outline.size()));
  if (!initial.empty() && initial.size() != outline.size())
    throw Error(msg("scene block ", block_count(), ": ", initial.size(), " initial vertices for ", outline.size(),
                    " vertices"));
  if (!initial.empty() && initial_vertices.empty() && !vertices.empty())
    initial_vertices = vertices;  // earlier blocks: no motion known, start = now
  vertices.insert(vertices.end(), outline.begin(), outline.end());
  if (!initial.empty())
    initial_vertices.insert(initial_vertices.end(), initial.begin(), initial.end());
  else if (!initial_vertices.empty())
    initial_vertices.insert(initial_vertices.end(), outline.begin(), outline.end());
  offsets.push_back(static_cast<std::int32_t>(vertices.size()));
  centroids.push_back(polygon_centroid(outline));
  stress.push_back(s);
  velocity.push_back(v);
  displacement.push_back(d);
  return static_cast<BlockId>(centroids.size() - 1);
}

void Scene::validate() const {
  const std::size_t n = centroids.size();
  if (offsets.size() != n + 1 || offsets.front() != 0 || static_cast<std::size_t>(offsets.back()) != vertices.size())
    throw Error(msg("scene: offsets (", offsets.size(), " entries, last ", offsets.empty() ? -1 : offsets.back(),
                    ") do not match ", n, " blocks and ", vertices.size(), " vertices"));
  if (stress.size() != n || velocity.size() != n || displacement.size() != n)
    throw Error(msg("scene: per-block arrays differ in size (centroids ", n, ", stress ", stress.size(), ", velocity ",
                    velocity.size(), ", displacement ", displacement.size(), ")"));
  if (!initial_vertices.empty() && initial_vertices.size() != vertices.size())
    throw Error(msg("scene: ", initial_vertices.size(), " initial vertices for ", vertices.size(), " vertices"));
  for (std::size_t b = 0; b < n; ++b)
    if (offsets[b + 1] - offsets[b] < 3) throw Error(msg("scene block ", b, ": fewer than 3 vertices"));
  for (std::size_t k = 0; k < vertices.size(); ++k)
    if (!vertices[k].allFinite() || (!initial_vertices.empty() && !initial_vertices[k].allFinite())) {
      const auto b =
          std::upper_bound(offsets.begin(), offsets.end(), static_cast<std::int32_t>(k)) - offsets.begin() - 1;
      throw Error(msg("scene block ", b, ": vertex ", k - offsets[b], " is not finite"));
    }
  for (const ContactMark& c : contacts)
    if (c.block < 0 || static_cast<std::size_t>(c.block) >= n || c.vertex < 0 ||
        c.vertex >= offsets[c.block + 1] - offsets[c.block])
      throw Error(msg("scene: contact at block ", c.block, " vertex ", c.vertex, " does not exist"));
    else if (c.eblock >= 0 && (static_cast<std::size_t>(c.eblock) >= n || c.edge < 0 ||
                               c.edge >= offsets[c.eblock + 1] - offsets[c.eblock]))
      throw Error(msg("scene: contact on block ", c.eblock, " edge ", c.edge, " does not exist"));
}

Box Scene::bounds(double magnify) const {
  if (vertices.empty()) return {};
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box b{inf, inf, -inf, -inf};
  for (std::size_t blk = 0; blk + 1 < offsets.size(); ++blk)
    for (std::int32_t k = offsets[blk]; k < offsets[blk + 1]; ++k) {
      const Vec2 p = drawn_vertex(blk, k, magnify);
      b.xmin = std::min(b.xmin, p.x()), b.xmax = std::max(b.xmax, p.x());
      b.ymin = std::min(b.ymin, p.y()), b.ymax = std::max(b.ymax, p.y());
    }
  return b;
}

}  // namespace dda::render
