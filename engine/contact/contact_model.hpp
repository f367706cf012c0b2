// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The contact model: one contact law behind one interface (as LAMMPS
// GRANULAR's sub-models, each declaring its per-contact history, and Kratos's
// ConstitutiveLaw with its Check / Initialize / Calculate / Finalize). The
// Stepper holds one model, chosen by the control contact_law, and asks it, at
// each stage of the step:
//
//   begin_step      check          refuse controls the law cannot work with
//                                  (and declare those it ignores)
//   DetectContacts  follow_search  the list was searched again: the law's
//                                  per-contact history follows each contact
//                                  by its identity
//   step start      save_step      what a redo of the step restores
//   PredictStates   start_attempt  the attempt's starting point (Δt) and,
//                                  in wave problems, a first guess of the
//                                  states from the warm start
//   Assemble        contribute     what each contact adds to the system for
//                                  the current iterate: springs on the
//                                  diagonal, forces on the right-hand side
//   CheckContacts   check_solve    whether another solve is needed
//   ControlStep     restore_step   a rejected attempt's redo
//   Update          energy, resolve_impacts, commit: the energy terms, an
//                   impact law that acts on the accepted step's velocities,
//                   and what the contacts keep for the next step
//
// Each law is one file: "shi" (shi_law.hpp), Shi's (1988) law as the paper
// has it; "holding" (holding_law.hpp), the default. Both decide contacts by
// an open-close iteration over penalty springs (penalty_contacts.hpp).
#include <memory>
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "block/time_scheme.hpp"
#include "contact/contact.hpp"
#include "contact/contact_detection.hpp"
#include "core/material.hpp"
#include "core/symmetric6.hpp"

namespace dda {

class ArchiveWriter;
class ArchiveReader;

// The controls and constants a contact law works with in a step.
struct ContactParameters {
  double g0 = 0;           // normal spring (resolved: never 0)
  double shear_ratio = 0;  // shear spring / normal spring
  double tolerance = 0;    // contact_tolerance × half the height (m): Shi's band of every decision
  std::span<const JointMaterial> joints;
  std::span<const double> tan_friction;  // tan φ per joint material
  // Friction that lags the normal force by t_r = friction_lag (s; 0: none,
  // the control of that name; friction_lag.hpp).
  double friction_lag = 0;
  // The landing law's coefficient of restitution (the control restitution;
  // -1: off; landing.hpp), and what it must be checked against.
  double restitution = -1;
  Integrator integrator = Integrator::Shi;

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
};

// A contact's springs: its full springs (ContactParameters::springs) scaled
// by its overlap scale.
struct ContactSprings {
  double kn = 0;
  double ks = 0;
};
// (Inline: every check and prediction of every contact asks for them.)
inline ContactSprings contact_springs(const Contact& c, const ContactParameters& p) {
  const ContactParameters::Springs k = p.springs(c);
  return {c.scale * k.kn, c.scale * k.ks};
}

// What a contact adds to the system for the current iterate: on
// dn = d0 + en·D and ds = s0 + es·D (contact_kinematics.hpp), a spring kn on
// dn and, where shear_spring, a spring ks on ds (kn·en·enᵀ and ks·es·esᵀ on
// its blocks' diagonal blocks, the coupling through the operator), and on
// the right-hand side F −= normal·en + shear·es (normal = kn·d0 for a
// spring; shear = ks·s0 for a spring, or a friction force).
struct ContactTerms {
  double kn = 0, ks = 0;         // the springs the operator couples the blocks with (0: none)
  double normal = 0, shear = 0;  // the forces on the right-hand side
  bool acts = false;             // adds to its blocks' rows at all
  bool shear_spring = false;     // its shear spring acts (ks on the diagonal)
  // Its force changes from solve to solve with no change of state (sliding
  // friction following the latest N): its rows are gathered again every
  // solve.
  bool follows_iterate = false;
};

// What a check of a solve asks for.
enum class NextSolve {
  None,      // settled: no contact asks for another solve
  Counted,   // another solve, counted against open_close_limit
  Uncounted  // another solve that open_close_limit does not count
};

// The contacts' energy terms over an accepted step (J/m): held in the
// closed contacts' springs at its end, and the work of friction (≤ 0).
struct ContactEnergy {
  double held = 0, friction = 0;
};

// What an impact law changed in a step, for the energy budget (J/m). The
// held terms and gravity's work as the solve left them, to the step's end
// after the impacts (kinetic, strain, contact, gravity); and what the solve's
// impact contacts did within the step (solved, against the step without
// them: the blocks' kinetic and strain energy, the springs' energy, gravity's
// and friction's work), which the budget had put in the residual and in
// friction. The impact's work is their balance: the residual keeps the time
// integrator's own.
struct ImpactEnergy {
  double kinetic = 0, strain = 0, contact = 0, gravity = 0;  // after − solved
  double from_solve = 0;  // solved − without the impact contacts, less gravity's work
  double friction = 0;    // the impact contacts' friction work as booked (≤ 0)
  double work() const { return kinetic + strain + contact - gravity + from_solve; }
};

// What an impact law reads of the step besides the contacts.
struct ImpactInputs {
  const Blocks& blocks;
  const TimeScheme& scheme;
  std::span<const Symmetric6> own_stiffness;  // per block: its own system's diagonal block (no contacts)
  std::span<const Mat3> elastic;              // per rock material
  std::span<const char> held;                 // per block: 1 for an immovable one (Boundaries::held_blocks)
  Vec2 gravity;
};

// A control a law does not read, and why: set away from its default under
// that law, it is refused (world/inert_controls.hpp; docs/contacts.md).
struct IgnoredControl {
  const char* control;
  const char* why;
};

class ContactModel {
 public:
  virtual ~ContactModel();
  virtual ContactLaw law() const = 0;

