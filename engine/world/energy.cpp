// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/energy.hpp"

#include <cmath>
#include <vector>

#include <Eigen/LU>

namespace dda {

void StepEnergy::start(const WorldState& w, const VecX& d, const TimeScheme& scheme, std::span<const Mat3> elastic,
                       double fixed_spring) {
  scheme_ = &scheme;
  elastic_ = elastic;
  gravity_ = w.controls.gravity;
  strain_damping_ = w.controls.strain_damping;
  // Each material's compliance once: the same inverse every block of it took.
  compliance_.resize(elastic.size());
  for (std::size_t m = 0; m < elastic.size(); ++m) compliance_[m] = elastic[m].inverse();
  blocks_.resize(w.blocks.count());
  loads_ = w.loads.step_work(w.blocks, d);
  boundaries_ = w.boundaries.step_work(w.time, w.step_end_time(), fixed_spring, w.blocks, d, scheme);
}

// Kinetic and strain energy of the block before and after the step, with the
// mass and area of the step's system (the block as it was), and the work of
// gravity and of the strains' damping.
void StepEnergy::book_block(const Blocks& blocks, std::size_t b, const Vec6& d_b, const IntegratedTt& mass) {
  const BlockState s = blocks.scheme_state(static_cast<BlockId>(b));
  const Vec6 v1 = scheme_->end_velocity(d_b, s);
  const Mat3& e = elastic_[blocks.material[b]];
  const Mat3& c = compliance_[blocks.material[b]];
  const Vec3 before = blocks.stress[b], after = before + e * d_b.tail<3>();
  BlockEnergyTerms& t = blocks_[b];
  t.kinetic_before = 0.5 * s.velocity.dot(mass * s.velocity);
  t.kinetic_after = 0.5 * v1.dot(mass * v1);
  t.strain_before = 0.5 * blocks.area[b] * before.dot(c * before);
  t.strain_after = 0.5 * blocks.area[b] * after.dot(c * after);
  t.gravity = blocks.mass[b] * gravity_.dot(d_b.head<2>());
  t.damping = 0;
  if (strain_damping_ > 0) {
    // The damping force at the step's start and end strain rates, over the
    // step's strain increment (as a VBC dashpot's work).
    const Mat3 cd = strain_damping_ * blocks.area[b] * e;
    t.damping = 0.5 * (cd * (s.velocity.tail<3>() + v1.tail<3>())).dot(d_b.tail<3>());
  }
}

void StepEnergy::account(WorldState& w) const {
  BlockEnergyTerms blocks;  // summed in block order (damping: its work, ≤ 0)
  for (const BlockEnergyTerms& t : blocks_) {
    blocks.kinetic_before += t.kinetic_before;
    blocks.kinetic_after += t.kinetic_after;
    blocks.strain_before += t.strain_before;
    blocks.strain_after += t.strain_after;
    blocks.gravity += t.gravity;
    if (strain_damping_ > 0) blocks.damping -= t.damping;
  }

  EnergyTerms step;
  step.kinetic = blocks.kinetic_after;
  step.strain = blocks.strain_after;
  step.contact = contacts_.held;
  step.gravity = blocks.gravity;
  step.point_loads = loads_.point;
  step.pressure = loads_.pressure;
  step.targets = boundaries_.targets;
  step.fixed_points = boundaries_.fixed_points;
  step.viscous = boundaries_.viscous + blocks.damping;
  step.spring_boundaries = boundaries_.springs;
  step.friction = contacts_.friction;
  const double contact_before = w.energy.started ? w.energy.total.contact : 0.0;
  const double held_before = blocks.kinetic_before + blocks.strain_before + contact_before;
  step.residual = (step.held() - held_before) - step.work();

  EnergyTerms& total = w.energy.total;
  total.kinetic = step.kinetic;
  total.strain = step.strain;
  total.contact = step.contact;
  total.gravity += step.gravity;
  total.point_loads += step.point_loads;
  total.pressure += step.pressure;
  total.targets += step.targets;
  total.fixed_points += step.fixed_points;
  total.viscous += step.viscous;
  total.spring_boundaries += step.spring_boundaries;
  total.friction += step.friction;
  total.residual += step.residual;
  w.energy.last_step = step;
  w.energy.started = true;
}

void account_impact_energy(EnergyBudget& energy, const ImpactEnergy& impact, const Boundaries::Work& solved,
                           const Boundaries::Work& landed) {
  const Boundaries::Work moved{landed.fixed_points - solved.fixed_points, landed.targets - solved.targets,
                               landed.viscous - solved.viscous, landed.springs - solved.springs};
  const double boundaries = moved.fixed_points + moved.targets + moved.viscous + moved.springs;
  for (EnergyTerms* t : {&energy.last_step, &energy.total}) {
    t->kinetic += impact.kinetic;
    t->strain += impact.strain;
    t->contact += impact.contact;
    t->gravity += impact.gravity;
    t->friction -= impact.friction;
    t->fixed_points += moved.fixed_points;
    t->targets += moved.targets;
    t->viscous += moved.viscous;
    t->spring_boundaries += moved.springs;
    t->residual -= impact.from_solve + boundaries - impact.friction;
  }
  energy.last_step.impact = impact.work();
  energy.total.impact += impact.work();
}

}  // namespace dda
