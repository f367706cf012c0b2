// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What the two penalty laws ("shi", shi_law.hpp; "holding", holding_law.hpp)
// share: contacts as springs (normal on a closed contact, shear on a locked
// one) decided by an open-close iteration (open / sliding / locked,
// Mohr-Coulomb on the springs' forces, Shi 1988), the friction lag
// (friction_lag.hpp) and the landing law (landing.hpp). Each law says, in its
// own file, what is its own: the bands of its decisions, how a sliding
// contact locks again, whether it locks unloaded, whether friction iterates
// to the accepted solve's normal force, where the shear springs' reference
// points go at the step's end.
#include <memory>
#include <span>
#include <vector>

#include "contact/contact_model.hpp"
#include "contact/friction_lag.hpp"

namespace dda {

class LandingLaw;

// Per-contact values that change during the open-close iteration of a step
// (32 bytes: every pass of the iteration reads them; what only the friction
// lag and the landing law need is kept apart, below).
struct ContactIterate {
  // Shear offset of the spring at the step start: the shear force the
  // contact carried into the step over ks (the holding law puts the
  // reference point there at the end of the step before), 0 for a contact
  // open at the step start. Kept through the step, so that the shear force
  // is continuous through every change of state (under Shi's law: 0 once it
  // closes or locks again).
  double s0 = 0;
  double normal_force = 0;  // from the previous iteration: drives sliding friction
  double shear = 0;         // shear ds at the last check (m)
  // Closed at the start of the step. A contact that was open approaches in
  // the step: under the holding law it decides friction with the gap band,
  // not the friction band of a share of the step's translations, which for a
  // block landing fast is many times the force that stops it (holding_law.cpp).
  bool closed_at_start = false;
};

// A contact under a displacement d of the blocks (a solve's, or a warm
// start's): its gap and shear, and the hysteresis of the decision.
struct ContactMotion {
  double dn = 0;           // penetration after the step (positive: the vertex is inside)
  double ds = 0;           // shear from the reference point after the step
  double ds_step = 0;      // shear motion in the step (the sliding direction)
  double gap_slack = 0;    // the hysteresis of gap decisions and intact joints (m)
  double shear_slack = 0;  // the hysteresis of friction decisions (m)
};

// Whether a sliding contact's friction agrees with the normal force of the
// solve it slid through (the holding law iterates until it does:
// holding_law.hpp).
enum class FrictionConsistency { Agrees, Moved, MovedGrossly };

class PenaltyContacts : public ContactModel {
 public:
  PenaltyContacts();
  ~PenaltyContacts() override;

  void take_over(const ContactModel* previous, std::size_t contacts) override;
  void follow_search(std::span<const int> previous) override;
  void check(const ContactParameters& p, const Blocks& blocks) const override;
  void save_step(std::span<const Contact> contacts) override;
  void restore_step(std::span<Contact> contacts) override;
  void contribute(std::span<const Contact> contacts, const ContactLinearisation& lin) override;
  ContactEnergy energy(std::span<const Contact> contacts, const ContactLinearisation& lin,
                       const VecX& d) const override;
  bool resolves_impacts() const override { return p_.restitution >= 0; }
  int resolve_impacts(std::span<Contact> contacts, const ContactLinearisation& lin, const ImpactInputs& in,
                      VecX& d) override;
  const ImpactEnergy& impact_energy() const override;
  void commit(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin) override;
  ContactEnergy energy_and_commit(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin,
                                  const VecX& d) override;
  void save(ArchiveWriter& ar) const override;
  void load(ArchiveReader& ar) override;

  // The friction lag's memory of each contact (for tests).
  std::span<const FrictionMemory> friction_memory() const { return memory_; }

