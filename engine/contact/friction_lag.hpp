// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Friction that lags the normal force (the control friction_lag, t_r in
// seconds; 0: none; docs/friction_flutter.md): the normal force N_f a contact's
// friction strength acts with follows N as the simplified Prakash–Clifton
// law over the interface's own life. Both penalty laws apply it
// (penalty_contacts.hpp), each contact's memory (FrictionMemory) their
// per-contact history.
#include <cmath>

#include "contact/contact.hpp"

namespace dda {

// What a contact carries from step to step: the normal force N_f its
// friction strength acted with at the end of the last accepted step, the
// mean of its N over its memory t_r; and its memory's age (s): > 0, how long
// the interface has been closed (N_f averages only the N it has carried
// since; infinite once it closed again after a brief opening: the same
// interface, its memory full); < 0, open for that long after being closed,
// briefly so far; 0: none (open for longer, never closed, or no
// friction_lag).
struct FrictionMemory {
  double normal = 0;
  double age = 0;

  template <class Archive>
  void fields(Archive& ar) {
    ar(normal, age);
  }
};

// A contact's lag in an attempt at a step: the lagged normal force at the
// step start, N_f0, and the step's weight w of the new N (lag_weight below);
// w = 1 (no lag) without friction_lag and for a contact with no lagged force
// yet (FrictionMemory).
struct LaggedFriction {
  double start = 0;
  double weight = 1;
};

// The weight of a step's N in the lagged friction normal force N_f of a
// contact whose memory is `age` old (s: how long it has been closed) at the
// step's start, over a step dt, lag t_r: N_f is the mean of the N the
// interface has carried, each instant weighted by exp(−(its age)/t_r), and
// the weights normalised over the interface's life only, since a landing is a
// new interface with no normal-force history before it closed:
//   w = (1 − exp(−dt/t_r)) / (1 − exp(−(age + dt)/t_r)),
// the exact step of that mean with N held over the step. A new contact
// (age 0) takes its first N (w = 1); while age ≪ t_r, N_f is the running
// mean of N since it closed (w ≈ dt/(age + dt)); once age ≫ t_r, the
// simplified Prakash–Clifton law dN_f/dt = (N − N_f)/t_r stepped exactly
// (w = 1 − exp(−dt/t_r); age infinite: an interface that closed again after a
// brief opening, remember_friction). At dt ≫ t_r, w = 1 to the last bit:
// no lag.
inline double lag_weight(double dt, double age, double t_r) {
  return std::expm1(-dt / t_r) / std::expm1(-(age + dt) / t_r);
}

// The lag of a contact in `state` with memory m in an attempt of step dt
// (t_r: friction_lag, 0 none).
inline LaggedFriction lagged_friction(const FrictionMemory& m, ContactState state, double dt, double t_r) {
  if (state != ContactState::Open && t_r > 0 && m.age > 0) return {m.normal, lag_weight(dt, m.age, t_r)};
  return {};
}

// The normal force a contact's friction strength acts with when its normal
// force at the step's end is n (compression positive): max(0, n), or with
// friction_lag the lagged N_f = N_f0 + w·(max(0, n) − N_f0), w from
// lag_weight above (the simplified Prakash–Clifton law, Ranjith and Rice
// 2001, over the interface's own life): stable for every Δt/t_r, the unlagged
// max(0, n) once Δt ≫ t_r (w = 1), and N itself in steady sliding. Every
// friction decision and force takes its N from here.
inline double friction_normal(const LaggedFriction& lag, double n) {
  const double now = n > 0 ? n : 0.0;
  return lag.weight == 1 ? now : lag.start + lag.weight * (now - lag.start);
}

// The accepted step of dt, with friction_lag t_r > 0: a closed contact keeps
// the lagged normal force its friction strength ended the step with, N_f
// (locked or sliding: the strength is a state of the contact that follows
// N, the Prakash–Clifton law; the force of a locked contact is its spring's,
// not touched by the lag), and its memory grows one step older; an open one
// drops N_f. A contact that closes as a new interface (a new one, one
// transferred to another edge, or one open for longer than a share of t_r:
// a landing) starts from its first N, and its strength is the mean of the N
// it has carried since (lag_weight): a strength it never had would let it
// hold where it must slide, one from zero would let a landing block slide
// frictionless for t_r, and its first N held for t_r let a block landing or
// loaded at once slide on the low N of its first step. A contact that closes
// again after a brief opening is the same interface: from its first N with
// the full memory t_r, so that a sliding block's contacts that open and
// close in a flutter do not follow N at once each time they close. Without
// friction_lag (t_r = 0) the contact holds none. `state` and `normal_force`:
// the contact's at the step's end.
void remember_friction(FrictionMemory& m, ContactState state, double normal_force, const LaggedFriction& lag, double dt,
                       double t_r);

}  // namespace dda