  // ---- The law's per-contact history: what it keeps of its own for each
  // contact from step to step (beside what every law keeps in Contact),
  // parallel to the contact list. A law that keeps none needs neither call.
  // A model made for a list of `contacts` contacts, which `previous` (another
  // law's model; nullptr: none) ran until now: the history it starts from,
  // the previous model's where that means the same to this law, else none.
  virtual void take_over(const ContactModel* /*previous*/, std::size_t /*contacts*/) {}
  // The list was searched again: contact i of the new list is contact
  // previous[i] of the old one (-1: a new contact, with no history).
  virtual void follow_search(std::span<const int> /*previous*/) {}

  // ---- begin_step
  // Throws dda::Error naming a control this law cannot work with here (with
  // these blocks, under this integrator), with the cure.
  virtual void check(const ContactParameters& p, const Blocks& blocks) const = 0;
  // The controls this law does not read.
  virtual std::span<const IgnoredControl> ignored_controls() const = 0;
  // The step's parameters (checked).
  void set_parameters(const ContactParameters& p) { p_ = p; }
  const ContactParameters& parameters() const { return p_; }

  // ---- The step's start, and a redo of it
  // What the open-close iteration changes in the contacts and the law's
  // per-contact state, kept at the step's start; and back to it.
  virtual void save_step(std::span<const Contact> contacts) = 0;
  virtual void restore_step(std::span<Contact> contacts) = 0;

  // ---- An attempt at the step (Δt = dt)
  // The Δt of the step the warm start extrapolates from (the last accepted
  // one's, `last_dt`, 0 before the first step; or this attempt's).
  virtual double warm_start_dt(double last_dt, double dt) const = 0;
  // The attempt's starting point and, given a warm start (`predicted`: the
  // displacement it extrapolates to; null: no guess), a first guess of the
  // contacts' states from it: one pass over the contacts.
  virtual void start_attempt(std::span<Contact> contacts, const ContactLinearisation& lin, double dt,
                             const VecX* predicted) = 0;
  // What each contact adds to the system for the current iterate (terms()),
  // and which contacts changed since the last contribution (changed(); read
  // only when not every row is gathered).
  virtual void contribute(std::span<const Contact> contacts, const ContactLinearisation& lin) = 0;
  std::span<const ContactTerms> terms() const { return terms_; }
  std::span<const char> changed() const { return changed_; }
  // Checks a solve d: each contact's state, forces and penetration, and
  // whether another solve is needed.
  virtual NextSolve check_solve(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d) = 0;
  // The deepest penetration of a closed contact at the last check (0: none;
  // the g2 bound of ControlStep), found in its pass over the contacts.
  double deepest_penetration() const { return deepest_penetration_; }

  // ---- Update (the accepted step d)
  virtual ContactEnergy energy(std::span<const Contact> contacts, const ContactLinearisation& lin,
                               const VecX& d) const = 0;
  // An impact law that acts on the accepted step: whether it acts in this
  // step; then, on the accepted step d (changed in place; the caller moves
  // the blocks with it), the number of contacts it resolved, and what that
  // changed in the energy budget.
  virtual bool resolves_impacts() const { return false; }
  virtual int resolve_impacts(std::span<Contact> /*contacts*/, const ContactLinearisation& /*lin*/,
                              const ImpactInputs& /*in*/, VecX& /*d*/) {
    return 0;
  }
  virtual const ImpactEnergy& impact_energy() const;
  // After the blocks moved: what the contacts keep for the next step, and
  // the impacted blocks' end-of-step state. Without impacts
  // (resolves_impacts() false) it touches no block, and may run beside the
  // pass that moves them.
  virtual void commit(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin) = 0;
  // energy() then commit(), without impacts: a model may do both in one
  // pass over the contacts (the same results).
  virtual ContactEnergy energy_and_commit(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin,
                                          const VecX& d) {
    const ContactEnergy e = energy(contacts, lin, d);
    commit(blocks, contacts, lin);
    return e;
  }

  // ---- Checkpoint: the law's own state carried from step to step, its
  // per-contact history included (load: into a model that took over the
  // restored list, take_over(nullptr, its size)).
  virtual void save(ArchiveWriter& /*ar*/) const {}
  virtual void load(ArchiveReader& /*ar*/) {}

 protected:
  ContactParameters p_;
  std::vector<ContactTerms> terms_;  // per contact
  std::vector<char> changed_;        // per contact
  double deepest_penetration_ = 0;
};

// The model of a contact law.
std::unique_ptr<ContactModel> make_contact_model(ContactLaw law);

}  // namespace dda
