// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The energy budget's accounting (energy_budget.hpp), in Update: from the
// accepted step displacement and the blocks as they were before it.
#include <span>
#include <vector>

#include "contact/contact_model.hpp"
#include "world/world_state.hpp"

namespace dda {

// The accepted step's energy, booked while Update moves the blocks, then
// added to w.energy (account): held energy from the blocks' state before and
// after the step (the end-of-step velocity from the time scheme), the
// contacts' forces from the last check (ContactModel::energy), the loads' and
// boundaries' work. `elastic` per rock material, `fixed_spring` =
// fixed_point_factor × g0. The blocks' terms come one block at a time from
// the pass that moves them (move_blocks' before_move), which has each
// block's mass matrix as the step's system had it, into a per-block buffer
// summed in block order: the same bits for any thread count as one serial
// loop. The buffers are kept from step to step: a step allocates nothing.
struct BlockEnergyTerms {
  double kinetic_before = 0, kinetic_after = 0, strain_before = 0, strain_after = 0, gravity = 0, damping = 0;
};
class StepEnergy {
 public:
  // Before anything moves, over the accepted solve's displacement d: the
  // loads' and boundaries' work, each material's compliance.
  void start(const WorldState& w, const VecX& d, const TimeScheme& scheme, std::span<const Mat3> elastic,
             double fixed_spring);
  // Block b's terms under its share d_b of the accepted solve, before it
  // moves; mass = ρ∫TᵀT of the block as it was.
  void book_block(const Blocks& blocks, std::size_t b, const Vec6& d_b, const IntegratedTt& mass);
  // The contacts' terms (ContactModel::energy, before an impact changes
  // them).
  void book_contacts(const ContactEnergy& contacts) { contacts_ = contacts; }
  // Adds the step to w.energy.
  void account(WorldState& w) const;

 private:
  const TimeScheme* scheme_ = nullptr;
  std::span<const Mat3> elastic_;
  Vec2 gravity_ = Vec2::Zero();
  double strain_damping_ = 0;
  std::vector<Mat3> compliance_;  // per rock material: the elastic matrix's inverse
  std::vector<BlockEnergyTerms> blocks_;
  ContactEnergy contacts_;
  Loads::Work loads_;
  Boundaries::Work boundaries_;
};

// After StepEnergy::account, the contact law's impacts of the step
// (ContactModel::resolve_impacts; the landing law, contact/landing.hpp): the held energy and the work of gravity,
// friction and the boundaries (`solved`: over the accepted solve; `landed`: over the step the law made of it) move to
// the step's end as the law left it, the impact term takes what the impacts changed, and the residual loses what the
// solve's landing springs had put in it: it stays the time integrator's.
void account_impact_energy(EnergyBudget& energy, const ImpactEnergy& impact, const Boundaries::Work& solved,
                           const Boundaries::Work& landed);

}  // namespace dda
