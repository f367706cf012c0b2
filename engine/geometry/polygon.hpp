// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Simple polygons: area, centroid and the second moments the DDA sub-matrices
// need, plus validation of user-supplied outlines.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dda {

// Integrals over a polygon. Second moments are about the centroid:
//   sxx = ∫(x-x0)² dA, syy = ∫(y-y0)² dA, sxy = ∫(x-x0)(y-y0) dA.
struct PolygonMoments {
  double area = 0;  // signed: positive for counter-clockwise vertices
  Vec2 centroid = Vec2::Zero();
  double sxx = 0, syy = 0, sxy = 0;
};

double signed_area(std::span<const Vec2> vertices);
PolygonMoments polygon_moments(std::span<const Vec2> vertices);

// Throws dda::Error naming `what` (e.g. "block 12") when the outline is not a
// usable simple polygon: fewer than 3 vertices, a non-finite coordinate,
// repeated consecutive vertices, zero area, or self-intersection.
// Vertex order may be either; callers orient with `make_counter_clockwise`.
void validate_simple_polygon(std::span<const Vec2> vertices, const std::string& what);

void make_counter_clockwise(std::vector<Vec2>& vertices);

// Signed cross product (a × b).
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Point in polygon (even-odd rule); points on the boundary may go either way.
bool point_in_polygon(std::span<const Vec2> vertices, const Vec2& p);

// Do the closed segments [a,b] and [c,d] cross at a point interior to both?
// Touching at end points or collinear overlap is not a proper crossing.
bool segments_cross_properly(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

// Like segments_cross_properly, but each end point must lie more than `tol`
// off the other segment's line. For nearly collinear segments the signs of
// the orientation tests are rounding noise, and two collinear edges of one
// outline (a block's side interrupted by a notch) would otherwise "cross" at
// random; whether such segments touch is a distance question (see
// validate_simple_polygon).
bool segments_cross_clearly(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double tol);

// Distance from p to the nearest point of the closed outline.
double distance_to_outline(std::span<const Vec2> vertices, const Vec2& p);

// A point of shared area that neither an edge crossing nor a vertex inside
// shows: coinciding outlines, or outlines overlapping along collinear edges.
// Each edge of `p` (counter-clockwise) is split where vertices of `q` lie on
// it (within `on_tol`); the midpoint of each piece, moved `inset` into p, is
// returned when it lies inside both more than inset / 2 from their outlines.
// Neighbours that only touch along edges have no such point.
std::optional<Vec2> shared_area_point(std::span<const Vec2> p, std::span<const Vec2> q, double inset, double on_tol);

}  // namespace dda
