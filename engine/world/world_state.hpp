// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What a World is: its controls, materials, blocks, loads, boundaries,
// followed points, contacts and clock. The World's methods build and read it;
// the Stepper (stepper.hpp) advances it one step at a time.
#include <vector>

#include "block/blocks.hpp"
#include "block/remeshing.hpp"
#include "boundary/boundaries.hpp"
#include "contact/contact.hpp"
#include "core/load_check.hpp"
#include "core/material.hpp"
#include "loading/loads.hpp"
#include "world/controls.hpp"
#include "world/energy_budget.hpp"
#include "world/step_profile.hpp"
#include "world/wave_model.hpp"

namespace dda {

struct WorldState {
  Controls controls;
  std::vector<RockMaterial> rocks;
  std::vector<JointMaterial> joints;
  Blocks blocks;
  Loads loads;
  Boundaries boundaries;
  std::vector<MaterialPoint> tracked;  // followed through the run (for monitors)
  std::vector<Contact> contacts;

  double time = 0;
  long steps = 0;
  double dt = 0;           // the next step's Δt (0: not yet chosen)
  double half_height = 0;  // the g2 reference length, fixed by the first step's checks (0: not yet)
  bool prepared = false;   // the first-step checks ran on these blocks
  StepStats last_stats;
  EnergyBudget energy;
  // The wave model decided before the first step, and what meshing the
  // blocks in place changed (world/wave_model.hpp).
  WaveModel wave;
  Remeshing remeshing;
  // Settling (World::settle_step): the step's loads, prescribed motions and
  // incident waves take their values at `time`, which does not advance.
  bool hold_time = false;

  // What a checkpoint holds (core/archive.hpp): all of it.
  template <class Archive>
  void fields(Archive& ar) {
    ar.section("controls"), ar(controls);
    ar.section("materials"), ar(rocks, joints);
    ar.section("blocks"), ar(blocks);
    ar.section("loads"), ar(loads);
    ar.section("boundaries"), ar(boundaries);
    ar.section("tracked points"), ar(tracked);
    ar.section("contacts"), ar(contacts);
    ar.section("clock"), ar(time, steps, dt, half_height, prepared, last_stats);
    ar.section("energy"), ar(energy);
    ar.section("wave model"), ar(wave, remeshing);
    if constexpr (Archive::reading) check_loaded(LoadCheck(ar.what()));
  }
  // Read from a checkpoint: every index and size against the model, before
  // the Stepper builds anything from it. Throws dda::Error naming the damage.
  void check_loaded(const LoadCheck& check) const;
  void check_loaded_wave_model(const LoadCheck& check) const;

  // Half the y extent of the blocks as they are now.
  double measured_half_height() const;
  // The contact spring g0 (N/m): the controls', or 50 × the stiffest rock's E.
  double contact_spring() const;
  // The time the step's loads and motions are evaluated at: t + Δt, or t
  // while settling (hold_time).
  double step_end_time() const { return hold_time ? time : time + dt; }
};

}  // namespace dda
