// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Settling: the model brought to equilibrium under what acts on it now
// (gravity, initial stresses, loads at their present values) before a
// dynamic run, as UDEC's `solve` then resetting the motion.
//
// A settling step is a static step (gg = 0: no velocity carried into it)
// with the time held: loads, prescribed motions and incident waves take their
// values at the present time, which does not advance. Its Δt is the model's
// time scale of motion under gravity, sqrt(h_min/|g|)/20 (the default time
// step of a model moved by gravity alone, time_step_rule.hpp); without
// gravity the model's own. In a static step the inertia term 2M/Δt² only
// regularises the solve: with c = 2/Δt², each step solves (K + cM)·d = R
// for the unbalanced force R of the state it starts from, so R shrinks by
// about cm/(k + cm) per step in a mode of stiffness k and mass m.
//
// Convergence: after a static step the unbalanced force of each block is
// the time scheme's out_of_balance (the residual F − K·d of the step's
// system, c·M·d); settling has converged when the largest of them, in
// translation, is at most `tolerance` of the reference force, the largest
// block weight m·|g| (or, without gravity, the largest stress resultant
// |σ|·sqrt(A) over a block).
//
// At rest: every velocity, acceleration and unbalanced force is zero, the
// displacements count from here (block and monitor-point origins), and the
// energy budget starts anew; stresses, contact forces and the time stay.
#include "world/world_state.hpp"

namespace dda {

struct UnbalancedForce {
  double ratio = 0;  // the largest block's unbalanced force over the reference force
  BlockId block = -1;
  double force = 0;      // N/m, that block's
  double reference = 0;  // N/m
};

// The measure above, from the state after the last step.
UnbalancedForce unbalanced_force(const WorldState& w);

// The Δt of a settling step (above).
double settle_time_step(const WorldState& w);

// The end of settling (above).
void come_to_rest(WorldState& w);

// While it lives, the World's steps are settling steps (gg = 0, time held, Δt
// up to settle_time_step); the controls are given back when it ends.
class SettlingSteps {
 public:
  explicit SettlingSteps(WorldState& w);
  ~SettlingSteps();
  SettlingSteps(const SettlingSteps&) = delete;
  SettlingSteps& operator=(const SettlingSteps&) = delete;

 private:
  WorldState& w_;
  double gg_, g1_;
};

}  // namespace dda
