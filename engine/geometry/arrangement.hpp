// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Planar arrangement of line segments with a snapping tolerance.
//
// Input: segments, each with a rank (how firmly its geometry must be kept).
// Output: vertices and non-overlapping edges such that no two edges cross,
// no vertex lies within `tol` of an edge it is not an end of, and no two
// vertices are within `tol` of each other. Every edge remembers the input
// segment it came from (`source`); where segments overlap, the edge goes to
// the highest rank, then the lowest segment index, and keeps that segment's
// direction.
//
// Method (a tolerance-based snap rounding):
//  1. broad phase on a uniform grid (cell ≈ sqrt(area / segments)), so the
//     cost is about O(S + K) for S segments and K intersections;
//  2. narrow phase per candidate pair: an end point within tol of the other
//     segment splits it there (T-junctions, joints through vertices, collinear
//     overlaps); otherwise a proper crossing splits both;
//  3. points within tol are snapped to one vertex, the highest-ranked point
//     first, so domain corners and points on the boundary never move; an end
//     point moved onto a segment (a T-junction) follows its foot;
//  4. segments are split at their vertices, and coincident pieces merged.
// Snapping can move a vertex by up to tol, which may bring it within tol of
// another edge, so the whole pass is repeated on the resulting edges until
// nothing changes (usually one extra round; nearly coincident joints take a
// few), or until it returns to an earlier state (an edge swapping between two
// vertices a few tolerances apart). Throws dda::Error if it does not settle
// within 24 rounds, or if the joints are far too many to cut.
#include <span>
#include <vector>

#include "core/types.hpp"

namespace dda::geometry {

struct ArrangementSegment {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  int rank = 0;      // rank of the points created on this segment
  int end_rank = 0;  // rank of its two end points (≥ rank for polygon corners)
};

struct Arrangement {
  struct Edge {
    int from = -1, to = -1;  // vertex indices, in the direction of the source segment
    int source = -1;         // index of the input segment
  };
  std::vector<Vec2> vertices;
  std::vector<Edge> edges;
  int rounds = 0;
};

Arrangement build_arrangement(std::span<const ArrangementSegment> segments, double tol);

}  // namespace dda::geometry
