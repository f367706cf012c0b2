// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/penalty_contacts.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "contact/holding_law.hpp"
#include "contact/landing.hpp"
#include "contact/shi_law.hpp"
#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {
// parallel_max's pattern for a result of one's own: fold(i, acc) folds item
// i into acc, join(a, b) joins two partial results; neither may depend on
// the order (maxima, flags), so that the result is the same on any thread
// count.
template <typename T, typename Fold, typename Join>
T parallel_fold(std::size_t n, T init, Fold&& fold, Join&& join) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kOrderFreeGrain), init,
      [&](const tbb::blocked_range<std::size_t>& r, T acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) fold(i, acc);
        return acc;
      },
      join);
}

// The chunks of contacts of the energy terms and the commit: any size gives
// the same sums (each chunk lists its terms, summed in contact order); small
// enough to share among many threads.
constexpr std::size_t kTermChunk = 128;
std::size_t term_chunk_count(std::size_t contacts) { return (contacts + kTermChunk - 1) / kTermChunk; }
}  // namespace

PenaltyContacts::PenaltyContacts() : landing_(std::make_unique<LandingLaw>()) {}
PenaltyContacts::~PenaltyContacts() = default;

// Both penalty laws keep the same history: another's is taken as it is.
void PenaltyContacts::take_over(const ContactModel* previous, std::size_t contacts) {
  const auto* penalty = dynamic_cast<const PenaltyContacts*>(previous);
  if (penalty && penalty->memory_.size() == contacts) {
    memory_ = penalty->memory_;
  } else {
    memory_.assign(contacts, FrictionMemory{});
  }
}

void PenaltyContacts::follow_search(std::span<const int> previous) {
  scratch_memory_.resize(previous.size());
  parallel_for_each(
      previous.size(),
      [&](std::size_t i) { scratch_memory_[i] = previous[i] >= 0 ? memory_[previous[i]] : FrictionMemory{}; }, 1024);
  memory_.swap(scratch_memory_);
}

void PenaltyContacts::check(const ContactParameters& p, const Blocks& blocks) const {
  validate_landing_law(p.restitution, p.integrator, blocks);
}

// The states are copied by the attempt's first pass over the contacts
// (start_attempt): nothing changes them before it. The friction lag's memory
// is not saved: only a commit (an accepted step) and a search (which saves
// again after it) change it.
void PenaltyContacts::save_step(std::span<const Contact> contacts) {
  saved_.resize(contacts.size());
  save_pending_ = true;
}

void PenaltyContacts::restore_step(std::span<Contact> contacts) {
  parallel_for_each(
      contacts.size(), [&](std::size_t i) { set_iteration_state(contacts[i], saved_[i]); }, 1024);
}

// An attempt's starting point: each contact's shear offset, the normal force
// of the last accepted solve (the friction of the first solve) and, with
// friction_lag, its lagged friction normal force and the weight of the new N
// in it over this attempt's dt; then the first guess from the warm start
// (predict, below). One pass over the contacts, which also keeps the step's
// start for a redo after save_step.
template <class Law>
void PenaltyContacts::start_attempt_as(Law& law, std::span<Contact> contacts, const ContactLinearisation& lin,
                                       double dt, const VecX* predicted) {
  iterate_.resize(contacts.size());
  const bool lagging = p_.friction_lag > 0;
  lag_.resize(lagging ? contacts.size() : 0);
  solved_friction_normal_.resize(resolves_impacts() ? contacts.size() : 0);
  dt_ = dt;
  if (predicted) law.measure_step(*predicted);
  const bool save = save_pending_;
  save_pending_ = false;
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        if (save) saved_[i] = iteration_state(c);
        ContactIterate& it = iterate_[i];
        it = {lin.offsets[i].s0, c.normal_force, lin.offsets[i].s0, c.state != ContactState::Open};
        if (lagging) lag_[i] = lagged_friction(memory_[i], c.state, dt, p_.friction_lag);
        if (predicted) predict(law, c, it, lag(i), lin.gradients[i], lin.offsets[i], *predicted);
      },
      1024);
}

template <class Law>
ContactMotion PenaltyContacts::motion(const Law& law, const ContactGradients& k, const ContactOffsets& o, const VecX& d,
                                      const Contact& c, const ContactIterate& it) const {
  const auto dv = d.segment<6>(6 * c.vblock);
  const auto de = d.segment<6>(6 * c.eblock);
  ContactMotion m;
  m.dn = o.d0 + k.en_v.dot(dv) + k.en_e.dot(de);  // summed from d0 on: every law's gap to the last bit
  m.ds_step = k.es_v.dot(dv) + k.es_e.dot(de);
  m.ds = it.s0 + m.ds_step;
  law.set_bands(m, o, it.closed_at_start);
  return m;
}

