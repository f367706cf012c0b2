#include "contact/open_close.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/parallel.hpp"

namespace dda {

void save_contact_states(std::span<const Contact> contacts, OpenCloseState& s) {
  s.saved.resize(contacts.size());
  parallel_for_each(
      contacts.size(), [&](std::size_t i) { s.saved[i] = iteration_state(contacts[i]); }, 1024);
}

void restore_contact_states(std::span<Contact> contacts, const OpenCloseState& s) {
  parallel_for_each(
      contacts.size(), [&](std::size_t i) { set_iteration_state(contacts[i], s.saved[i]); }, 1024);
}

namespace {
// Friction that lags the normal force: a contact that closes again within
// this share of t_r after it opened is the same interface, whose strength
// keeps the full memory t_r (the lag as if it had never opened, from its
// first N); one open for longer is a new interface, whose strength is the
// mean of the N it carries since it closed (lag_weight, contact_law.hpp).
// 60° on 45° with gravity on at once at Δt = 1e-5 s chatters with every
// re-closing a new interface (or at 0.1 t_r), and two landings that rock
// move at 1 t_r (docs/contacts.md, Tried and not kept).
constexpr double kSameInterface = 0.3;
}  // namespace

void start_open_close(std::span<const Contact> contacts, const ContactLinearisation& lin, const ContactParameters& p,
                      double dt, OpenCloseState& s) {
  s.iterate.resize(contacts.size());
  s.friction_passes = 0;
  s.gross_passes = 0;
  s.free_pass = false;
  s.dt = dt;
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        const Contact& c = contacts[i];
        const bool closed = c.state != ContactState::Open;
        s.iterate[i] = {lin.offsets[i].s0, c.normal_force, lin.offsets[i].s0, closed};
        if (closed && p.friction_lag > 0 && c.friction_age > 0) {
          s.iterate[i].lag_start = c.friction_normal;
          s.iterate[i].lag_weight = lag_weight(dt, c.friction_age, p.friction_lag);
        }
      },
      1024);
}

ContactSprings contact_springs(const Contact& c, const ContactParameters& p) {
  const ContactParameters::Springs k = p.springs(c);
  return {c.scale * k.kn, c.scale * k.ks};
}

