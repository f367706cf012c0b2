#pragma once
// The contacts' side of the open-close iteration: the first guess of their
// states (PredictStates), the open / sliding / locked decision after each
// solve (CheckContacts, Mohr-Coulomb in contact_law.hpp), and what a step
// keeps for a redo and leaves behind once accepted.
#include <span>
#include <vector>

#include "contact/contact.hpp"
#include "contact/contact_detection.hpp"
#include "contact/contact_law.hpp"
#include "core/material.hpp"

namespace dda {

// The contact law's parameters for a step.
struct ContactParameters {
  double g0 = 0;           // normal spring (resolved: never 0)
  double shear_ratio = 0;  // shear spring / normal spring
  double tolerance = 0;    // Shi's law: the band of every decision (m), contact_tolerance × half the height
  std::span<const JointMaterial> joints;
  std::span<const double> tan_friction;  // tan φ per joint material

  // A contact's full springs (before its overlap scale): its joint's
  // stiffness over the length it stands for when the joint material gives
  // one and the contact stands for a length (facing edges), else g0 and
  // shear_ratio·g0 (corners, and joints without a stiffness).
  struct Springs {
    double kn, ks;
  };
  Springs springs(const Contact& c) const {
    const JointMaterial& j = joints[c.joint];
    if (j.normal_stiffness > 0 && c.length > 0) {
      const double ks = j.shear_stiffness > 0 ? j.shear_stiffness : shear_ratio * j.normal_stiffness;
      return {j.normal_stiffness * c.length, ks * c.length};
    }
    return {g0, shear_ratio * g0};
  }
  ContactLaw law = ContactLaw::Holding;  // update_contact_state
  // Friction that lags the normal force by t_r = friction_lag (s; 0: none,
  // the control of that name; docs/contacts.md).
  double friction_lag = 0;
};

// A contact's springs (ContactParameters::springs), scaled by its overlap scale.
ContactSprings contact_springs(const Contact& c, const ContactParameters& p);

// Per contact, parallel to the contact list: what the open-close iteration
// works on.
struct OpenCloseState {
  std::vector<ContactIterate> iterate;
  std::vector<char> changed;                 // by the last check (its rows are reassembled)
  int friction_passes = 0;                   // solves of this attempt redone for friction alone
  int gross_passes = 0;                      // ... of them for a gross lag, not counted by the open-close limit
  bool free_pass = false;                    // the last check asked for such a solve
  double dt = 0;                             // the attempt's step (s)
  std::vector<ContactIterationState> saved;  // at the start of the step, for a redo
  // Whether a contact may hold a lagged friction force (keep_lagged_friction
  // left one, or the contacts came from elsewhere: a checkpoint). Without
  // friction_lag and with none held, the step has nothing to drop.
  bool lagged_friction_held = true;
};

// The contacts' iteration state at the start of a step, and back to it.
void save_contact_states(std::span<const Contact> contacts, OpenCloseState& s);
void restore_contact_states(std::span<Contact> contacts, const OpenCloseState& s);

// An attempt's starting point: each contact's shear offset, the normal
// force of the last accepted solve (Shi's friction lag) and, with
// friction_lag, its lagged friction normal force and the weight of the new
// N in it over this attempt's dt (lag_weight, contact_law.hpp).
void start_open_close(std::span<const Contact> contacts, const ContactLinearisation& lin, const ContactParameters& p,
                      double dt, OpenCloseState& s);

// The open-close iteration's first guess from a warm start d (see the .cpp
// for the transitions taken and those not).
void predict_contact_states(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                            const ContactParameters& p, OpenCloseState& s);

// The open-close decision after a solve d; records each contact's
// penetration and forces. True when any contact changed.
bool check_contact_states(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                          const ContactParameters& p, OpenCloseState& s);

// The deepest penetration of a closed contact (the g2 bound).
double deepest_penetration(std::span<const Contact> contacts);

// The accepted step: a closed contact keeps (or takes) the shear reference
// point at which its shear spring carries the shear force it ends the step
// with (locked: its spring force; sliding: its friction); open ones drop it.
void keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, const OpenCloseState& s,
                           const ContactParameters& p);

// The accepted step, with friction_lag: a closed contact keeps the lagged
// normal force its friction strength ended the step with, N_f (locked or
// sliding: the strength is a state of the contact that follows N, the
// Prakash–Clifton law; the force of a locked contact is its spring's, not
// touched by the lag), and its memory grows one step older; an open one drops
// N_f. A contact that closes as a new interface (a new one, one transferred to
// another edge, or one open for longer than a share of t_r: a landing)
// starts from its first N, and its strength is the mean of the N it has
// carried since (lag_weight): a strength it never had would let it hold where
// it must slide, one from zero would let a landing block slide frictionless
// for t_r, and its first N held for t_r let a block landing or loaded at once
// slide on the low N of its first step. A contact that closes again after a
// brief opening is the same interface: from its first N with the full memory
// t_r, so that a sliding block's contacts that open and close in a flutter do
// not follow N at once each time they close. Without friction_lag every
// contact holds none (a pass only where one may hold one).
void keep_lagged_friction(std::span<Contact> contacts, OpenCloseState& s, const ContactParameters& p);

}  // namespace dda