template <class Law>
bool PenaltyContacts::decide(const Law& law, Contact& c, ContactIterate& it, const LaggedFriction& lag,
                             const JointMaterial& joint, double tan_phi, const ContactSprings& k,
                             const ContactMotion& m) const {
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
  auto lock = [&] {
    c.state = ContactState::Locked;
    if (law.locks_unloaded()) it.s0 = 0;
  };

  if (c.intact && law.unbonded(joint)) c.intact = false;
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
        lock();  // just closed: locked first; the next iteration checks friction
        break;
      case ContactState::Locked:
        if (std::abs(shear) > friction_normal(lag, normal) * tan_phi + k.ks * m.shear_slack) slide_towards(ds);
        break;
      case ContactState::Sliding:
        if (law.locks_again(c, lag, normal, tan_phi, k, m)) lock();
        break;
    }
  }
  it.normal_force = c.state == ContactState::Open ? 0.0 : normal;
  it.shear = ds;
  return c.state != old_state || c.intact != old_intact ||
         (c.state == ContactState::Sliding && c.slide_sign != old_sign);
}

// The open-close iteration's first guess in wave problems (short solves):
// instead of the last step's states, those the warm start implies (the
// displacement the last step's motion extrapolates to), so that the first
// solve is more often the last (blast(2): 2.95 → 2.08 open-close iterations
// per step over its 0.05 s). After long solves (quasi-static walls) the warm
// start is the last step's own displacement, which has little to tell:
// predicting from it took wall(10) 3.7 % more CG iterations (555 against
// 536 per step) and wall(20) the same, so it is not done there
// (solve_regime.hpp). Only transitions a wrong guess cannot harm are taken,
// since the solves that follow undo a wrong guess only where the solved
// displacement contradicts it:
//   * a contact closes (locked first, as in the iteration); a wrong close
//     shows up as tension in the solve and opens again;
//   * a closed contact starts or stops sliding (friction, from the predicted
//     shear against N·tanφ, or the predicted motion reversing); a wrong
//     slide meets full friction against its direction, moves back in the
//     solve and locks again;
// and not:
//   * a closed contact opening: on a contact at rest the predicted gap is
//     round-off around the (small) penetration, and a contact wrongly opened
//     closes again locked, dropping its sliding history (a block sliding down
//     an incline would stick a step at a time);
//   * an intact joint failing: failure is for good, only a solve may cause it;
// and the friction of sliding contacts in the first solve still uses the
// normal force of the last accepted solve, not a predicted one (the solves
// then iterate towards the consistent one, check_solve): predicted from the
// warm start, a block landing on a slope (scripts/incline.lua) got an N of a
// penetration it never reached, and its open-close iteration did not settle
// in five steps.
template <class Law>
void PenaltyContacts::predict(const Law& law, Contact& c, ContactIterate& it, const LaggedFriction& lag,
                              const ContactGradients& k, const ContactOffsets& o, const VecX& d) const {
  if (c.intact) return;
  const ContactIterationState before = iteration_state(c);
  const ContactIterate iterate = it;
  const ContactMotion m = motion(law, k, o, d, c, iterate);
  decide(law, c, it, lag, p_.joints[c.joint], p_.tan_friction[c.joint], contact_springs(c, p_), m);
  if (before.state != ContactState::Open && c.state == ContactState::Open) {
    set_iteration_state(c, before);
    it = iterate;
  }
  it.normal_force = iterate.normal_force;
}

// The springs each contact acts with in this solve (normal on a closed
// contact, shear too on a locked one) and its forces on the right-hand side:
// the springs' offsets and, sliding, the friction N·tanφ against the sliding
// direction, with N from the previous iteration (lagged with friction_lag).
void PenaltyContacts::contribute(std::span<const Contact> contacts, const ContactLinearisation& lin) {
  terms_.resize(contacts.size());
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        const Contact& c = contacts[i];
        const ContactParameters::Springs full = p_.springs(c);
        ContactTerms& t = terms_[i];
        t.kn = c.state == ContactState::Open ? 0.0 : c.scale * full.kn;
        t.ks = c.state == ContactState::Locked ? c.scale * full.ks : 0.0;
        t.acts = c.state != ContactState::Open;
        t.shear_spring = c.state == ContactState::Locked;
        t.follows_iterate = c.state == ContactState::Sliding;
        if (!t.acts) return;
        const ContactIterate& it = iterate_[i];
        t.normal = t.kn * lin.offsets[i].d0;
        t.shear = t.shear_spring ? t.ks * it.s0
                                 : c.slide_sign * (friction_normal(lag(i), it.normal_force) * p_.tan_friction[c.joint]);
      },
      1024);
}

