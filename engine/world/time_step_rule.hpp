// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The default upper step time g1 (the control g1 = 0): Δt from what moves
// the model, as a list of named terms of which the least is taken.
//
// A model moved by gravity alone (no loads, prescribed motions or incident
// waves: gravity, fixed points, resisting springs and dashpots, initial
// velocities and stresses) needs Δt to follow its blocks' motion, whose time
// scale under gravity is sqrt(h/g) (a block of height h falls its own height
// in 1.4 of it and topples in a few):
//
//   Δt_g = sqrt(h_min / |g|) / 20
//
// Any other model is loaded dynamically. Where it moves as bodies under its
// loads (world/wave_model.hpp, moves_as_bodies: first-order blocks, each
// within the element size that resolves the loads' highest frequency f, the
// model within a shear wavelength: a block sliding on its base under an
// earthquake), the loads' waves cross every block quasi-statically and Δt
// follows the loads, and gravity where it acts:
//
//   Δt_f = 1 / (20 f)               a period of the loads' highest frequency in 20 steps
//   Δt   = min(Δt_f, Δt_g)
//
// (resolving the waves inside such blocks, as below, put the step where the
// contacts' springs ring: El Centro's sliding block slid 13 % too far at
// the 1.7e-5 s the paper's rule gave, and within 0.06 % at 1e-4 to 1e-2 s).
// Otherwise Δt follows the waves the loads send through the blocks, as the
// paper's Eqs. 1–3 (a = 0.05, b = 0.177):
//
//   Δt_a = a · h_min / C_P          a P wave crosses the smallest block in 20 steps
//   Δt_b = 2b · sqrt(m_min / g0)    the lightest block on its contact springs: 1/17.7 of that period
//
// h_min is the smallest block's height across its longest edge (its area
// over that edge's length), m_min the smallest block mass, C_P the largest
// P-wave speed of the rocks, g0 the normal contact spring.
//
// A further limit is one more term in default_time_step (time_step_rule.cpp):
// its name, its Δt and its formula, taken into the minimum when it applies.
// docs/time_step.md ("The default time step") has the rule and why.
#include <string>
#include <vector>

#include "world/world_state.hpp"

namespace dda {

struct TimeStepTerm {
  const char* name;     // "waves in the smallest block"
  double dt;            // s
  std::string formula;  // "0.05·h_min/C_P, h_min = 0.2 m, C_P = 2150 m/s"
};

struct TimeStepChoice {
  double dt = 0;               // the least of the terms (0: no blocks)
  bool gravity_alone = false;  // the model is moved by gravity alone
  bool bodies = false;         // loaded dynamically, moving as bodies (Δt_f)
  std::vector<TimeStepTerm> terms;
  // "Δt = 1.13e-02 s, moved by gravity alone: motion under gravity,
  // sqrt(h_min/|g|)/20 (h_min = 0.5 m)" (for the run log).
  std::string describe() const;
};

// The rule above for the model as it is now.
TimeStepChoice default_time_step(const WorldState& w);

// Δt_g, the motion term, whatever else moves the model (0 without gravity).
double motion_time_step(const WorldState& w);

}  // namespace dda
