#include "contact/contact_law.hpp"

#include <cmath>

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

double contact_slack(double tolerance, double motion, double edge_length) {
  constexpr double kRoundOff = 1e-12;  // of the edge's length: positions carry ~1e-16 of the coordinates
  return tolerance * motion + kRoundOff * edge_length;
}

bool update_contact_state(Contact& c, ContactIterate& it, const JointMaterial& joint, double tan_phi,
                          const ContactSprings& k, const ContactMotion& m, ContactLaw law) {
  const bool holding = law == ContactLaw::Holding;
  const ContactState old_state = c.state;
  const bool old_intact = c.intact;
  const std::int8_t old_sign = c.slide_sign;
  const double dn = m.dn, ds = m.ds;
  const double normal = k.kn * dn;  // compression positive
  const double shear = k.ks * ds;
  auto slide_towards = [&](double direction) {
    c.state = ContactState::Sliding;
    c.slide_sign = direction >= 0 ? 1 : -1;
  };

  // A joint without cohesion or tensile strength holds nothing an unbonded
  // contact does not: the holding law decides it as one (its friction in the
  // contact's own units, not the intact joints' model-wide band).
  if (holding && c.intact && joint.cohesion == 0 && joint.tensile_strength == 0) c.intact = false;
  if (c.intact) {
    // An intact joint holds tension up to σt·L and shear up to c·L + N·tanφ,
    // with the same hysteresis margin as the open-close decision below (at
    // σt = 0, round-off tension must not break a joint that carries nothing).
    if (normal < -(joint.tensile_strength * c.length + k.kn * m.gap_slack)) {
      c.intact = false;
      c.state = ContactState::Open;
    } else if (std::abs(shear) > joint.cohesion * c.length + normal * tan_phi + k.ks * m.gap_slack) {
      c.intact = false;
      if (dn < 0)
        c.state = ContactState::Open;
      else
        slide_towards(ds);
    } else {
      c.state = ContactState::Locked;
    }
  } else if (old_state == ContactState::Open ? dn <= m.gap_slack : dn < -m.gap_slack) {
    c.state = ContactState::Open;
  } else {
    switch (old_state) {
      case ContactState::Open:
        // Just closed: lock first; the next iteration checks friction.
        c.state = ContactState::Locked;
        if (!holding) it.s0 = 0;
        break;
      case ContactState::Locked:
        if (std::abs(shear) > friction_normal(it, normal) * tan_phi + k.ks * m.shear_slack) slide_towards(ds);
        break;
      case ContactState::Sliding:
        // Lock again once the shear spring, put back, would carry less than
        // the friction: the same test as the one above from the other side
        // (a return mapping), so a contact at its friction limit does not
        // alternate between a locked solve whose spring exceeds N·tanφ and a
        // sliding one whose motion, measured from the step start, reverses
        // while its spring unloads. Shi's law (or no shear spring): once the
        // motion reverses, re-locked unloaded.
        if (holding && k.ks > 0
                ? k.ks * ds * c.slide_sign < friction_normal(it, normal) * tan_phi - k.ks * m.shear_slack
                : m.ds_step * c.slide_sign < -m.shear_slack) {
          c.state = ContactState::Locked;
          if (!holding) it.s0 = 0;
        }
        break;
    }
  }
  it.normal_force = c.state == ContactState::Open ? 0.0 : normal;
  it.shear = ds;
  return c.state != old_state || c.intact != old_intact ||
         (c.state == ContactState::Sliding && c.slide_sign != old_sign);
}

}  // namespace dda