template <class Law>
NextSolve PenaltyContacts::check_solve_as(Law& law, std::span<Contact> contacts, const ContactLinearisation& lin,
                                          const VecX& d) {
  const std::size_t nc = contacts.size();
  changed_.resize(nc);
  law.measure_step(d);
  std::atomic<bool> any_friction{false};  // a sliding contact's N moved
  std::atomic<bool> any_gross{false};     // ... grossly
  struct Found {
    int changed = 0;     // 2: a state changed, 1: friction alone moved
    double deepest = 0;  // the deepest penetration of a closed contact
  };
  const auto check = [&](std::size_t i) {
    Contact& c = contacts[i];
    ContactIterate& it = iterate_[i];
    const ContactSprings springs = contact_springs(c, p_);
    const ContactMotion m = motion(law, lin.gradients[i], lin.offsets[i], d, c, it);
    const double tan_phi = p_.tan_friction[c.joint];
    const ContactState before = c.state;
    const LaggedFriction lag_i = lag(i);
    const double solved_with = it.normal_force;  // the N this solve's friction used
    if (!solved_friction_normal_.empty()) solved_friction_normal_[i] = friction_normal(lag_i, solved_with);
    const bool changed = decide(law, c, it, lag_i, p_.joints[c.joint], tan_phi, springs, m);
    // A contact that slid through the solve with the N of the solve before
    // (or of the prediction), and slides on: whether its friction agrees
    // with the N of this solve (the holding law iterates until it does).
    const FrictionConsistency friction =
        !changed && before == ContactState::Sliding && c.state == ContactState::Sliding
            ? law.friction_consistency(it.normal_force, solved_with, springs, m, lin.offsets[i])
            : FrictionConsistency::Agrees;
    const bool friction_moved = friction != FrictionConsistency::Agrees;
    if (friction == FrictionConsistency::MovedGrossly) any_gross.store(true, std::memory_order_relaxed);
    changed_[i] = changed || friction_moved;
    c.penetration = m.dn;
    c.normal_force = it.normal_force;
    c.shear_force = c.state == ContactState::Locked ? springs.ks * m.ds
                    : c.state == ContactState::Sliding
                        ? law.reported_friction_sign(c) * friction_normal(lag_i, c.normal_force) * tan_phi
                        : 0.0;
    if (friction_moved) any_friction.store(true, std::memory_order_relaxed);
    return changed ? 2 : friction_moved ? 1 : 0;
  };
  const Found found = parallel_fold(
      nc, Found{},
      [&](std::size_t i, Found& f) {
        f.changed = std::max(f.changed, check(i));
        if (contacts[i].state != ContactState::Open) f.deepest = std::max(f.deepest, contacts[i].penetration);
      },
      [](const Found& a, const Found& b) {
        return Found{std::max(a.changed, b.changed), std::max(a.deepest, b.deepest)};
      });
  deepest_penetration_ = found.deepest;
  // States that changed always call for another solve; friction alone as
  // the law says.
  const bool states_changed = found.changed == 2;
  const NextSolve for_friction =
      any_friction.load(std::memory_order_relaxed)
          ? law.solve_again_for_friction(any_gross.load(std::memory_order_relaxed), states_changed)
          : NextSolve::None;
  return states_changed ? NextSolve::Counted : for_friction;
}

// The elastic energy of the closed contacts' springs after the last check,
// and the work of friction on the sliding ones over the step. Each chunk's
// terms (in parallel) into its own list of the terms it adds (an open
// contact adds none), then the lists summed in contact order: the same bits
// as one serial loop over the contacts, for any thread count.
void PenaltyContacts::energy_terms(std::span<const Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                                   std::size_t chunk) const {
  double* held = held_terms_.data() + 2 * chunk * kTermChunk;
  double* friction = friction_terms_.data() + chunk * kTermChunk;
  int h = 0, f = 0;
  for (std::size_t i = chunk * kTermChunk; i < std::min(contacts.size(), (chunk + 1) * kTermChunk); ++i) {
    const Contact& c = contacts[i];
    if (c.state == ContactState::Open) continue;
    const ContactParameters::Springs s = p_.springs(c);
    const double kn = c.scale * s.kn, ks = c.scale * s.ks;
    if (kn > 0) held[h++] = 0.5 * c.normal_force * c.normal_force / kn;
    if (c.state == ContactState::Locked) {
      if (ks > 0) held[h++] = 0.5 * c.shear_force * c.shear_force / ks;
    } else {
      // Sliding: friction (|Contact::shear_force| = N·tanφ) opposes the
      // step's shear motion, whichever sign convention the law reports its
      // shear force in: the work is −|S·ds|.
      const ContactGradients& g = lin.gradients[i];
      const double ds_step = g.es_v.dot(d.segment<6>(6 * c.vblock)) + g.es_e.dot(d.segment<6>(6 * c.eblock));
      friction[f++] = std::abs(c.shear_force * ds_step);
    }
  }
  term_counts_[chunk] = {h, f};
}

