// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/contact_kinematics.hpp"

#include "block/displacement.hpp"
#include "geometry/polygon.hpp"

namespace dda {

const char* to_string(ContactState s) {
  switch (s) {
    case ContactState::Open:
      return "open";
    case ContactState::Sliding:
      return "sliding";
    case ContactState::Locked:
      return "locked";
  }
  return "?";
}

ContactKinematics contact_kinematics(const BlockPolygons& blocks, std::span<const Vec2> centroids, const Contact& c) {
  ContactKinematics k;
  const Vec2& p1 = blocks.vertex(c.vblock, c.vertex);
  const Vec2& p2 = blocks.vertex(c.eblock, c.edge);
  const Vec2& p3 = blocks.vertex(c.eblock, c.edge + 1);
  const Vec2& cv = centroids[c.vblock];
  const Vec2& ce = centroids[c.eblock];
  const Vec2 edge = p3 - p2;
  const double l = edge.norm();
  const Vec2 t = edge / l;
  k.edge_length = l;

  // Normal: twice the signed area of (p1, p2, p3) over l; it is positive
  // when p1 lies left of the counter-clockwise edge, i.e. inside the block.
  // Its derivative with respect to the three points' displacements gives the
  // coefficients below (Shi 1988, eq. 4.8).
  k.d0 = cross(p2 - p1, p3 - p1) / l;
  const Vec2 g1(p2.y() - p3.y(), p3.x() - p2.x());
  const Vec2 g2(p3.y() - p1.y(), p1.x() - p3.x());
  const Vec2 g3(p1.y() - p2.y(), p2.x() - p1.x());
  k.en_v = displacement_transpose_times(p1, cv, g1) / l;
  k.en_e = (displacement_transpose_times(p2, ce, g2) + displacement_transpose_times(p3, ce, g3)) / l;

  // Shear: displacement of the vertex along the edge relative to the
  // reference point p0 on the edge (where it locked, else its projection).
  k.param = (p1 - p2).dot(t) / l;
  const double ref = c.ref_valid ? c.ref_param : k.param;
  const Vec2 p0 = p2 + ref * edge;
  k.s0 = (p1 - p0).dot(t);
  k.es_v = displacement_transpose_times(p1, cv, t);
  k.es_e = -displacement_transpose_times(p0, ce, t);
  return k;
}

}  // namespace dda
