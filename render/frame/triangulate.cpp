// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "frame/triangulate.hpp"

#include <cmath>

namespace dda::render {
namespace {

double cross3(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Is p inside or on triangle abc (counter-clockwise)?
bool in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross3(a, b, p) >= 0 && cross3(b, c, p) >= 0 && cross3(c, a, p) >= 0;
}

}  // namespace

void triangulate(std::span<const Vec2> poly, std::vector<std::array<int, 3>>& out) {
  const int n = static_cast<int>(poly.size());
  if (n < 3) return;
  double area2 = 0;
  for (int i = 0; i < n; ++i) area2 += poly[i].x() * poly[(i + 1) % n].y() - poly[(i + 1) % n].x() * poly[i].y();
  const double sign = area2 < 0 ? -1 : 1;

  bool convex = true;
  for (int i = 0; i < n && convex; ++i)
    if (sign * cross3(poly[i], poly[(i + 1) % n], poly[(i + 2) % n]) < 0) convex = false;
  if (convex) {
    for (int i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
    return;
  }

  // Ear clipping on a counter-clockwise index list.
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = sign > 0 ? i : n - 1 - i;
  int guard = 0;
  while (idx.size() > 3 && guard < 2 * n * n) {
    const int m = static_cast<int>(idx.size());
    bool clipped = false;
    for (int i = 0; i < m; ++i, ++guard) {
      const int ia = idx[(i + m - 1) % m], ib = idx[i], ic = idx[(i + 1) % m];
      const Vec2 &a = poly[ia], &b = poly[ib], &c = poly[ic];
      if (cross3(a, b, c) <= 0) continue;  // reflex or flat corner: not an ear
      bool empty = true;
      for (int j = 0; j < m && empty; ++j) {
        const int k = idx[j];
        if (k == ia || k == ib || k == ic) continue;
        if (poly[k] == a || poly[k] == b || poly[k] == c) continue;
        if (in_triangle(poly[k], a, b, c)) empty = false;
      }
      if (!empty) continue;
      out.push_back({ia, ib, ic});
      idx.erase(idx.begin() + i);
      clipped = true;
      break;
    }
    if (!clipped) break;  // not simple: fan what is left
  }
  for (std::size_t i = 1; i + 1 < idx.size(); ++i) out.push_back({idx[0], idx[i], idx[i + 1]});
}

}  // namespace dda::render
