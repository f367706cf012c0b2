// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/holding_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.hpp"

namespace dda {

namespace {
// The hysteresis of friction decisions: this share of the spread of the
// step's block translations (contact_slack).
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
// Friction consistency (check_solve): the share of N to which the normal
// force of a sliding contact's friction must agree with its solve's, and the
// solves an attempt may add for it alone.
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

// The spread of the blocks' translations in d: per direction, the largest
// block translation less the smallest, the larger of the two directions. The
// motion the friction band follows: the solve's error is relative to the
// step's displacements, yet a translation every block shares (a shaken base
// carrying its blocks, a model moving as a whole) is no motion of any contact
// and drops out. With a block held fixed it is at least the largest
// translation (the band tried and not kept: docs/contacts.md).
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

constexpr IgnoredControl kIgnored[] = {
    {"contact_tolerance",
     "the holding law's bands are shares of the spread of the step's block translations, not a length of the "
     "model"},
};
}  // namespace

double contact_slack(double tolerance, double motion, double edge_length) {
  constexpr double kRoundOff = 1e-12;  // of the edge's length: positions carry ~1e-16 of the coordinates
  return tolerance * motion + kRoundOff * edge_length;
}

std::span<const IgnoredControl> HoldingLaw::ignored_controls() const { return kIgnored; }

void HoldingLaw::start_attempt(std::span<Contact> contacts, const ContactLinearisation& lin, double dt,
                               const VecX* predicted) {
  start_attempt_as(*this, contacts, lin, dt, predicted);
  friction_passes_ = 0;
  gross_passes_ = 0;
}

void HoldingLaw::measure_step(const VecX& d) { spread_ = translation_spread(d); }

// A contact open at the step start approaches in it: the friction band, a
// share of the step's translations, is then a share of its own approach (a
// block landing at 7.7 m/s, Δt = 1 ms: ks × 77 µm, 7.7e6 N against the
// 1e6 N that stop it), and its contact would lock and throw it back. It
// decides friction with the gap band, as its gap.
void HoldingLaw::set_bands(ContactMotion& m, const ContactOffsets& o, bool closed_at_start) const {
  m.gap_slack = contact_slack(kGapTolerance, spread_, o.edge_length);
  m.shear_slack = closed_at_start ? contact_slack(kFrictionTolerance, spread_, o.edge_length) : m.gap_slack;
}

// A joint without cohesion or tensile strength holds nothing an unbonded
// contact does not: decided as one (its friction in the contact's own
// units, not the intact joints' model-wide band).
bool HoldingLaw::unbonded(const JointMaterial& joint) const {
  return joint.cohesion == 0 && joint.tensile_strength == 0;
}

// Once the shear spring, put back, would carry less than the friction: the
// same test as the one that starts the slide, from the other side (a return
// mapping), so that a contact at its friction limit does not alternate
// between a locked solve whose spring exceeds N·tanφ and a sliding one whose
// motion, measured from the step start, reverses while its spring unloads.
// Without a shear spring: once the motion reverses.
bool HoldingLaw::locks_again(const Contact& c, const LaggedFriction& lag, double normal, double tan_phi,
                             const ContactSprings& k, const ContactMotion& m) const {
  return k.ks > 0 ? k.ks * m.ds * c.slide_sign < friction_normal(lag, normal) * tan_phi - k.ks * m.shear_slack
                  : m.ds_step * c.slide_sign < -m.shear_slack;
}

// Friction consistent with the normal force of the accepted solution: a
// contact that slid through the solve with the N of the solve before (or of
// the prediction) iterates again until that N holds, to kConsistency of N
// (and round-off, in force).
FrictionConsistency HoldingLaw::friction_consistency(double normal, double solved_with, const ContactSprings& k,
                                                     const ContactMotion& m, const ContactOffsets& o) const {
  const double moved = std::abs(normal - solved_with);
  if (!(moved > kConsistency * std::abs(normal) + k.kn * contact_slack(0, 0, o.edge_length)))
    return FrictionConsistency::Agrees;
  return moved > kGrossLag * std::abs(normal) + k.kn * m.gap_slack ? FrictionConsistency::MovedGrossly
                                                                   : FrictionConsistency::Moved;
}

// Friction alone asks for at most kMaxFrictionPasses solves (it converges
// fast: a sliding block's N depends on its friction only through its moment,
// and the open-close limit, which cuts the step, must not be spent on it),
// then only while it lags grossly, in solves the open-close limit does not
// count.
NextSolve HoldingLaw::solve_again_for_friction(bool gross, bool states_changed) {
  const bool gross_pass =
      !states_changed && friction_passes_ >= kMaxFrictionPasses && gross && gross_passes_ < kMaxGrossPasses;
  const bool friction_pass = friction_passes_ < kMaxFrictionPasses || gross_pass;
  ++friction_passes_;
  if (gross_pass) ++gross_passes_;
  return !friction_pass ? NextSolve::None : gross_pass ? NextSolve::Uncounted : NextSolve::Counted;
}

// The reference point sits where the shear spring carries the contact's
// shear force: a locked contact keeps the point it locked at (the
// iteration's reference, moved only when it re-locked from the step start's
// offset), a sliding one takes the point behind the vertex at which the
// spring would carry its friction N·tanφ. A contact that locks again (or a
// step redone) then starts from the force it carried, without a jump: a
// spring that re-locked unloaded let a block on an incline slip by its shear
// displacement S/ks at every re-lock and ratchet down the slope.
void HoldingLaw::keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, std::size_t begin,
                                       std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    Contact& c = contacts[i];
    const ContactOffsets& o = lin.offsets[i];
    const ContactIterate& it = iterate_[i];
    const double ks = contact_springs(c, p_).ks;
    if (c.state == ContactState::Open || !(ks > 0)) {
      c.ref_valid = false;
      continue;
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
  }
}

}  // namespace dda
