// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// contact_law = "holding" (the default): penalty springs decided by the
// open-close iteration (penalty_contacts.hpp), with friction that holds a
// block that must hold at every step size (docs/contacts.md):
//   * bands in the step's own units: a share of the spread of the step's
//     block translations (and round-off of the contact's edge), not a length
//     of the model; a contact open at the step's start decides friction
//     with the gap band;
//   * a contact's shear force is continuous through its changes of state
//     (shear memory: the reference point sits where the spring carries the
//     force the contact ended the step with), and a sliding contact locks
//     again by a return mapping;
//   * friction agrees with the normal force of the accepted solve (solves
//     for friction alone);
//   * joints without cohesion or tension are unbonded from the start;
//   * the warm start after a cut or growth of Δt holds the last accepted
//     step's acceleration.
#include "contact/penalty_contacts.hpp"

namespace dda {

// The bands of the holding law (friction; with a smaller share, gaps and
// intact joints), in the step's own units: a displacement, the tolerance's
// share of the spread of the step's block translations (`motion`: a
// translation all blocks share drops out: a shaken base), and at least
// round-off of the contact's edge's length. The decision values come from a
// solve whose error is relative to the step's displacements, so the band
// follows the step: it is neither a length of the model (a contact in a
// model 100× larger decides the same) nor a force through g0, and it
// vanishes for blocks at rest, where friction must hold to its last newton.
// (The model's spread, not the contact's own relative motion: a settling
// wall's vertical joints, which carry next to nothing, slid and opened on
// the loose solves' error with that: docs/contacts.md.)
double contact_slack(double tolerance, double motion, double edge_length);

class HoldingLaw final : public PenaltyContacts {
 public:
  ContactLaw law() const override { return ContactLaw::Holding; }
  std::span<const IgnoredControl> ignored_controls() const override;
  double warm_start_dt(double last_dt, double dt) const override { return last_dt > 0 ? last_dt : dt; }
  void start_attempt(std::span<Contact> contacts, const ContactLinearisation& lin, double dt,
                     const VecX* predicted) override;
  NextSolve check_solve(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d) override {
    return check_solve_as(*this, contacts, lin, d);
  }

 private:
  friend class PenaltyContacts;  // asks the decisions' questions below
  void measure_step(const VecX& d);
  void set_bands(ContactMotion& m, const ContactOffsets& o, bool closed_at_start) const;
  bool unbonded(const JointMaterial& joint) const;
  bool locks_unloaded() const { return false; }
  bool locks_again(const Contact& c, const LaggedFriction& lag, double normal, double tan_phi, const ContactSprings& k,
                   const ContactMotion& m) const;
  FrictionConsistency friction_consistency(double normal, double solved_with, const ContactSprings& k,
                                           const ContactMotion& m, const ContactOffsets& o) const;
  NextSolve solve_again_for_friction(bool gross, bool states_changed);
  void keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, std::size_t begin,
                             std::size_t end) override;
  bool sliding_keeps_reference() const override { return true; }

  double spread_ = 0;        // of the block translations of the displacement decided on (measure_step)
  int friction_passes_ = 0;  // solves of this attempt redone for friction alone
  int gross_passes_ = 0;     // ... of them for a gross lag, not counted by the open-close limit
};

}  // namespace dda
