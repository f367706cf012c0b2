// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "block/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace dda {

namespace {

// Triangles as corner triples, merged into shared nodes: corners closer than
// `tol` are one node (the same point computed along a shared edge from
// either side differs by round-off at most).
class MeshBuilder {
 public:
  explicit MeshBuilder(double tol) : tol_(tol) {}

  void add(const Vec2& a, const Vec2& b, const Vec2& c) {
    if (cross(b - a, c - a) <= 0) return;  // degenerate (never for a convex outline)
    mesh_.triangles.push_back({node(a), node(b), node(c)});
  }
  TriangleMesh take(std::span<const Vec2> outline) {
    label_outline_edges(mesh_, outline, tol_);
    return std::move(mesh_);
  }

 private:
  int node(const Vec2& p) {
    const auto key = std::make_pair(std::llround(p.x() / (4 * tol_)), std::llround(p.y() / (4 * tol_)));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = index_.find({key.first + dx, key.second + dy});
        if (it != index_.end() && (mesh_.nodes[it->second] - p).norm() <= tol_) return it->second;
      }
    const int id = static_cast<int>(mesh_.nodes.size());
    mesh_.nodes.push_back(p);
    index_.emplace(key, id);
    return id;
  }

  double tol_;
  TriangleMesh mesh_;
  std::map<std::pair<long long, long long>, int> index_;
};

