#pragma once
// Contact mechanics: the linearised penetration and shear of a vertex-edge
// contact (Shi 1988), the springs they carry, and the Mohr-Coulomb open /
// sliding / locked decision of the open-close iteration.
#include <span>

#include "contact/contact.hpp"
#include "core/material.hpp"
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

// Per-contact values that change during the open-close iteration of a step.
struct ContactIterate {
  double s0 = 0;            // shear offset in force (0 once the contact re-locks mid-step)
  double normal_force = 0;  // from the previous iteration: drives sliding friction
};

struct ContactSprings {
  double kn = 0;         // g0
  double ks = 0;         // shear_ratio × g0
  double tolerance = 0;  // open-close hysteresis (m)
};

// Decide the contact's next state from the latest displacements. Returns true
// when the state (or the intact flag, or the sliding direction) changed.
// `dn`, `ds` are the current penetration and shear; `ds_step` the shear
// displacement within this step (sliding direction).
bool update_contact_state(Contact& c, ContactIterate& it, const JointMaterial& joint, double tan_phi,
                          const ContactSprings& k, double dn, double ds, double ds_step);

}  // namespace dda