namespace {
// The holding law's hysteresis of friction decisions: this share of the
// spread of the step's block translations (contact_slack).
constexpr double kFrictionTolerance = 1e-2;
// ... and of gap decisions and intact joints: a hundredth of the friction's.
// A gap's band is a penetration that carries no force: it must stay well
// below the penetrations that carry the loads (a brick's weight on its
// springs, 5e-8 m, is 1e-2 of a settling wall's spread, where the friction's
// share made the walls' answer depend on the iteration's path), yet above
// the error of the loose solves on contacts that carry nothing (1e-6 and
// below: wall(20) with gg = 1 cut 11 of its 30 steps, against 2).
// docs/contacts.md has the measurements.
constexpr double kGapTolerance = 1e-4;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Friction consistency (check_contact_states): the share of N to which the
// normal force of a sliding contact's friction must agree with its solve's,
// and the solves an attempt may add for it alone.
constexpr double kConsistency = 1e-6;
constexpr int kMaxFrictionPasses = 1;
// ... beyond which friction alone asks for more solves only while it lags
// grossly: a sliding contact's N moved by more than this share of itself
// (and the gap band's force) through the solve. Those solves do not count
// against the open-close limit (a cut step lands a block differently:
// docs/contacts.md), up to kMaxGrossPasses an attempt. A block dropped onto
// its springs by gravity switched on at once changes N by factors of 2 to 8
// between solves; a landing's friction lags by up to 30 % (at 30 % and
// below, the 1 m landing of Friction.BlockLandingOnAFlatFaceFromOneMetreEndsWhereItLands
// ends 0.3 mm back, not 19 µm).
constexpr double kGrossLag = 0.5;
constexpr int kMaxGrossPasses = 30;

// A contact's motion under the displacement d of a solve (or of a warm
// start), from the shear offset s0 in force.
ContactMotion contact_motion(const ContactGradients& k, const ContactOffsets& o, const VecX& d, const Contact& c,
                             double s0, const ContactParameters& p, double step_motion, bool closed_at_start) {
  const auto dv = d.segment<6>(6 * c.vblock);
  const auto de = d.segment<6>(6 * c.eblock);
  ContactMotion m;
  m.dn = o.d0 + k.en_v.dot(dv) + k.en_e.dot(de);  // summed from d0 on: every law's gap to the last bit
  m.ds_step = k.es_v.dot(dv) + k.es_e.dot(de);
  m.ds = s0 + m.ds_step;
  if (p.law == ContactLaw::Shi) {
    // Shi's law: every decision has the model-wide band.
    m.gap_slack = m.shear_slack = p.tolerance;
    return m;
  }
  m.gap_slack = contact_slack(kGapTolerance, step_motion, o.edge_length);
  // A contact open at the step start approaches in it: the friction band, a
  // share of the step's translations, is then a share of its own approach
  // (a block landing at 7.7 m/s, Δt = 1 ms: ks × 77 µm, 7.7e6 N against the
  // 1e6 N that stop it), and its contact would lock and throw it back. It
  // decides friction with the gap band, as its gap.
  m.shear_slack = closed_at_start ? contact_slack(kFrictionTolerance, step_motion, o.edge_length) : m.gap_slack;
  return m;
}

// The spread of the blocks' translations in d: per direction, the largest
// block translation less the smallest, the larger of the two directions. The
// motion the friction band follows: the solve's error is relative to the
// step's displacements, yet a translation every block shares (a shaken base
// carrying its blocks, a model moving as a whole) is no motion of any contact
// and drops out. With a block held fixed it is at least the largest
// translation (what the band was before: docs/contacts.md).
double translation_spread(const VecX& d) {
  const std::size_t n = static_cast<std::size_t>(d.size() / 6);
  double spread = 0;
  for (const int axis : {0, 1}) {
    const double high = parallel_max<double>(n, -kInfinity, [&](std::size_t b) { return d[6 * b + axis]; });
    const double low = -parallel_max<double>(n, -kInfinity, [&](std::size_t b) { return -d[6 * b + axis]; });
    if (n > 0) spread = std::max(spread, high - low);
  }
  return spread;
}

}  // namespace

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
// then iterate towards the consistent one, check_contact_states): predicted
// from the warm start, a block landing on a slope (scripts/incline.lua) got
// an N of a penetration it never reached, and its open-close iteration did
// not settle in five steps.
void predict_contact_states(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                            const ContactParameters& p, OpenCloseState& s) {
  const double step_motion = translation_spread(d);
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        if (c.intact) return;
        const ContactIterationState before = iteration_state(c);
        const ContactIterate iterate = s.iterate[i];
        const ContactMotion m =
            contact_motion(lin.gradients[i], lin.offsets[i], d, c, iterate.s0, p, step_motion, iterate.closed_at_start);
        update_contact_state(c, s.iterate[i], p.joints[c.joint], p.tan_friction[c.joint], contact_springs(c, p), m,
                             p.law);
        if (before.state != ContactState::Open && c.state == ContactState::Open) {
          set_iteration_state(c, before);
          s.iterate[i] = iterate;
        }
        s.iterate[i].normal_force = iterate.normal_force;
      },
      1024);
}

bool check_contact_states(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                          const ContactParameters& p, OpenCloseState& s) {
  const std::size_t nc = contacts.size();
  s.changed.resize(nc);
  const double step_motion = translation_spread(d);
  std::atomic<bool> any_friction{false};  // a sliding contact's N moved
  std::atomic<bool> any_gross{false};     // ... by more than kGrossLag of N
  const int any_changed = parallel_max<int>(nc, 0, [&](std::size_t i) {
    Contact& c = contacts[i];
    const ContactSprings springs = contact_springs(c, p);
    const ContactMotion m = contact_motion(lin.gradients[i], lin.offsets[i], d, c, s.iterate[i].s0, p, step_motion,
                                           s.iterate[i].closed_at_start);
    const double tan_phi = p.tan_friction[c.joint];
    const ContactState before = c.state;
    const double solved_with = s.iterate[i].normal_force;  // the N this solve's friction used
    s.iterate[i].solved_normal = solved_with;
    bool changed = update_contact_state(c, s.iterate[i], p.joints[c.joint], tan_phi, springs, m, p.law);
    // Friction consistent with the normal force of the accepted solution: a
    // contact that slid through the solve with the N of the solve before (or
    // of the prediction) iterates again until that N holds, to kConsistency
    // of N (and round-off, in force).
    bool friction_moved = false;
    if (p.law == ContactLaw::Holding && !changed && before == ContactState::Sliding &&
        c.state == ContactState::Sliding) {
      const double n = s.iterate[i].normal_force;
      const double moved = std::abs(n - solved_with);
      friction_moved =
          moved > kConsistency * std::abs(n) + springs.kn * contact_slack(0, 0, lin.offsets[i].edge_length);
      if (friction_moved && moved > kGrossLag * std::abs(n) + springs.kn * m.gap_slack)
        any_gross.store(true, std::memory_order_relaxed);
    }
    s.changed[i] = changed || friction_moved;
    c.penetration = m.dn;
    c.normal_force = s.iterate[i].normal_force;
    // (Shi's law kept the engine's earlier sign of the sliding friction,
    // against the spring's: its results, state hashes included, are the
    // earlier ones bit for bit.)
    const double friction_sign = p.law == ContactLaw::Shi ? -c.slide_sign : c.slide_sign;
    c.shear_force = c.state == ContactState::Locked ? springs.ks * m.ds
                    : c.state == ContactState::Sliding
                        ? friction_sign * friction_normal(s.iterate[i], c.normal_force) * tan_phi
                        : 0.0;
    if (friction_moved) any_friction.store(true, std::memory_order_relaxed);
    return changed ? 2 : friction_moved ? 1 : 0;
  });
  // States that changed always call for another solve; friction alone for
  // at most kMaxFrictionPasses (it converges fast: a sliding block's N
  // depends on its friction only through its moment, and the open-close
  // limit, which cuts the step, must not be spent on it), then only while it
  // lags grossly, in solves the open-close limit does not count (free_pass).
  const bool friction = any_friction.load(std::memory_order_relaxed);
  const bool gross_pass = friction && any_changed < 2 && s.friction_passes >= kMaxFrictionPasses &&
                          any_gross.load(std::memory_order_relaxed) && s.gross_passes < kMaxGrossPasses;
  const bool friction_pass = friction && (s.friction_passes < kMaxFrictionPasses || gross_pass);
  if (friction) ++s.friction_passes;
  if (gross_pass) ++s.gross_passes;
  s.free_pass = gross_pass;
  return any_changed == 2 || friction_pass;
}

