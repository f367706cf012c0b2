// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The energy budget (J per metre of thickness): what the blocks and contacts
// hold, the work each kind of load and boundary does on the blocks, what
// friction takes, and the balance residual, per step and since the first
// step. Accounted by StepEnergy (energy.hpp); docs/time_integration.md
// says what each term is and how the residual reads.

namespace dda {

struct EnergyTerms {
  // Held (at the end of the step).
  double kinetic = 0;  // ½·vᵀMv per block, M = ρ∫TᵀT (strain rates included)
  double strain = 0;   // ½·A·σᵀE⁻¹σ per block
  double contact = 0;  // ½N²/k_n (+ ½S²/k_s locked) per closed contact
  // Work done on the blocks (negative: taken from them).
  double gravity = 0, point_loads = 0, pressure = 0, targets = 0, fixed_points = 0;
  double viscous = 0;            // VBC dashpots and the strains' damping (≤ 0: absorbed)
  double spring_boundaries = 0;  // SBC springs (≤ 0)
  double friction = 0;           // sliding contacts (≤ 0: dissipated)
  double impact = 0;             // the landing law's impacts (≤ 0 for e ≤ 1: what they took)
  // (held now − held before) − work: energy the time integrator (and the
  // contacts' state changes) made (> 0) or dissipated (< 0).
  double residual = 0;

  template <class Archive>
  void fields(Archive& ar) {
    ar(kinetic, strain, contact, gravity, point_loads, pressure, targets, fixed_points, viscous, spring_boundaries,
       friction, impact, residual);
  }

  double held() const { return kinetic + strain + contact; }
  double work() const {
    return gravity + point_loads + pressure + targets + fixed_points + viscous + spring_boundaries + friction + impact;
  }
};

// Every term by name (the Lua names: m:energy() and the monitor fields
// "energy_<name>"), in the order above, with what it is.
struct EnergyTermName {
  const char* name;
  double EnergyTerms::*term;
  const char* doc;
};
inline constexpr EnergyTermName kEnergyTerms[] = {
    {"kinetic", &EnergyTerms::kinetic, "kinetic energy held now, ½·vᵀMv per block (strain rates included)"},
    {"strain", &EnergyTerms::strain, "strain energy held now, ½·A·σᵀE⁻¹σ per block"},
    {"contact", &EnergyTerms::contact, "energy held now in the closed contacts' springs, ½N²/k_n (+ ½S²/k_s locked)"},
    {"gravity", &EnergyTerms::gravity, "work of gravity on the blocks"},
    {"point_loads", &EnergyTerms::point_loads, "work of the point loads"},
    {"pressure", &EnergyTerms::pressure, "work of the pressures on edges"},
    {"targets", &EnergyTerms::targets, "work of the prescribed motions (displacement targets)"},
    {"fixed_points", &EnergyTerms::fixed_points, "work of the fixed points' springs"},
    {"viscous", &EnergyTerms::viscous, "work of the viscous boundaries and the strains' damping (≤ 0: absorbed)"},
    {"spring_boundaries", &EnergyTerms::spring_boundaries, "work of the spring boundaries (≤ 0)"},
    {"friction", &EnergyTerms::friction, "work of friction at sliding contacts (≤ 0: dissipated)"},
    {"impact", &EnergyTerms::impact, "work of the landing law's impacts (≤ 0 for e ≤ 1)"},
    {"residual", &EnergyTerms::residual,
     "(held now − held at the start) − work: energy the time integrator and the contacts' state changes made "
     "(> 0) or dissipated (< 0)"},
};

struct EnergyBudget {
  EnergyTerms total;      // held now; work and residual since the first step
  EnergyTerms last_step;  // held now; the last step's work and residual
  bool started = false;   // held energy known (the first accounted step sets it)
  template <class Archive>
  void fields(Archive& ar) {
    ar(total, last_step, started);
  }
};

}  // namespace dda
