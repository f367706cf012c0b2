// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The energy budget's accounting (energy_budget.hpp), in Update: from the
// accepted step displacement, before anything moves.
#include <span>
#include <vector>

#include "contact/contact_detection.hpp"
#include "contact/contact_model.hpp"
#include "world/world_state.hpp"

namespace dda {

// Adds the accepted step d to w.energy: held energy from the blocks' state
// before and after d (the end-of-step velocity from the time scheme), the
// contacts' forces from the last check, the loads' and boundaries' work.
// `elastic` per rock material, `fixed_spring` = fixed_point_factor × g0;
// the contacts' terms are the contact law's (ContactModel::energy).
// The blocks' terms are computed in parallel into `scratch` (the caller's,
// kept from step to step: a step allocates nothing) and summed in block
// order, the same bits for any thread count as one serial loop. The
// contacts' terms are one serial loop, run beside the blocks' terms: on a
// memory-bound machine computing them in parallel into a buffer and summing
// that in contact order took longer (docs/performance.md).
struct BlockEnergyTerms {
  double kinetic_before = 0, kinetic_after = 0, strain_before = 0, strain_after = 0, gravity = 0, damping = 0;
};
struct EnergyScratch {
  std::vector<BlockEnergyTerms> blocks;  // per block
  std::vector<Mat3> compliance;          // per rock material: the elastic matrix's inverse
};
void account_step_energy(WorldState& w, const VecX& d, const TimeScheme& scheme, std::span<const Mat3> elastic,
                         const ContactLinearisation& lin, const ContactModel& contact_law, double fixed_spring,
                         EnergyScratch& scratch);

// After account_step_energy, the contact law's impacts of the step
// (ContactModel::resolve_impacts; the landing law, contact/landing.hpp): the held energy and the work of gravity,
// friction and the boundaries (`solved`: over the accepted solve; `landed`: over the step the law made of it) move to
// the step's end as the law left it, the impact term takes what the impacts changed, and the residual loses what the
// solve's landing springs had put in it: it stays the time integrator's.
void account_impact_energy(EnergyBudget& energy, const ImpactEnergy& impact, const Boundaries::Work& solved,
                           const Boundaries::Work& landed);

}  // namespace dda
