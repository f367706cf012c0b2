// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/settle.hpp"

#include <algorithm>
#include <cmath>

#include "world/time_step_rule.hpp"

namespace dda {

UnbalancedForce unbalanced_force(const WorldState& w) {
  UnbalancedForce u;
  const Blocks& blocks = w.blocks;
  const double g = w.controls.gravity.norm();
  for (std::size_t b = 0; b < blocks.count(); ++b) {
    const Vec6& r = blocks.out_of_balance[b];
    const double force = std::isnan(r[0]) ? 0 : std::hypot(r[0], r[1]);
    if (force > u.force) u.force = force, u.block = static_cast<BlockId>(b);
    const double weight = blocks.mass[b] * g;
    const double stress = blocks.stress[b].cwiseAbs().maxCoeff() * std::sqrt(blocks.area[b]);
    u.reference = std::max({u.reference, weight, g > 0 ? 0.0 : stress});
  }
  u.ratio = u.reference > 0 ? u.force / u.reference : (u.force > 0 ? INFINITY : 0);
  return u;
}

double settle_time_step(const WorldState& w) {
  const double g = w.controls.gravity.norm();
  if (g > 0) return motion_time_step(w);
  return w.controls.g1 > 0 ? w.controls.g1 : default_time_step(w).dt;
}

void come_to_rest(WorldState& w) {
  Blocks& blocks = w.blocks;
  std::fill(blocks.velocity.begin(), blocks.velocity.end(), Vec6::Zero());
  std::fill(blocks.acceleration.begin(), blocks.acceleration.end(), Vec6::Zero());
  std::fill(blocks.out_of_balance.begin(), blocks.out_of_balance.end(), Vec6::Zero());
  std::fill(blocks.last_displacement.begin(), blocks.last_displacement.end(), Vec6::Zero());
  blocks.initial_centroid = blocks.centroid;
  blocks.initial_vertices = blocks.vertices;
  for (MaterialPoint& p : w.tracked) p.origin = p.point;
  w.energy = EnergyBudget{};
}

SettlingSteps::SettlingSteps(WorldState& w) : w_(w), gg_(w.controls.gg), g1_(w.controls.g1) {
  const double dt = settle_time_step(w);
  w.controls.gg = 0;
  w.controls.g1 = dt;
  w.dt = dt;  // from the settling Δt, not a wave model's small one; cuts then work as in any step
  w.hold_time = true;
}

SettlingSteps::~SettlingSteps() {
  w_.controls.gg = gg_;
  w_.controls.g1 = g1_;
  w_.hold_time = false;
}

}  // namespace dda
