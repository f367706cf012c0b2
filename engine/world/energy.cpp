// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/energy.hpp"

#include <cmath>
#include <vector>

#include <tbb/parallel_invoke.h>
#include <Eigen/LU>

#include "assembly/block_terms.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {

// Kinetic and strain energy of the blocks before and after the step, with
// the mass and area of the step's system (the blocks as they were), and the
// work of gravity: per block, summed in block order.
struct BlockEnergy {
  double kinetic_before = 0, kinetic_after = 0, strain_before = 0, strain_after = 0, gravity = 0;
  double damping = 0;  // work of the strains' damping (≤ 0), with the VBC dashpots' ("viscous")
};

BlockEnergy block_energy(const Blocks& blocks, const VecX& d, const TimeScheme& scheme, std::span<const Mat3> elastic,
                         const Vec2& gravity, double strain_damping, EnergyScratch& scratch) {
  // Each material's compliance once (the same inverse every block of it
  // took), each block's terms in parallel, then summed in block order: the
  // same bits as one serial loop, for any thread count.
  std::vector<Mat3>& compliance = scratch.compliance;
  compliance.resize(elastic.size());
  for (std::size_t m = 0; m < elastic.size(); ++m) compliance[m] = elastic[m].inverse();
  std::vector<BlockEnergyTerms>& per_block = scratch.blocks;
  per_block.resize(blocks.count());
  parallel_for_each(blocks.count(), [&](std::size_t b) {
    const Vec6 db = d.segment<6>(6 * b);
    const BlockState s = blocks.scheme_state(static_cast<BlockId>(b));
    const IntegratedTt mass = block_tt(blocks, b, scheme.mesh_mass).scaled(blocks.mass[b] / blocks.area[b]);
    const Vec6 v1 = scheme.end_velocity(db, s);
    const Mat3& c = compliance[blocks.material[b]];
    const Vec3 before = blocks.stress[b], after = before + elastic[blocks.material[b]] * db.tail<3>();
    BlockEnergyTerms& t = per_block[b];
    t.kinetic_before = 0.5 * s.velocity.dot(mass * s.velocity);
    t.kinetic_after = 0.5 * v1.dot(mass * v1);
    t.strain_before = 0.5 * blocks.area[b] * before.dot(c * before);
    t.strain_after = 0.5 * blocks.area[b] * after.dot(c * after);
    t.gravity = blocks.mass[b] * gravity.dot(db.head<2>());
    t.damping = 0;
    if (strain_damping > 0) {
      // The damping force at the step's start and end strain rates, over the
      // step's strain increment (as a VBC dashpot's work).
      const Mat3 cd = strain_damping * blocks.area[b] * elastic[blocks.material[b]];
      t.damping = 0.5 * (cd * (s.velocity.tail<3>() + v1.tail<3>())).dot(db.tail<3>());
    }
  });
  BlockEnergy e;
  for (const BlockEnergyTerms& t : per_block) {
    e.kinetic_before += t.kinetic_before;
    e.kinetic_after += t.kinetic_after;
    e.strain_before += t.strain_before;
    e.strain_after += t.strain_after;
    e.gravity += t.gravity;
    if (strain_damping > 0) e.damping -= t.damping;
  }
  return e;
}

}  // namespace

void account_step_energy(WorldState& w, const VecX& d, const TimeScheme& scheme, std::span<const Mat3> elastic,
                         const ContactLinearisation& lin, const ContactModel& contact_law, double fixed_spring,
                         EnergyScratch& scratch) {
  // The contacts' serial sum runs beside the blocks' parallel terms (each
  // result its own, so the same bits): the step waits for the longer only.
  BlockEnergy blocks;
  ContactEnergy contacts;
  tbb::parallel_invoke(
      [&] {
        blocks = block_energy(w.blocks, d, scheme, elastic, w.controls.gravity, w.controls.strain_damping, scratch);
      },
      [&] { contacts = contact_law.energy(w.contacts, lin, d); });
  const Loads::Work loads = w.loads.step_work(w.blocks, d);
  const Boundaries::Work bounds = w.boundaries.step_work(w.time, w.step_end_time(), fixed_spring, w.blocks, d, scheme);

  EnergyTerms step;
  step.kinetic = blocks.kinetic_after;
  step.strain = blocks.strain_after;
  step.contact = contacts.held;
  step.gravity = blocks.gravity;
  step.point_loads = loads.point;
  step.pressure = loads.pressure;
  step.targets = bounds.targets;
  step.fixed_points = bounds.fixed_points;
  step.viscous = bounds.viscous + blocks.damping;
  step.spring_boundaries = bounds.springs;
  step.friction = contacts.friction;
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
