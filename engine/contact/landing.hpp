// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The landing law (control `restitution`, off by default; docs/landings.md):
// a contact that lands in a step ends it as a rigid-body impact with a
// coefficient of restitution e would end it, not as the penalty springs and
// the time step throw it.
//
// Why: a contact spring far stiffer than the step resolves (ωΔt ≫ 1) stops
// a landing block within the step, and Shi's v₁ = 2d/Δt − v₀ then maps the
// contact's approach velocity to about its opposite: a block dropped 3 m
// onto a rough face bounced with e ≈ 0.76 and was thrown back along the face
// at 1.42 m/s (Δt = 1e-3 s), numbers that change with Δt. Where the step
// resolves the springs (Δt = 1e-5 s), they are an elastic bounce (e ≈ 1).
//
// What: after the accepted solve (in Update only: a step cut and redone
// finds nothing changed), for the contacts that land in the step (open at
// its start, approaching then faster than landing_speed_threshold, and
// closed by the solve, or taken in by the step without the landing forces;
// a free block that another closed contact holds as well is confined, and
// its landings are left to the springs):
//   * the step without the landing contacts: their forces at the step's end
//     taken out of each block's own system (its elasticity, inertia and
//     loads), d_pre = d + K_own⁻¹·(N·Jnᵀ + S·Jtᵀ): the blocks' motion as if
//     nothing had landed, strains included (a landing force that stops a
//     block within one step strains it ∝ 1/Δt, an elastic bounce);
//   * the impact: from the gap and approach at the step's start and the
//     approach the step's other forces give, the time t* at which the
//     contact closes and its approach speed v_imp then (exact for a rigid
//     block under constant forces: independent of Δt);
//   * normal: the contact leaves with −e·v_imp and the other forces act for
//     the rest of the step, Δt − t* (a contact that would come back within
//     the step ends at rest on its face); the blocks end the step where
//     that motion puts them (at e = 0 touching, no penetration);
//   * tangential: the contact point stops (sticks) if the impact's impulse
//     stays within Coulomb's bound μ·(its normal impulse), which includes
//     the support of the rest of the step; else it slides with the impulse
//     at the bound;
//   * the correction of velocities and positions, Δv = M⁻¹Jᵀλ over the
//     blocks' rigid unknowns (u, v, r) with their rigid mass (m, m, I), held
//     blocks (fixed points, displacement targets) immovable: the least
//     change of kinetic energy that meets these targets, by projected
//     Gauss–Seidel over the landing contacts in the contact list's order,
//     serial: the same bits for any thread count;
//   * the landing contacts' springs end the step unloaded (normal and
//     shear), locked or sliding as the impact left them.
// Strain rates are left as the step without the landing made them: a
// first-order block's strain inertia (ρ∫(x − x₀)²) would take three
// quarters of a corner impulse of a 1 m × 0.5 m block and leave its centroid
// falling, an elastic bounce no rigid block has. Only under Shi's
// integrator (time_scheme.hpp, end_state_after_impact) and for first-order
// blocks: validate_landing_law.
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "block/time_scheme.hpp"
#include "contact/contact.hpp"
#include "contact/contact_detection.hpp"
#include "contact/contact_model.hpp"
#include "contact/penalty_contacts.hpp"

namespace dda {

// Throws dda::Error when the controls or the blocks rule the landing law out
// (restitution ≥ 0 under a second-order integrator, or with meshed blocks).
void validate_landing_law(double restitution, Integrator integrator, const Blocks& blocks);

// A contact lands when it approaches at the step's start faster than this:
// 2·|g|·max(Δt, t_ring), t_ring the contact's slowest ring: on its spring,
// 1/ω = √(m/k_n) (m its effective rigid mass), or in either of its blocks
// (held ones too), a wave's time across the block, √A/c = √(mass/E')
// (c² = E'/ρ). A block put down on a face (gravity switched on at once, or
// after a landing at e = 0) rings on its springs, in its strains and in
// the base's, its corners at up to about g·t_ring and lifting off by tenths
// of a micrometre: a 1 m × 0.5 m granite block on a 20 m base held at three
// points rattles at up to 1.8 cm/s at Δt = 1e-5 s, against g·t_ring =
// 3.0 cm/s through the base. An unresolved ring comes back within a step at
// up to gΔt. A landing slower than twice that is one the springs stop
// within a ring or two, with a bounce no larger than the ring itself.
double landing_speed_threshold(const Vec2& gravity, double dt, double ring_time);

class LandingLaw {
 public:
  // The landing law on the accepted step d (changed in place; the caller
  // moves the blocks with it): the number of contacts that landed. Does
  // nothing (and returns 0) when p.restitution < 0 (off). `iterates`: the
  // contacts' open-close iteration of the accepted solve;
  // `solved_friction_normal`: per contact, the friction normal force of
  // that solve (friction_normal of the N it used).
  int resolve(std::span<Contact> contacts, const ContactLinearisation& lin, std::span<ContactIterate> iterates,
              std::span<const double> solved_friction_normal, const ContactParameters& p, const ImpactInputs& in,
              VecX& d);
  const ImpactEnergy& energy() const { return energy_; }
  // After move_blocks: the impacted blocks' end-of-step state (velocity and
  // what Shi's scheme derives from it).
  void write_end_states(Blocks& blocks) const;
  // After the law kept its shear references: the landing contacts' shear
  // springs unloaded at their corrected end positions (a sliding one only
  // where the law keeps a reference for it: Shi's slides on from where it is).
  void unload_shear_springs(std::span<Contact> contacts, const ContactLinearisation& lin,
                            std::span<const ContactIterate> iterates, bool sliding_keeps_reference) const;

 private:
  struct Landing {
    int contact;
    double approach;            // its normal rate at the step's start (penetration per second)
    int va, vb;                 // slots of the vertex block and the edge block
    double w_n, w_t;            // J·M⁻¹·Jᵀ of the normal and the shear row (rigid unknowns)
    double target_rate;         // the normal rate (penetration per second) the step must end with
    double target_penetration;  // the penetration it must end with (≤ 0: a gap)
    double penetration;         // at the step's end without the landing contacts (d_pre)
    double p_n, p_t;            // accumulated normal and shear impulse of the impact (N·s/m)
    double mu;
  };
  struct Slot {
    BlockId block;
    bool held;
    IntegratedTt mass;
    Mat3 rigid_inverse;  // zero for a held block
    Vec6 force;          // the landing contacts' forces in the solve (generalised, on its unknowns)
    Vec6 d_pre, v_pre;   // the step's displacement and end velocity without the landing contacts
    Vec6 v;              // the end velocity after the impact
    Vec3 dd;             // displacement added (u, v, r)
    BlockEndState end;
  };
  int slot_of(BlockId b, const Blocks& blocks, const VecX& d, const TimeScheme& scheme, std::span<const char> held);
  void solve_velocities(const ContactLinearisation& lin);
  void solve_positions(const ContactLinearisation& lin);

  std::vector<Landing> candidates_, landings_;
  std::vector<Slot> slots_;
  std::vector<int> slot_index_;  // per block: its slot, -1 none
  std::vector<char> confined_;   // per block: a closed contact that does not land holds it
  ImpactEnergy energy_;
};

}  // namespace dda
