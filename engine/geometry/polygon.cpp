// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"

namespace dda {

double signed_area(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  if (n < 3) return 0;
  // Relative to the first vertex, so coordinates far from the origin keep their digits.
  double twice = 0;
  for (std::size_t k = 1; k + 1 < n; ++k) twice += cross(v[k] - v[0], v[k + 1] - v[0]);
  return 0.5 * twice;
}

PolygonMoments polygon_moments(std::span<const Vec2> v) {
  PolygonMoments m;
  const std::size_t n = v.size();
  if (n < 3) return m;
  // Green's theorem edge sums, in coordinates relative to the first vertex.
  // (It runs for every block every step: the next vertex without an integer
  // division.)
  const Vec2 o = v[0];
  double a2 = 0, cx = 0, cy = 0, ixx = 0, iyy = 0, ixy = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 p = v[k] - o;
    const Vec2 q = v[k + 1 < n ? k + 1 : 0] - o;
    const double c = p.x() * q.y() - q.x() * p.y();
    a2 += c;
    cx += (p.x() + q.x()) * c;
    cy += (p.y() + q.y()) * c;
    ixx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * c;
    iyy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * c;
    ixy += (p.x() * q.y() + 2 * p.x() * p.y() + 2 * q.x() * q.y() + q.x() * p.y()) * c;
  }
  const double area = 0.5 * a2;
  m.area = area;
  if (area == 0) return m;
  const double gx = cx / (3 * a2), gy = cy / (3 * a2);
  m.centroid = o + Vec2(gx, gy);
  // About the centroid (parallel-axis theorem). The sign of the sums follows
  // the orientation; report moments of the filled region (positive).
  const double s = area > 0 ? 1.0 : -1.0;
  m.sxx = s * (ixx / 12.0 - area * gx * gx);
  m.syy = s * (iyy / 12.0 - area * gy * gy);
  m.sxy = s * (ixy / 24.0 - area * gx * gy);
  return m;
}

bool segments_cross_properly(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool segments_cross_clearly(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double tol) {
  const double lab = (b - a).norm(), lcd = (d - c).norm();
  if (lab == 0 || lcd == 0) return false;
  // Signed distances of each end point from the other segment's line.
  const double d1 = cross(b - a, c - a) / lab, d2 = cross(b - a, d - a) / lab;
  const double d3 = cross(d - c, a - c) / lcd, d4 = cross(d - c, b - c) / lcd;
  return ((d1 > tol && d2 < -tol) || (d1 < -tol && d2 > tol)) && ((d3 > tol && d4 < -tol) || (d3 < -tol && d4 > tol));
}

namespace {

// Is p on the closed segment [a,b] (within a relative tolerance)?
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p, double tol) {
  const Vec2 ab = b - a;
  const double len = ab.norm();
  if (len == 0) return (p - a).norm() <= tol;
  if (std::abs(cross(ab, p - a)) / len > tol) return false;
  const double t = ab.dot(p - a) / (len * len);
  return t >= -tol / len && t <= 1 + tol / len;
}

// Whether edges i and j (i ≠ j) of the outline cross or touch (within tol);
// the adjacent ones (sharing a vertex) only by a proper crossing.
enum class Meeting { None, Cross, Touch };
Meeting edges_meet(std::span<const Vec2> v, std::size_t i, std::size_t j, double tol) {
  const std::size_t n = v.size();
  const Vec2 &a = v[i], &b = v[(i + 1) % n], &c = v[j], &d = v[(j + 1) % n];
  // A crossing within tol of an end point is caught as a touch below.
  if (segments_cross_clearly(a, b, c, d, tol)) return Meeting::Cross;
  const bool adjacent = (i + 1) % n == j || (j + 1) % n == i;
  if (!adjacent &&
      (on_segment(a, b, c, tol) || on_segment(a, b, d, tol) || on_segment(c, d, a, tol) || on_segment(c, d, b, tol)))
    return Meeting::Touch;
  return Meeting::None;
}

// The first pair of edges (lowest i, then j, i < j) that meet, by a sweep
// along x: only edges whose boxes (grown by tol) overlap are compared, so
// the cost is O(n log n + k), k such pairs: about n for an outline that a
// vertical line crosses a bounded number of times (a round hole of 20 000
// vertices), where comparing every pair took n²/2.
struct EdgeMeeting {
  std::size_t i = 0, j = 0;
  Meeting kind = Meeting::None;
};
EdgeMeeting first_meeting(std::span<const Vec2> v, double tol) {
  const std::size_t n = v.size();
  struct Box {
    double x0, x1, y0, y1;
  };
  std::vector<Box> box(n);
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 &a = v[k], &b = v[(k + 1) % n];
    box[k] = {std::min(a.x(), b.x()) - tol, std::max(a.x(), b.x()) + tol, std::min(a.y(), b.y()) - tol,
              std::max(a.y(), b.y()) + tol};
    order[k] = k;
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t p, std::size_t q) { return box[p].x0 < box[q].x0 || (box[p].x0 == box[q].x0 && p < q); });
  EdgeMeeting first;
  auto found = [&](std::size_t i, std::size_t j, Meeting kind) {
    if (i > j) std::swap(i, j);
    if (first.kind == Meeting::None || i < first.i || (i == first.i && j < first.j)) first = {i, j, kind};
  };
  std::vector<std::size_t> active;  // edges whose x extent reaches the sweep line
  for (const std::size_t e : order) {
    std::erase_if(active, [&](std::size_t a) { return box[a].x1 < box[e].x0; });
    for (const std::size_t a : active)
      if (box[a].y0 <= box[e].y1 && box[e].y0 <= box[a].y1)
        if (const Meeting m = edges_meet(v, std::min(a, e), std::max(a, e), tol); m != Meeting::None) found(a, e, m);
    active.push_back(e);
  }
  return first;
}

}  // namespace

