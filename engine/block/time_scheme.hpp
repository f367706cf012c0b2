#pragma once
// How a block's inertia and end-of-step velocity follow from its step
// displacement d: Shi's scheme (Newmark β = ½, γ = 1), with the dynamic
// parameter gg, the share of the last velocity carried into the step:
//
//   v0 = gg·v_last,   d = v0·Δt + a·Δt²/2,   v1 = 2d/Δt − v0
//
// (exact for constant acceleration). The inertia force −ρ∫TᵀT a dA then
// adds (2ρ/Δt²)∫TᵀT to the block's diagonal and (2ρ/Δt)∫TᵀT·v0 to its
// right-hand side. Everything in the step that depends on the time
// integration asks this struct: the inertia terms (assembly), viscous
// boundaries' dashpots (boundary), the warm start (the solve regime) and
// the velocity update (Update). A second-order scheme (Newmark average
// acceleration, generalized-α) replaces these five formulas; if it keeps
// state of its own (an acceleration per block), that state is written only
// in Update, so a step redone with a smaller Δt finds it as it was.
#include "core/types.hpp"

namespace dda {

struct TimeScheme {
  double dt = 0;
  double gg = 1;

  // Inertia of a block of density rho, ∫TᵀT = tt, last velocity v_last.
  void add_inertia(double rho, const Mat6& tt, const Vec6& v_last, Mat6& k, Vec6& f) const {
    k += (2 * rho / (dt * dt)) * tt;
    f += (2 * rho / dt) * (tt * (gg * v_last));
  }
  // v1 = velocity_factor()·d − carried_velocity(v_last): what a dashpot acts on.
  double velocity_factor() const { return 2.0 / dt; }
  Vec6 carried_velocity(const Vec6& v_last) const { return gg * v_last; }
  Vec6 end_velocity(const Vec6& d, const Vec6& v_last) const { return 2.0 / dt * d - gg * v_last; }
  // The displacement the last step's motion extrapolates to (its acceleration
  // held): (1 + gg)·v·Δt − d_last, with v = 2·d_last/Δt − gg·v_before.
  Vec6 extrapolated_displacement(const Vec6& v_last, const Vec6& d_last) const {
    return (1 + gg) * dt * v_last - d_last;
  }
};

}  // namespace dda
