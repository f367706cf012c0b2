// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// How a block's inertia, dashpot velocity, warm start and end-of-step motion
// follow from its step displacement d: the one place that knows the time
// integrator (docs/time_integration.md has the equations in
// DDA's notation beside Newmark's).
//
// Every scheme is a member of the generalized-α family (Chung & Hulbert
// 1993) written for DDA's unknown, the step displacement d = u₁ − u₀:
//
//   a₁ = (d − Δt·v₀ − Δt²(½ − β)·a₀) / (βΔt²)
//   v₁ = v₀ + Δt[(1 − γ)·a₀ + γ·a₁]
//   M[(1 − αm)·a₁ + αm·a₀] = (1 − αf)·R₁ + αf·R₀
//
// R is the generalised force not balanced by the springs, dashpots and
// stresses (loads at t + Δt, contacts, boundaries, elasticity: everything
// the step assembles besides inertia). Divided by (1 − αf), the step keeps
// DDA's system with R₁ at t + Δt and only the inertia terms change:
//
//   K += c_m·M,  c_m = (1 − αm) / ((1 − αf)·β·Δt²)
//   F += M·[(1 − αm)/(βΔt)·v₀ + ((1 − αm)(½ − β)/β − αm)·a₀] / (1 − αf)
//        + αf/(1 − αf)·R₀
//
// with M = ρ∫TᵀT dA, the block's consistent mass (an element of a meshed
// block: as mesh_mass says, MeshMass below). The schemes:
//   shi:                β = ½, γ = 1, αm = αf = 0: v₁ = 2d/Δt − v₀, first
//                       order, dissipative (exact for constant acceleration);
//                       computed with Shi's own formulas, bit for bit;
//   newmark:            β = ¼, γ = ½, αm = αf = 0 (average acceleration):
//                       second order, no dissipation;
//   generalized_alpha:  αm = (2ρ∞ − 1)/(ρ∞ + 1), αf = ρ∞/(ρ∞ + 1),
//                       γ = ½ − αm + αf, β = ¼(1 − αm + αf)²: second order,
//                       spectral radius ρ∞ at high frequency.
// The dynamic parameter gg scales the state carried into the step (v₀, a₀,
// R₀) for every scheme: 1 dynamic, 0 static.
//
// State: the velocity v, the acceleration a and the unbalanced force R of
// each block at the end of the last step (Blocks::velocity, acceleration,
// out_of_balance). It is written only in Update (end_state), so a step
// redone with a smaller Δt finds it as it was; a and R are quantities at a
// time t, not per step, so a change of Δt (a cut, regrowth) leaves them
// consistent. Shi's scheme writes them too (the step's mean acceleration),
// so a model may switch schemes between steps.
#include "block/displacement.hpp"
#include "core/symmetric6.hpp"
#include "core/types.hpp"

namespace dda {

// Auto (the controls' default) is resolved before a step: the wave scheme
// where the wave model is active, else Shi (world/wave_model.hpp).
enum class Integrator { Shi, Newmark, GeneralizedAlpha, Auto };

// The mass of an element of a meshed block (block/mesh.hpp), the control
// mesh_mass; first-order blocks always have their consistent mass. An
// element's unknowns are its three nodes' displacements (D_e = A_e·u_e), so
// a mass over the nodes, M_u, is M_D = A_e⁻ᵀ·M_u·A_e⁻¹ in DDA's
// unknowns, A_e⁻¹ = [T(p1); T(p2); T(p3)]:
//   Consistent: ρ∫TᵀT dA, the exact integral (the CST's consistent mass);
//   Lumped:     ρ·(A/3)·Σ T(pᵢ)ᵀT(pᵢ), a third of the element's mass at each
//               corner (the diagonal, row-sum mass over the nodes). About the
//               element's centroid (ΣXᵢ = 0) that is ∫TᵀT with the second
//               moments ∫X², ∫Y², ∫XY four times the exact ones (a triangle's
//               ∫X² = (A/12)·ΣXᵢ²): the same mass and centre of mass, so
//               translation is exact; the element's own turning and
//               straining inertia ×4;
//   Mixed:      the mean of the two (second moments × 2.5), which cancels the
//               leading dispersion error of linear elements in 1-D (the
//               consistent mass's short waves run faster than c, the lumped
//               one's slower). docs/meshed_blocks.md has what each does.
//   Auto (the controls' default), resolved before a step: the wave scheme's
//               where the wave model is active, else Consistent
//               (world/wave_model.hpp).
enum class MeshMass { Consistent, Lumped, Mixed, Auto };

// The factor on an element's second moments in its ∫TᵀT (above).
inline double element_moment_factor(MeshMass m) {
  return m == MeshMass::Lumped ? 4.0 : m == MeshMass::Mixed ? 2.5 : 1.0;
}

// One block's state at the start of the step (before gg).
struct BlockState {
  const Vec6& velocity;
  const Vec6& acceleration;
  const Vec6& out_of_balance;
};

// One block's state at the end of the step.
struct BlockEndState {
  Vec6 velocity, acceleration, out_of_balance;
};

struct TimeScheme {
  double dt = 0;
  double gg = 1;
  Integrator integrator = Integrator::Shi;
  double beta = 0.5, gamma = 1, alpha_m = 0, alpha_f = 0;
  MeshMass mesh_mass = MeshMass::Consistent;  // the elements' mass (block_tt, blocks.hpp)