 protected:
  // ---- What each law says (its own file)
  // The decisions' questions are asked of every contact in every open-close
  // iteration, so a law answers them without virtual calls: each law
  // overrides start_attempt and check_solve with the passes below bound to
  // itself (start_attempt_as, check_solve_as), which call these by the law's
  // own type. The defaults here are for a law that does not say otherwise.
  //
  // Before the decisions on a displacement d (a solve's, or the warm
  // start's): what the bands need of it.
  void measure_step(const VecX& /*d*/) {}
  // The bands of the decisions of a contact (m.gap_slack, m.shear_slack):
  //   void set_bands(ContactMotion& m, const ContactOffsets& o, bool closed_at_start) const;
  // An intact joint that is decided as an unbonded contact from the start.
  bool unbonded(const JointMaterial& /*joint*/) const { return false; }
  // Whether a contact that closes or locks again does so unloaded (its
  // shear offset dropped to 0 at its position at the step's start):
  //   bool locks_unloaded() const;
  // Whether a sliding contact locks again:
  //   bool locks_again(const Contact& c, const LaggedFriction& lag, double normal, double tan_phi,
  //                    const ContactSprings& k, const ContactMotion& m) const;
  // Whether the friction of a contact that slid through the solve with the
  // normal force `solved_with` and slides on agrees with the solve's own
  // normal force (Agrees: the law does not iterate friction); and, when one
  // did not, whether another solve is wanted for friction alone (`gross`:
  // one moved grossly; `states_changed`: another solve comes anyway).
  FrictionConsistency friction_consistency(double /*normal*/, double /*solved_with*/, const ContactSprings& /*k*/,
                                           const ContactMotion& /*m*/, const ContactOffsets& /*o*/) const {
    return FrictionConsistency::Agrees;
  }
  NextSolve solve_again_for_friction(bool /*gross*/, bool /*states_changed*/) { return NextSolve::None; }
  // The sign of a sliding contact's reported shear force (Contact::shear_force)
  // against its sliding direction.
  double reported_friction_sign(const Contact& c) const { return c.slide_sign; }
  // The accepted step's shear reference points (Contact::ref_param) of
  // contacts [begin, end), and whether a sliding contact keeps one.
  virtual void keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, std::size_t begin,
                                     std::size_t end) = 0;
  virtual bool sliding_keeps_reference() const = 0;

  // The open-close passes over the contacts, with the law's questions (above)
  // asked of `law` (the object itself, by its own type).
  template <class Law>
  void start_attempt_as(Law& law, std::span<Contact> contacts, const ContactLinearisation& lin, double dt,
                        const VecX* predicted);
  template <class Law>
  NextSolve check_solve_as(Law& law, std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d);

  // Per contact, parallel to the contact list.
  std::vector<ContactIterate> iterate_;
  // Friction that lags the normal force (friction_lag.hpp): each contact's
  // N_f0 and w of the attempt, with friction_lag on; empty without it, when
  // every contact's is LaggedFriction{} (friction follows N).
  std::vector<LaggedFriction> lag_;
  LaggedFriction lag(std::size_t i) const { return lag_.empty() ? LaggedFriction{} : lag_[i]; }
  // With the landing law on: the friction normal force each contact's last
  // solve used (landing.hpp takes that solve's forces out of the step).
  std::vector<double> solved_friction_normal_;

 private:
  // A contact's first guess from the warm start d (start_attempt).
  template <class Law>
  void predict(const Law& law, Contact& c, ContactIterate& it, const LaggedFriction& lag, const ContactGradients& k,
               const ContactOffsets& o, const VecX& d) const;
  // The decision both laws share: the contact's next state from its motion
  // under the latest displacements (Mohr-Coulomb on the springs' forces,
  // with the law's bands and re-locking). Returns true when the state (or
  // the intact flag, or the sliding direction) changed.
  template <class Law>
  bool decide(const Law& law, Contact& c, ContactIterate& it, const LaggedFriction& lag, const JointMaterial& joint,
              double tan_phi, const ContactSprings& k, const ContactMotion& m) const;
  // A contact's motion under d, from the shear offset s0 in force.
  template <class Law>
  ContactMotion motion(const Law& law, const ContactGradients& k, const ContactOffsets& o, const VecX& d,
                       const Contact& c, const ContactIterate& it) const;

  // The per-contact history: the friction lag's memory (friction_lag.hpp).
  std::vector<FrictionMemory> memory_;
  std::vector<FrictionMemory> scratch_memory_;  // follow_search's
  // At the start of the step, for a redo: taken by the attempt's first pass
  // over the contacts (save_pending_), which finds them as save_step did.
  std::vector<ContactIterationState> saved_;
  bool save_pending_ = false;
  double dt_ = 0;  // the attempt's step (s)
  // Whether a contact may hold a lagged friction force (the last commit left
  // one, or the contacts came from elsewhere: a checkpoint, another law).
  // Without friction_lag and with none held, a commit has nothing to drop.
  bool lagged_friction_held_ = true;
  std::unique_ptr<LandingLaw> landing_;
  // The energy terms of chunk `chunk` of the contacts (of kTermChunk), into
  // its lists; the lists' sizes for `contacts` contacts (returns the number
  // of chunks); their sum in contact order.
  void energy_terms(std::span<const Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                    std::size_t chunk) const;
  std::size_t start_energy_terms(std::size_t contacts) const;
  ContactEnergy sum_energy_terms() const;
  // commit, chunk by chunk; before_commit(chunk) first in each.
  template <class BeforeCommit>
  void commit_in_chunks(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin,
                        BeforeCommit&& before_commit);
  // The energy terms, per chunk of contacts, in contact order: what the
  // chunk's contacts add to the held energy (up to two each) and take by
  // friction (one), and how many of each (kept from step to step, so a step
  // allocates nothing).
  mutable std::vector<double> held_terms_, friction_terms_;
  mutable std::vector<std::pair<int, int>> term_counts_;
};

}  // namespace dda