// Triangle abc divided into m² similar triangles.
void divide_triangle(MeshBuilder& mesh, const Vec2& a, const Vec2& b, const Vec2& c, int m) {
  auto at = [&](int i, int j) -> Vec2 { return a + (b - a) * (double(i) / m) + (c - a) * (double(j) / m); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i + j < m; ++i) {
      mesh.add(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + j + 1 < m) mesh.add(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
}

int divisions(double length, double size) { return std::max(1, static_cast<int>(std::ceil(length / size - 1e-9))); }

// The first vertex (0-based) at which the counter-clockwise outline turns
// clockwise, beyond round-off; -1 when it is convex.
int first_reflex_vertex(std::span<const Vec2> v) {
  const int n = static_cast<int>(v.size());
  for (int k = 0; k < n; ++k) {
    const Vec2 &p = v[(k + n - 1) % n], &q = v[k], &r = v[(k + 1) % n];
    if (cross(q - p, r - q) < -1e-12 * (q - p).norm() * (r - q).norm()) return k;
  }
  return -1;
}

}  // namespace

void label_outline_edges(TriangleMesh& mesh, std::span<const Vec2> outline, double tol) {
  const int n = static_cast<int>(outline.size());
  auto on_edge = [&](const Vec2& p, int k) {
    const Vec2 a = outline[k], b = outline[(k + 1) % n];
    const Vec2 d = b - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (a + t * d - p).norm() <= tol;
  };
  mesh.outline_edge.resize(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec2 &p = mesh.nodes[mesh.triangles[t][k]], &q = mesh.nodes[mesh.triangles[t][(k + 1) % 3]];
      int edge = -1;
      for (int e = 0; e < n && edge < 0; ++e)
        if (on_edge(p, e) && on_edge(q, e)) edge = e;
      mesh.outline_edge[t][k] = edge;
    }
}

TriangleMesh mesh_polygon(std::span<const Vec2> outline, double size, const std::string& what) {
  if (first_reflex_vertex(outline) < 0) return mesh_convex_polygon(outline, size, what);
  return mesh_concave_polygon(outline, size, what);
}

double estimated_mesh_elements(std::span<const Vec2> v, double size) {
  const int n = static_cast<int>(v.size());
  if (!(size > 0) || n < 3) return 0;
  if (first_reflex_vertex(v) >= 0) return std::abs(polygon_moments(v).area) / (0.2 * size * size);
  double longest = 0;
  for (int k = 0; k < n; ++k) longest = std::max(longest, (v[(k + 1) % n] - v[k]).norm());
  // As mesh_convex_polygon divides (in floating point: the count may not fit an int).
  auto parts = [&](double length) { return std::max(1.0, std::ceil(length / size - 1e-9)); };
  if (n == 3) return parts(longest) * parts(longest);
  if (n == 4)
    return 4 * parts(std::max((v[1] - v[0]).norm(), (v[2] - v[3]).norm())) *
           parts(std::max((v[3] - v[0]).norm(), (v[2] - v[1]).norm()));
  const Vec2 c = polygon_moments(v).centroid;
  double fan_longest = longest;
  for (int k = 0; k < n; ++k) fan_longest = std::max(fan_longest, (v[k] - c).norm());
  return n * parts(fan_longest) * parts(fan_longest);
}

TriangleMesh mesh_convex_polygon(std::span<const Vec2> v, double size, const std::string& what) {
  if (!(size > 0) || !std::isfinite(size)) throw Error(msg(what, ": mesh size ", size, " must be positive"));
  const int n = static_cast<int>(v.size());
  if (const int k = first_reflex_vertex(v); k >= 0)
    throw Error(
        msg(what, " is not convex (at its vertex ", k + 1, "); the structured mesher takes convex blocks only"));
  double longest = 0;
  for (int k = 0; k < n; ++k) longest = std::max(longest, (v[(k + 1) % n] - v[k]).norm());
  const double across = longest / size;
  if (across * across * std::max(4, n) > kMaxMeshElements)
    throw Error(msg(what, ": mesh size ", size, " m would cut this block (edges up to ", longest, " m) into more than ",
                    kMaxMeshElements, " elements; use a larger mesh size"));
  MeshBuilder mesh(1e-9 * longest);
  if (n == 3) {
    divide_triangle(mesh, v[0], v[1], v[2], divisions(longest, size));
  } else if (n == 4) {
    // A bilinear grid: s along edge 0 (v0 → v1), t along edge 3 (v0 → v3).
    const int ms = divisions(std::max((v[1] - v[0]).norm(), (v[2] - v[3]).norm()), size);
    const int mt = divisions(std::max((v[3] - v[0]).norm(), (v[2] - v[1]).norm()), size);
    auto at = [&](int i, int j) -> Vec2 {
      const double s = double(i) / ms, t = double(j) / mt;
      return (1 - s) * (1 - t) * v[0] + s * (1 - t) * v[1] + s * t * v[2] + (1 - s) * t * v[3];
    };
    for (int j = 0; j < mt; ++j)
      for (int i = 0; i < ms; ++i) {
        // Four triangles about the cell's centre (crossed diagonals): the
        // pattern is mirror-symmetric in each cell, so a plane wave along
        // the grid stays plane (one diagonal per cell gives the corners
        // unequal consistent masses: a wave along the bar then shears it,
        // 4.5 % on Model 1's first peak at 0.1 m; docs/meshed_blocks.md).
        const Vec2 p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
        const Vec2 centre = 0.25 * (p00 + p10 + p11 + p01);
        mesh.add(p00, p10, centre);
        mesh.add(p10, p11, centre);
        mesh.add(p11, p01, centre);
        mesh.add(p01, p00, centre);
      }
  } else {
    // A fan from the centroid, every triangle divided alike so that the
    // radial edges they share match node for node.
    const Vec2 c = polygon_moments(v).centroid;
    double fan_longest = longest;
    for (int k = 0; k < n; ++k) fan_longest = std::max(fan_longest, (v[k] - c).norm());
    const int m = divisions(fan_longest, size);
    for (int k = 0; k < n; ++k) divide_triangle(mesh, c, v[k], v[(k + 1) % n], m);
  }
  return mesh.take(v);
}

BlockId element_under(const Blocks& blocks, BlockId b, const Vec2& p) {
  if (!blocks.is_element(b)) return b;
  const int mesh = blocks.mesh[b];
  BlockId nearest = b;
  double best = std::numeric_limits<double>::infinity();
  for (BlockId e = 0; e < static_cast<BlockId>(blocks.count()); ++e) {
    if (blocks.mesh[e] != mesh) continue;
    const auto outline = blocks.outline(e);
    if (point_in_polygon(outline, p)) return e;
    const double d = distance_to_outline(outline, p);
    if (d < best) best = d, nearest = e;
  }
  return nearest;
}

Vec2 mesh_centroid(const Blocks& blocks, int mesh) {
  Vec2 moment = Vec2::Zero();
  double area = 0;
  for (std::size_t e = 0; e < blocks.count(); ++e)
    if (blocks.mesh[e] == mesh) moment += blocks.area[e] * blocks.centroid[e], area += blocks.area[e];
  return moment / area;
}

int mesh_node_count(const Blocks& blocks) {
  int n = 0;
  for (const int id : blocks.node) n = std::max(n, id + 1);
  return n;
}

}  // namespace dda
