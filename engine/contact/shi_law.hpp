// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// contact_law = "shi": Shi's (1988) contact law as the paper has it, and as
// the engine had it before the holding law, bit for bit (the paper's
// figures, docs/validation.md, bench/state_hashes_shi.txt). Penalty springs
// decided by the open-close iteration (penalty_contacts.hpp), with:
//   * one band for every decision, contact_tolerance × half the model's
//     height (a length of the model);
//   * a contact that closes or locks again does so unloaded, at its position
//     at the step's start; a sliding contact locks again once its motion
//     reverses;
//   * friction uses the normal force of the solve before;
//   * the shear reference point of a locked contact is where it locked;
//     a sliding contact keeps none;
//   * the warm start extrapolates with this step's Δt, and the reported shear
//     force of a sliding contact has the sign the engine gave it before.
// A block that must stay on a slope creeps down it at small Δt
// (docs/contacts.md).
#include "contact/penalty_contacts.hpp"

namespace dda {

class ShiLaw final : public PenaltyContacts {
 public:
  ContactLaw law() const override { return ContactLaw::Shi; }
  std::span<const IgnoredControl> ignored_controls() const override { return {}; }
  double warm_start_dt(double /*last_dt*/, double dt) const override { return dt; }
  void start_attempt(std::span<Contact> contacts, const ContactLinearisation& lin, double dt,
                     const VecX* predicted) override {
    start_attempt_as(*this, contacts, lin, dt, predicted);
  }
  NextSolve check_solve(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d) override {
    return check_solve_as(*this, contacts, lin, d);
  }

 private:
  friend class PenaltyContacts;  // asks the decisions' questions below
  // Every decision has the model-wide band.
  void set_bands(ContactMotion& m, const ContactOffsets& /*o*/, bool /*closed_at_start*/) const {
    m.gap_slack = m.shear_slack = p_.tolerance;
  }
  bool locks_unloaded() const { return true; }
  // Once the motion since the step's start reverses (then unloaded).
  bool locks_again(const Contact& c, const LaggedFriction& /*lag*/, double /*normal*/, double /*tan_phi*/,
                   const ContactSprings& /*k*/, const ContactMotion& m) const {
    return m.ds_step * c.slide_sign < -m.shear_slack;
  }
  double reported_friction_sign(const Contact& c) const { return -c.slide_sign; }
  void keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, std::size_t begin,
                             std::size_t end) override;
  bool sliding_keeps_reference() const override { return false; }
};

}  // namespace dda
