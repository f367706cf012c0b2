// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Helpers shared by the block-cutting tests: input builders and a check that a
// BlockSet really tiles the domain minus its holes, computed independently of
// the cutting code (only polygon.hpp's area and point-in-polygon are reused).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../scenes.hpp"
#include "geometry/cutting.hpp"
#include "geometry/polygon.hpp"

namespace dda::geometry::test {

using dda::test::rectangle;  // (x0, y0, width, height)

inline JointSet persistent_set(double dip, double spacing, Vec2 origin = Vec2::Zero(), int material = 0) {
  JointSet s;
  s.dip_deg = dip;
  s.spacing = spacing;
  s.origin = origin;
  s.joint_material = material;
  return s;
}

inline double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

inline double distance_to_outline(const std::vector<Vec2>& poly, const Vec2& p) {
  double best = 1e300;
  for (std::size_t k = 0; k < poly.size(); ++k)
    best = std::min(best, point_segment_distance(p, poly[k], poly[(k + 1) % poly.size()]));
  return best;
}

// Every block is a simple counter-clockwise polygon with only true corners,
// its area field matches its outline, the areas sum to the domain minus the
// holes (relative `area_tolerance`), and sample points on a jittered grid lie
// in exactly one block when in rock and in none when in a hole or outside.
inline void expect_valid_partition(const BlockSet& set, const CutInput& in, double area_tolerance = 1e-12,
                                   int samples_per_side = 40) {
  ASSERT_FALSE(set.blocks.empty());
  double expected = std::abs(signed_area(in.domain));
  for (const auto& h : in.holes) expected -= std::abs(signed_area(h));
  double sum = 0;
  for (std::size_t b = 0; b < set.blocks.size(); ++b) {
    const CutBlock& block = set.blocks[b];
    const std::string what = "block " + std::to_string(b);
    ASSERT_GE(block.vertices.size(), 3u) << what;
    ASSERT_EQ(block.vertices.size(), block.edges.size()) << what;
    EXPECT_NO_THROW(validate_simple_polygon(block.vertices, what)) << what;
    const double a = signed_area(block.vertices);
    EXPECT_GT(a, 0) << what << " is not counter-clockwise";
    EXPECT_NEAR(block.area, a, 1e-12 * std::max(1.0, a)) << what;
    sum += block.area;
    // No vertex where the outline goes straight on with the same edge tag.
    const std::size_t n = block.vertices.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& u = block.vertices[(k + n - 1) % n];
      const Vec2& v = block.vertices[k];
      const Vec2& w = block.vertices[(k + 1) % n];
      const double off_line = std::abs(cross(w - u, v - u)) / (w - u).norm();
      const bool straight = off_line <= 1e-9 * (w - u).norm() && (v - u).dot(w - v) > 0;
      EXPECT_FALSE(straight && block.edges[(k + n - 1) % n] == block.edges[k])
          << what << " has a straight-on vertex " << k << " at (" << v.x() << ", " << v.y() << ")";
    }
  }
  EXPECT_NEAR(sum, expected, area_tolerance * expected);

  // Coverage: each sample point in exactly one block (or none in a void).
  Vec2 lo = in.domain[0], hi = in.domain[0];
  for (const Vec2& p : in.domain) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  std::vector<Vec2> box_lo, box_hi;
  for (const CutBlock& b : set.blocks) {
    Vec2 l = b.vertices[0], h = b.vertices[0];
    for (const Vec2& p : b.vertices) {
      l = l.cwiseMin(p);
      h = h.cwiseMax(p);
    }
    box_lo.push_back(l);
    box_hi.push_back(h);
  }
  const double margin = 1e-7 * (hi - lo).norm();
  int checked = 0;
  for (int i = 0; i < samples_per_side; ++i)
    for (int j = 0; j < samples_per_side; ++j) {
      // Irrational offsets keep the samples off lattice joints.
      const Vec2 p(lo.x() + (hi.x() - lo.x()) * (i + 0.5 + 0.3 * std::sin(1.7 * i + 2.3 * j)) / samples_per_side,
                   lo.y() + (hi.y() - lo.y()) * (j + 0.5 + 0.3 * std::cos(2.9 * i + 1.1 * j)) / samples_per_side);
      bool in_rock = point_in_polygon(in.domain, p);
      bool near_boundary = distance_to_outline(in.domain, p) < margin;
      for (const auto& h : in.holes) {
        if (point_in_polygon(h, p)) in_rock = false;
        near_boundary = near_boundary || distance_to_outline(h, p) < margin;
      }
      int inside = 0;
      bool near_edge = false;
      for (std::size_t b = 0; b < set.blocks.size(); ++b) {
        if (p.x() < box_lo[b].x() - margin || p.x() > box_hi[b].x() + margin || p.y() < box_lo[b].y() - margin ||
            p.y() > box_hi[b].y() + margin)
          continue;
        if (distance_to_outline(set.blocks[b].vertices, p) < margin) near_edge = true;
        if (point_in_polygon(set.blocks[b].vertices, p)) ++inside;
      }
      if (near_edge || near_boundary) continue;
      ++checked;
      EXPECT_EQ(inside, in_rock ? 1 : 0) << "sample point (" << p.x() << ", " << p.y() << ")";
    }
  EXPECT_GT(checked, samples_per_side * samples_per_side / 2);
}

// The blocks as exact numbers, for comparing two cuts.
inline std::vector<double> fingerprint(const BlockSet& set) {
  std::vector<double> f;
  for (const CutBlock& b : set.blocks) {
    f.push_back(static_cast<double>(b.vertices.size()));
    for (const Vec2& v : b.vertices) {
      f.push_back(v.x());
      f.push_back(v.y());
    }
  }
  return f;
}

}  // namespace dda::geometry::test
