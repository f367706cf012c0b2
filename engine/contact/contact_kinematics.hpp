// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The linearised penetration and shear of a vertex-edge contact (Shi 1988),
// at the start of a step: what every contact law decides on and what its
// springs act through.
#include <span>

#include "contact/contact.hpp"
#include "geometry/block_polygons.hpp"

namespace dda {

// Penetration dn and shear ds of a contact as linear functions of the two
// blocks' step displacements Dv (vertex block) and De (edge block):
//   dn = d0 + en_v·Dv + en_e·De   (positive: the vertex is inside)
//   ds = s0 + es_v·Dv + es_e·De   (along the edge direction, from the locked
//                                  reference point; s0 = 0 without one)
// Kept in two arrays per contact list: the gradients are what the product
// A·x reads, again and again in every CG iteration of a wave problem
// (192 bytes, three cache lines; with the offsets beside them the product
// would read 224).
struct ContactGradients {
  Vec6 en_v, en_e, es_v, es_e;
};
struct ContactOffsets {
  double d0 = 0;
  double s0 = 0;
  double param = 0;  // projection of the vertex on the edge (0..1) at the step start
  double edge_length = 0;
};
struct ContactKinematics : ContactGradients, ContactOffsets {};

ContactKinematics contact_kinematics(const BlockPolygons& blocks, std::span<const Vec2> centroids, const Contact& c);

}  // namespace dda
