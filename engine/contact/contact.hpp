// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A vertex-edge contact between two blocks, with the state every contact law
// keeps and reports from step to step (open / sliding / locked, intact joint
// or failed, the shear reference point, the forces). What a law keeps of its
// own for a contact lives in the law's model (contact_model.hpp).
#include <cstdint>

#include "core/types.hpp"

namespace dda {

enum class ContactState : std::uint8_t { Open, Sliding, Locked };
constexpr ContactState enum_last(ContactState) { return ContactState::Locked; }  // (core/archive.hpp)

// The contact law (the control contact_law; each law one file behind the
// interface of contact_model.hpp): Holding (holding_law.hpp), the default,
// in which friction holds a block that must hold at every step size; Shi
// (shi_law.hpp), Shi's (1988) law as the paper has it, bit for bit the
// engine's earlier results (the paper's figures, docs/validation.md).
enum class ContactLaw { Holding, Shi };

const char* to_string(ContactState s);

struct Contact {
  // Identity: vertex `vertex` of block `vblock` against edge `edge` (from
  // vertex `edge` to `edge+1`) of block `eblock`. Stable while both exist.
  BlockId vblock = -1;
  BlockId eblock = -1;
  std::int32_t vertex = -1;
  std::int32_t edge = -1;
  std::int32_t joint = 0;  // joint material (of the edge)

  ContactState state = ContactState::Open;
  // Intact: cohesion and tensile strength still act. Lost for good on failure.
  bool intact = false;
  // Bonded: intact when first found (a joint touching before the first
  // step). Never changes: a bonded contact that is no longer intact is a
  // joint that broke (if its material had strength to lose); one made later
  // never was a joint.
  bool bonded = false;
  // Share of joint length this contact stands for (cohesion and tension act
  // over it): half the overlap of two facing edges; 0 at a corner contact.
  double length = 0;
  // Spring scale in (0, 1]: 1 except for facing edges that overlap by less
  // than 5 % of the shorter edge, whose springs ramp in with the overlap (see
  // narrow_phase.hpp).
  double scale = 1;
  // Shear reference: the point on the edge's line (parameter along it) at
  // which the shear spring carries the contact's shear force (where a locked
  // contact locked; behind a sliding vertex by its friction / ks); valid
  // while closed.
  double ref_param = 0;
  bool ref_valid = false;
  // Sign of the last sliding direction along the edge (for friction).
  std::int8_t slide_sign = 0;
  // Results of the last converged solve (compression positive), for callers.
  double normal_force = 0;  // N (per unit thickness)
  double shear_force = 0;   // N
  double penetration = 0;   // m, positive when the vertex is inside the edge's block

  // What a checkpoint holds (core/archive.hpp): every field.
  template <class Archive>
  void fields(Archive& ar) {
    ar(vblock, eblock, vertex, edge, joint, state, intact, bonded, length, scale, ref_param, ref_valid, slide_sign,
       normal_force, shear_force, penetration);
  }
};

// What the open-close iteration changes in a contact: carried over when the
// contact list is searched again, kept at the start of a step for a redo
// (a fifth of a whole Contact: memory counts on models of 10^5 blocks).
// The shear force and penetration are left out: every solve recomputes them
// before anyone reads them.
struct ContactIterationState {
  double ref_param, normal_force;
  ContactState state;
  bool intact, ref_valid;
  std::int8_t slide_sign;
};

inline ContactIterationState iteration_state(const Contact& c) {
  return {c.ref_param, c.normal_force, c.state, c.intact, c.ref_valid, c.slide_sign};
}

inline void set_iteration_state(Contact& c, const ContactIterationState& s) {
  c.ref_param = s.ref_param;
  c.normal_force = s.normal_force;
  c.state = s.state;
  c.intact = s.intact;
  c.ref_valid = s.ref_valid;
  c.slide_sign = s.slide_sign;
}

inline bool same_identity(const Contact& a, const Contact& b) {
  return a.vblock == b.vblock && a.vertex == b.vertex && a.eblock == b.eblock && a.edge == b.edge;
}
inline bool identity_less(const Contact& a, const Contact& b) {
  if (a.vblock != b.vblock) return a.vblock < b.vblock;
  if (a.vertex != b.vertex) return a.vertex < b.vertex;
  if (a.eblock != b.eblock) return a.eblock < b.eblock;
  return a.edge < b.edge;
}

}  // namespace dda
