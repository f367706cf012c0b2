#pragma once
// The controls of a World: what a script sets with dda.model{...} and
// m:controls{...}. They may change between steps and are checked at the
// start of each step (validate_controls).
#include "core/material.hpp"
#include "core/types.hpp"
#include "solver/solver_settings.hpp"

namespace dda {

struct Controls {
  PlaneMode plane = PlaneMode::Stress;
  double g0 = 0;             // normal contact spring (N/m per unit thickness); 0 → 50 × largest E
  double shear_ratio = 0.4;  // shear spring = shear_ratio × g0 (Shi's 2/5)
  double g1 = 0;             // upper step time (s); 0 → estimate from Eqs. 1–3 (suggested_time_step)
  double g2 = 0.005;         // largest step displacement / half the model height
  double gg = 1;             // dynamic parameter: share of velocity carried into the next step
  int open_close_limit = 6;  // open-close iterations before Δt is cut and the step redone
  // Open-close hysteresis, as a fraction of half the model height: a closed
  // contact opens once separated by more than this, an open one closes once
  // penetrated by more; a locked contact slides once its shear force exceeds
  // its strength by the shear spring times this. Without it, contacts that
  // carry next to no force (the Poisson-loaded vertical joints of a wall)
  // flip state on round-off and the iteration never settles.
  double contact_tolerance = 1e-9;
  // Contact range (m): pairs closer than this at the start of a step are
  // contacts; a step in which a vertex moves more than range / 2.5 is cut.
  // 0 → automatic: starts at a tenth of the median edge length (fine models
  // then do not carry their blocks' second neighbours as contacts: wave
  // problems move micrometres a step) and widens, redoing the step, whenever
  // a vertex moves further, up to Shi's 2.5·g2·(half height).
  double contact_range = 0;
  double fixed_point_factor = 100;  // fixed-point spring = factor × g0
  Vec2 gravity = Vec2::Zero();      // m/s²
  double cut_factor = 1.0 / 3.0;    // Δt multiplier when a step is redone
  int max_step_cuts = 20;           // cuts in one step before giving up (error)
  double cg_tolerance = 1e-10;      // PCG relative residual of the accepted solution
  // PCG relative residual while contact states still change, in steps after
  // one whose solves took over 30 iterations (the final solve of a step is
  // always tightened to the accepted tolerance: cg_tolerance, or in static
  // analysis cg_static_tolerance); = cg_tolerance: off.
  double cg_open_close_tolerance = 1e-4;
  // PCG relative residual of the accepted solution in static analysis (gg = 0:
  // no velocity carried into the next step) in steps after long solves (over
  // 30 CG iterations per solve: walls); the larger of it and cg_tolerance
  // applies. Such a step's friction already carries the error of its loose
  // open-close solves (the normal force of a solve good to
  // cg_open_close_tolerance), and with gg = 0 a displacement error is not
  // carried on as a velocity, so solving the last pass past 1e-6 changes the
  // answer less than the loose solves do: wall(20) over 300 steps, 1e-6 and
  // 1e-10 agree to 1.7e-11 m and both end 7.5e-8 m (of 8.4e-4 m settled)
  // from the scheme's limit (every solve at 1e-12 or tighter), and wall(40)
  // takes 294 against 486 CG iterations per step (40 against 64 ms). Where
  // contacts slide and steps are cut (wall(10), gravity tilted 22°, 200
  // steps), 1e-10, 1e-8 and 1e-6 end 4.7e-6, 1.1e-6 and 1.2e-6 m from the
  // limit (of 3.2e-4 m): there the loose solves decide which contacts change
  // state in which step. Dynamic analysis (gg > 0) keeps cg_tolerance:
  // a wall(6) with gg = 1 moved 3e-5 of its settlement at 1e-6, against
  // 2e-6 at 1e-10. = cg_tolerance: off.
  double cg_static_tolerance = 1e-6;
  // Start each step's open-close iteration from the contact states the warm
  // start predicts (closing and friction transitions only), not from the last
  // step's: fewer iterations in wave problems (blast(2): 2.95 → 2.08 per
  // step; not done after long solves, whose warm start predicts nothing).
  // The answer is another consistent set of states, not the same bits.
  bool predict_states = true;
  // The linear solver's own knobs (solver/solver_settings.hpp): the PCG's
  // preconditioner, block-Jacobi refresh tolerance and re-solve patches.
  SolverSettings solver;
  int cg_max_iterations = 0;  // 0 → 10 × unknowns + 100
  int threads = 0;            // 0 → every core
};

// Throws dda::Error naming the first control out of its range.
void validate_controls(const Controls& c);

}  // namespace dda