std::size_t PenaltyContacts::start_energy_terms(std::size_t contacts) const {
  held_terms_.resize(2 * contacts);
  friction_terms_.resize(contacts);
  term_counts_.resize(term_chunk_count(contacts));
  return term_counts_.size();
}

ContactEnergy PenaltyContacts::sum_energy_terms() const {
  ContactEnergy e;
  for (std::size_t k = 0; k < term_counts_.size(); ++k) {
    const double* held = held_terms_.data() + 2 * k * kTermChunk;
    const double* friction = friction_terms_.data() + k * kTermChunk;
    for (int j = 0; j < term_counts_[k].first; ++j) e.held += held[j];
    for (int j = 0; j < term_counts_[k].second; ++j) e.friction -= friction[j];
  }
  return e;
}

ContactEnergy PenaltyContacts::energy(std::span<const Contact> contacts, const ContactLinearisation& lin,
                                      const VecX& d) const {
  parallel_for_each(
      start_energy_terms(contacts.size()), [&](std::size_t k) { energy_terms(contacts, lin, d, k); }, 1);
  return sum_energy_terms();
}

int PenaltyContacts::resolve_impacts(std::span<Contact> contacts, const ContactLinearisation& lin,
                                     const ImpactInputs& in, VecX& d) {
  return landing_->resolve(contacts, lin, iterate_, solved_friction_normal_, p_, in, d);
}

const ImpactEnergy& PenaltyContacts::impact_energy() const { return landing_->energy(); }

// The accepted step: the landing law's blocks' end states, the shear springs'
// reference points (the landing contacts' springs unloaded), the friction
// lag's memory; chunk by chunk, in parallel, where energy_and_commit also
// makes each chunk's energy terms (one pass over the contacts).
void PenaltyContacts::commit(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin) {
  commit_in_chunks(blocks, contacts, lin, [](std::size_t) {});
}

ContactEnergy PenaltyContacts::energy_and_commit(Blocks& blocks, std::span<Contact> contacts,
                                                 const ContactLinearisation& lin, const VecX& d) {
  start_energy_terms(contacts.size());
  commit_in_chunks(blocks, contacts, lin, [&](std::size_t k) { energy_terms(contacts, lin, d, k); });
  return sum_energy_terms();
}

template <class BeforeCommit>
void PenaltyContacts::commit_in_chunks(Blocks& blocks, std::span<Contact> contacts, const ContactLinearisation& lin,
                                       BeforeCommit&& before_commit) {
  landing_->write_end_states(blocks);
  // Contacts found by a search start with no lagged friction, and a carried
  // contact keeps what it held: without the lag, a list cleared once stays
  // clear.
  const double t_r = p_.friction_lag;
  const bool remember = t_r > 0 || lagged_friction_held_;
  lagged_friction_held_ = t_r > 0;
  const std::size_t n = contacts.size();
  parallel_for_each(
      term_chunk_count(n),
      [&](std::size_t k) {
        before_commit(k);
        const std::size_t begin = k * kTermChunk, end = std::min(n, begin + kTermChunk);
        keep_shear_references(contacts, lin, begin, end);
        if (remember)
          for (std::size_t i = begin; i < end; ++i)
            remember_friction(memory_[i], contacts[i].state, contacts[i].normal_force, lag(i), dt_, t_r);
      },
      1);
  landing_->unload_shear_springs(contacts, lin, iterate_, sliding_keeps_reference());
}

void PenaltyContacts::save(ArchiveWriter& ar) const { ar(memory_); }

void PenaltyContacts::load(ArchiveReader& ar) {
  const std::size_t contacts = memory_.size();
  ar(memory_);
  if (memory_.size() != contacts)
    throw Error(msg(ar.what(), " is damaged: the contact law's memory of ", memory_.size(), " contacts for a list of ",
                    contacts));
  for (std::size_t i = 0; i < memory_.size(); ++i)
    if (std::isnan(memory_[i].normal) || std::isnan(memory_[i].age))
      throw Error(msg(ar.what(), " is damaged: the contact law's memory of contact ", i, " holds NaN"));
  lagged_friction_held_ = true;  // the restored contacts may hold some
}

// The laws' passes (each law's start_attempt and check_solve).
template void PenaltyContacts::start_attempt_as(ShiLaw&, std::span<Contact>, const ContactLinearisation&, double,
                                                const VecX*);
template void PenaltyContacts::start_attempt_as(HoldingLaw&, std::span<Contact>, const ContactLinearisation&, double,
                                                const VecX*);
template NextSolve PenaltyContacts::check_solve_as(ShiLaw&, std::span<Contact>, const ContactLinearisation&,
                                                   const VecX&);
template NextSolve PenaltyContacts::check_solve_as(HoldingLaw&, std::span<Contact>, const ContactLinearisation&,
                                                   const VecX&);

}  // namespace dda