  // The scheme's parameters; rho_inf only for generalized-α.
  void choose(Integrator kind, double rho_inf) {
    integrator = kind;
    alpha_m = alpha_f = 0;
    if (kind == Integrator::Shi) {
      beta = 0.5, gamma = 1;
    } else if (kind == Integrator::Newmark) {
      beta = 0.25, gamma = 0.5;
    } else {
      alpha_m = (2 * rho_inf - 1) / (rho_inf + 1);
      alpha_f = rho_inf / (rho_inf + 1);
      gamma = 0.5 - alpha_m + alpha_f;
      beta = 0.25 * (1 - alpha_m + alpha_f) * (1 - alpha_m + alpha_f);
    }
  }
  bool is_shi() const { return integrator == Integrator::Shi; }

  // The mass coefficient c_m: the inertia adds c_m·M to the block's diagonal.
  double mass_factor() const { return is_shi() ? 2 / (dt * dt) : (1 - alpha_m) / ((1 - alpha_f) * beta * dt * dt); }

  // Inertia of a block of density rho, ∫TᵀT = tt.
  void add_inertia(double rho, const IntegratedTt& tt, const BlockState& s, Symmetric6& k, Vec6& f) const {
    if (is_shi()) {
      tt.add_scaled_to(2 * rho / (dt * dt), k);
      f += tt.scaled(2 * rho / dt) * (gg * s.velocity);
      return;
    }
    tt.add_scaled_to(rho * mass_factor(), k);
    const Vec6 carried =
        ((1 - alpha_m) / (beta * dt)) * s.velocity + ((1 - alpha_m) * (0.5 - beta) / beta - alpha_m) * s.acceleration;
    f += tt.scaled(gg * rho / (1 - alpha_f)) * carried + (gg * alpha_f / (1 - alpha_f)) * s.out_of_balance;
  }

  // v₁ = velocity_factor()·d − carried_velocity(s): what a dashpot acts on.
  double velocity_factor() const { return is_shi() ? 2.0 / dt : gamma / (beta * dt); }
  Vec6 carried_velocity(const BlockState& s) const {
    if (is_shi()) return gg * s.velocity;
    return gg * ((gamma / beta - 1) * s.velocity + (dt * (gamma / (2 * beta) - 1)) * s.acceleration);
  }
  Vec6 end_velocity(const Vec6& d, const BlockState& s) const {
    if (is_shi()) return 2.0 / dt * d - gg * s.velocity;
    return velocity_factor() * d - carried_velocity(s);
  }

  // The state at the end of the step under displacement d; mass = ρ∫TᵀT as
  // in the step's system.
  BlockEndState end_state(const Vec6& d, const BlockState& s, const IntegratedTt& mass) const {
    BlockEndState e;
    e.velocity = end_velocity(d, s);
    if (is_shi()) {
      // The step's constant acceleration, and the force that drove it.
      e.acceleration = (e.velocity - gg * s.velocity) / dt;
      e.out_of_balance = mass * e.acceleration;
      return e;
    }
    const Vec6 v0 = gg * s.velocity, a0 = gg * s.acceleration;
    e.acceleration = (d - dt * v0 - (dt * dt * (0.5 - beta)) * a0) / (beta * dt * dt);
    e.out_of_balance =
        (mass * Vec6((1 - alpha_m) * e.acceleration + alpha_m * a0) - (gg * alpha_f) * s.out_of_balance) /
        (1 - alpha_f);
    return e;
  }

  // The state at the end of the step when the landing law (an impact,
  // contact/landing.hpp) replaced the velocity end_state would give by v1:
  // Shi's scheme only, whose one state is the velocity (the step's constant
  // acceleration and its force follow from v1 as in end_state). The
  // second-order schemes' acceleration follows from d, and an impact that
  // changes v1 but not d would break a₁ = (d − Δt·v₀ − …)/(βΔt²): the
  // landing law refuses them.
  BlockEndState end_state_after_impact(const Vec6& v1, const BlockState& s, const IntegratedTt& mass) const {
    BlockEndState e;
    e.velocity = v1;
    e.acceleration = (v1 - gg * s.velocity) / dt;
    e.out_of_balance = mass * e.acceleration;
    return e;
  }

  // The warm start: the displacement the last step's motion extrapolates to.
  // Shi: its acceleration held, a = (v·Δt_last − d_last)·2/Δt_last² (with
  // v = 2·d_last/Δt_last − gg·v_before), so gg·v·Δt + a·Δt²/2; at
  // Δt = Δt_last that is (1 + gg)·v·Δt − d_last, which a step after a cut or a
  // growth of Δt must not take: after a cut by 3 it points up the slope a
  // block slides down. The others: v·Δt + a·Δt²/2.
  Vec6 extrapolated_displacement(const BlockState& s, const Vec6& d_last, double dt_last) const {
    if (is_shi()) {
      if (dt_last == dt) return (1 + gg) * dt * s.velocity - d_last;
      const double r = dt / dt_last;
      return gg * dt * s.velocity + (r * r) * (dt_last * s.velocity - d_last);
    }
    return gg * (dt * s.velocity + (0.5 * dt * dt) * s.acceleration);
  }
};

}  // namespace dda