void validate_simple_polygon(std::span<const Vec2> v, const std::string& what) {
  const std::size_t n = v.size();
  if (n < 3) throw Error(msg(what, ": a polygon needs at least 3 vertices, got ", n));
  double extent = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(v[k].x()) || !std::isfinite(v[k].y()))
      throw Error(msg(what, ": vertex ", k + 1, " has a non-finite coordinate"));
    extent = std::max({extent, std::abs(v[k].x() - v[0].x()), std::abs(v[k].y() - v[0].y())});
  }
  const double tol = 1e-12 * std::max(extent, 1e-300);
  for (std::size_t k = 0; k < n; ++k) {
    if ((v[(k + 1) % n] - v[k]).norm() <= tol)
      throw Error(msg(what, ": vertices ", k + 1, " and ", (k + 1) % n + 1, " are repeated (zero-length edge)"));
  }
  const EdgeMeeting meeting = first_meeting(v, tol);
  const double area = signed_area(v);
  // A bow-tie has zero area too: its crossing is the cause to name.
  if (!(std::abs(area) > tol * extent) && meeting.kind != Meeting::Cross)
    throw Error(msg(what, ": polygon has zero area"));
  if (meeting.kind != Meeting::None)
    throw Error(msg(what, ": polygon is self-intersecting (edges ", meeting.i + 1, " and ", meeting.j + 1,
                    meeting.kind == Meeting::Cross ? " cross)" : " touch)"));
}

void make_counter_clockwise(std::vector<Vec2>& v) {
  if (signed_area(v) < 0) std::reverse(v.begin(), v.end());
}

bool point_in_polygon(std::span<const Vec2> v, const Vec2& p) {
  bool inside = false;
  const std::size_t n = v.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    if ((v[i].y() > p.y()) != (v[j].y() > p.y())) {
      const double x = v[j].x() + (p.y() - v[j].y()) * (v[i].x() - v[j].x()) / (v[i].y() - v[j].y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double distance_to_outline(std::span<const Vec2> vertices, const Vec2& p) {
  double d = INFINITY;
  for (std::size_t j = 0; j < vertices.size(); ++j) {
    const Vec2 a = vertices[j], e = vertices[(j + 1) % vertices.size()] - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    d = std::min(d, (p - (a + t * e)).norm());
  }
  return d;
}

std::optional<Vec2> shared_area_point(std::span<const Vec2> p, std::span<const Vec2> q, double inset, double on_tol) {
  std::vector<double> cuts;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 a = p[i], e = p[(i + 1) % p.size()] - a;
    const double len = e.norm();
    if (!(len > 0)) continue;
    cuts.assign({0.0, 1.0});
    for (const Vec2& v : q) {
      const double t = (v - a).dot(e) / (len * len);
      if (t > 0 && t < 1 && std::abs(cross(e, v - a)) / len <= on_tol) cuts.push_back(t);
    }
    std::sort(cuts.begin(), cuts.end());
    const Vec2 inward = Vec2(-e.y(), e.x()) / len;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const Vec2 point = a + 0.5 * (cuts[k] + cuts[k + 1]) * e + inset * inward;
      const bool in_p = point_in_polygon(p, point) && distance_to_outline(p, point) > 0.5 * inset;
      if (in_p && point_in_polygon(q, point) && distance_to_outline(q, point) > 0.5 * inset) return point;
    }
  }
  return std::nullopt;
}

}  // namespace dda
