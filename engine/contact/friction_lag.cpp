// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/friction_lag.hpp"

#include <limits>

namespace dda {

namespace {
// A contact that closes again within this share of t_r after it opened is
// the same interface, whose strength keeps the full memory t_r (the lag as
// if it had never opened, from its first N); one open for longer is a new
// interface, whose strength is the mean of the N it carries since it closed
// (lag_weight). 60° on 45° with gravity on at once at Δt = 1e-5 s chatters
// with every re-closing a new interface (or at 0.1 t_r), and two landings
// that rock move at 1 t_r (docs/friction_flutter.md, Tried and not kept).
constexpr double kSameInterface = 0.3;
}  // namespace

void remember_friction(FrictionMemory& m, ContactState state, double normal_force, const LaggedFriction& lag, double dt,
                       double t_r) {
  const double age = m.age;
  if (!(t_r > 0)) {
    m.normal = 0;
    m.age = 0;
  } else if (state != ContactState::Open) {
    m.normal = friction_normal(lag, normal_force);
    // One step older; closed again after a brief opening: the same
    // interface, its memory full (w = 1 − exp(−Δt/t_r) from now on).
    m.age = age > 0 ? age + dt : age < 0 ? std::numeric_limits<double>::infinity() : dt;
  } else {
    // Open: how long, while that is brief (kSameInterface).
    const double open_for = (age < 0 ? -age : 0.0) + dt;
    m.normal = 0;
    m.age = age != 0 && open_for < kSameInterface * t_r ? -open_for : 0.0;
  }
}

}  // namespace dda
