#pragma once
// Contact mechanics: the linearised penetration and shear of a vertex-edge
// contact (Shi 1988), the springs they carry, and the Mohr-Coulomb open /
// sliding / locked decision of the open-close iteration.
#include <cmath>
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

// The contact law (the control contact_law; docs/contacts.md):
//   * Holding: a contact's shear force is continuous through its changes of
//     state (shear memory), a sliding contact locks again by a return mapping,
//     friction agrees with the normal force of the accepted solve, friction
//     decisions have a band in the contact's own units, and joints without
//     cohesion or tension are unbonded from the start: friction holds a block
//     that must hold, at every step size;
//   * Shi: Shi's (1988) law, as the engine had it before: a contact that
//     closes or locks again does so unloaded, friction uses the normal force
//     of the solve before, every decision has the model-wide band. A block
//     that must stay on a slope creeps down it. Bit for bit the engine's
//     earlier results (the paper's figures, docs/validation.md).
enum class ContactLaw { Holding, Shi };

// Per-contact values that change during the open-close iteration of a step.
struct ContactIterate {
  // Shear offset of the spring at the step start: the shear force the
  // contact carried into the step over ks (keep_shear_references puts the
  // reference point there), 0 for a contact open at the step start. Kept
  // through the step, so that the shear force is continuous through every
  // change of state (under Shi's law: 0 once it closes or locks again).
  double s0 = 0;
  double normal_force = 0;  // from the previous iteration: drives sliding friction
  double shear = 0;         // shear ds at the last check (m)
  // Closed at the start of the step. A contact that was open approaches in
  // the step: under the holding law it decides friction with the gap band,
  // not the friction band of a share of the step's translations, which for a
  // block landing fast is many times the force that stops it (open_close.cpp).
  bool closed_at_start = false;
  // Friction that lags the normal force (control friction_lag): the lagged
  // normal force at the step start, N_f0, and the step's weight of the new
  // N (lag_weight below); w = 1 (no lag) without friction_lag and for a
  // contact with no lagged force yet (friction_normal below).
  double lag_start = 0;
  double lag_weight = 1;
  // The normal force the last solve's friction used (the landing law,
  // contact/landing.hpp, takes that solve's forces out of the step).
  double solved_normal = 0;
};

// The weight of a step's N in the lagged friction normal force N_f of a
// contact whose memory is `age` old (s: how long it has been closed) at the
// step's start, over a step dt, lag t_r: N_f is the mean of the N the
// interface has carried, each instant weighted by exp(−(its age)/t_r), and
// the weights normalised over the interface's life only, since a landing is a
// new interface with no normal-force history before it closed:
//   w = (1 − exp(−dt/t_r)) / (1 − exp(−(age + dt)/t_r)),
// the exact step of that mean with N held over the step. A new contact
// (age 0) takes its first N (w = 1); while age ≪ t_r, N_f is the running
// mean of N since it closed (w ≈ dt/(age + dt)); once age ≫ t_r, the
// simplified Prakash–Clifton law dN_f/dt = (N − N_f)/t_r stepped exactly
// (w = 1 − exp(−dt/t_r); age infinite: an interface that closed again after a
// brief opening, keep_lagged_friction). At dt ≫ t_r, w = 1 to the last bit:
// no lag.
inline double lag_weight(double dt, double age, double t_r) {
  return std::expm1(-dt / t_r) / std::expm1(-(age + dt) / t_r);
}

// The normal force a contact's friction strength acts with when its normal
// force at the step's end is n (compression positive): max(0, n), or with
// friction_lag the lagged N_f = N_f0 + w·(max(0, n) − N_f0), w from
// lag_weight above (the simplified Prakash–Clifton law, Ranjith and Rice
// 2001, over the interface's own life): stable for every Δt/t_r, today's
// max(0, n) once Δt ≫ t_r (w = 1), and N itself in steady sliding. Every
// friction decision and force takes its N from here.
inline double friction_normal(const ContactIterate& it, double n) {
  const double now = n > 0 ? n : 0.0;
  return it.lag_weight == 1 ? now : it.lag_start + it.lag_weight * (now - it.lag_start);
}

// A contact's springs: normal on a closed contact, shear on a locked one.
struct ContactSprings {
  double kn = 0;  // g0
  double ks = 0;  // shear_ratio × g0
};

// A contact under a displacement d of the blocks (a solve's, or a warm
// start's): its gap and shear, and the hysteresis of the decision.
struct ContactMotion {
  double dn = 0;           // penetration after the step (positive: the vertex is inside)
  double ds = 0;           // shear from the reference point after the step
  double ds_step = 0;      // shear motion in the step (the sliding direction)
  double gap_slack = 0;    // the hysteresis of gap decisions and intact joints (m): contact_slack under
                           // the holding law, the model-wide band under Shi's
  double shear_slack = 0;  // the hysteresis of friction decisions (m): contact_slack under the holding
                           // law, the model-wide band under Shi's
};

// The bands of the holding law (friction; with a smaller share, gaps and
// intact joints), in the step's own units: a
// displacement, the tolerance's share of the spread of the step's block
// translations (a translation all blocks share drops out: a shaken base), and
// at least round-off of the contact's edge's length. The decision values come
// from a solve whose error is relative to the step's displacements, so the
// band follows the step: it is neither a length of the model (a contact in a
// model 100× larger decides the same) nor a force through g0, and it vanishes
// for blocks at rest, where friction must hold to its last newton. (The
// model's spread, not the contact's own relative motion: a settling wall's
// vertical joints, which carry next to nothing, slid and opened on the loose
// solves' error with that: docs/contacts.md.)
double contact_slack(double tolerance, double motion, double edge_length);

// Decide the contact's next state from its motion under the latest
// displacements (Mohr-Coulomb on the springs' forces). Returns true when the
// state (or the intact flag, or the sliding direction) changed. Under the
// holding law the shear force is continuous through every change of state
// (ContactIterate::s0); under Shi's, a contact that closes or locks again
// does so unloaded at its position at the step start.
bool update_contact_state(Contact& c, ContactIterate& it, const JointMaterial& joint, double tan_phi,
                          const ContactSprings& k, const ContactMotion& m, ContactLaw law);

}  // namespace dda