double deepest_penetration(std::span<const Contact> contacts) {
  return parallel_max<double>(contacts.size(), 0.0, [&](std::size_t i) {
    return contacts[i].state == ContactState::Open ? 0.0 : contacts[i].penetration;
  });
}

namespace {
// Shi's law: a contact that ends the step locked keeps the point it locked at
// (or takes its position at the step start, where it locked again unloaded);
// others drop it.
void keep_locked_references(std::span<Contact> contacts, const ContactLinearisation& lin, const OpenCloseState& s) {
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        if (c.state == ContactState::Locked) {
          if (!c.ref_valid || s.iterate[i].s0 != lin.offsets[i].s0) {
            c.ref_param = lin.offsets[i].param;
            c.ref_valid = true;
          }
        } else {
          c.ref_valid = false;
        }
      },
      256);
}
}  // namespace

// The reference point sits where the shear spring carries the contact's
// shear force: a locked contact keeps the point it locked at (the iteration's
// reference, moved only when it re-locked from the step start's offset), a
// sliding one takes the point behind the vertex at which the spring would
// carry its friction N·tanφ. A contact that locks again (or a step redone)
// then starts from the force it carried, without a jump: a spring that
// re-locked unloaded let a block on an incline slip by its shear
// displacement S/ks at every re-lock and ratchet down the slope.
void keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, const OpenCloseState& s,
                           const ContactParameters& p) {
  if (p.law == ContactLaw::Shi) {
    keep_locked_references(contacts, lin, s);
    return;
  }
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        const ContactOffsets& o = lin.offsets[i];
        const ContactIterate& it = s.iterate[i];
        const double ks = contact_springs(c, p).ks;
        if (c.state == ContactState::Open || !(ks > 0)) {
          c.ref_valid = false;
          return;
        }
        // Where it.shear was measured from.
        const double reference = c.ref_valid && it.s0 == o.s0 ? c.ref_param : o.param - it.s0 / o.edge_length;
        if (c.state == ContactState::Locked) {
          c.ref_param = reference;
        } else {
          const double carried = c.shear_force / ks;  // the friction's shear offset
          c.ref_param = reference + (it.shear - carried) / o.edge_length;
        }
        c.ref_valid = true;
      },
      256);
}

void keep_lagged_friction(std::span<Contact> contacts, OpenCloseState& s, const ContactParameters& p) {
  const bool lag = p.friction_lag > 0;
  // Contacts found by a search start with none, and a carried contact keeps
  // what it held: without the lag, a list cleared once stays clear.
  if (!lag && !s.lagged_friction_held) return;
  s.lagged_friction_held = lag;
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        const double age = c.friction_age;
        if (!lag) {
          c.friction_normal = 0;
          c.friction_age = 0;
        } else if (c.state != ContactState::Open) {
          c.friction_normal = friction_normal(s.iterate[i], c.normal_force);
          // One step older; closed again after a brief opening: the same
          // interface, its memory full (w = 1 − exp(−Δt/t_r) from now on).
          c.friction_age = age > 0 ? age + s.dt : age < 0 ? kInfinity : s.dt;
        } else {
          // Open: how long, while that is brief (kSameInterface).
          const double open_for = (age < 0 ? -age : 0.0) + s.dt;
          c.friction_normal = 0;
          c.friction_age = age != 0 && open_for < kSameInterface * p.friction_lag ? -open_for : 0.0;
        }
      },
      1024);
}

}  // namespace dda
