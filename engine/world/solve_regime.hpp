// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// How a step solves, chosen once per step before its first solve: the
// policy that decides everything the step does differently where solves are
// short (wave problems: the blocks' inertia dominates their springs, a few
// CG iterations per solve) and where they are long (quasi-static walls:
// contacts and elasticity dominate, hundreds). Which regime a step is in is
// read off the last step solved with the backend this step uses
// (LinearSolver::choose_backend: after the factor, the last PCG step): over
// kLongSolveIterations CG iterations per solve is long. The count is the same
// for any thread count, so the choice keeps results independent of the
// threads. A solver that takes one iteration per solve (a direct
// factorisation) is in the short regime after its first step, where the warm
// start and state prediction still pay.
//
//                        short solves                 long solves
//   warm start           the last step's motion       the last step's
//                        extrapolated (blast(2):      displacement (extrapolating
//                        10 % fewer CG iterations)    raised the walls' CG count)
//   predicted states     Controls::predict_states     no (the warm start predicts
//                                                     nothing)
//   open-close solves    cg_tolerance every time      cg_open_close_tolerance while
//                                                     states change, then tightened
//   accepted tolerance   cg_tolerance                 cg_tolerance; static analysis
//                                                     (gg = 0): the larger of it and
//                                                     cg_static_tolerance
//   system product       matrix-free contact springs  stored 6×6 blocks (the mat-vec
//                                                     dominates)
//   local re-solves      yes (PCG patches)            no (a local change reaches far)
#include "solver/linear_solver.hpp"
#include "world/controls.hpp"

namespace dda {

struct SolveRegime {
  enum class Kind { ShortSolves, LongSolves };
  Kind kind = Kind::ShortSolves;
  const char* name() const { return kind == Kind::LongSolves ? "long" : "short"; }  // StepStats::solve_regime
  bool extrapolate_warm_start = true;
  bool predict_states = true;
  double open_close_tolerance = 0;  // of the solves while contact states still change
  double accept_tolerance = 0;      // of the solve whose states hold
  bool stored_products = false;     // multiply with stored 6×6 blocks (ContactOperator::store_products)
  bool local_resolves = true;       // the solver may re-solve locally after a local change

  static constexpr double kLongSolveIterations = 30;  // CG iterations per solve in the last step

  // The regime of the step the solver chose its backend for (`solves`:
  // LinearSolver::choose_backend's; no solves yet, before the first step:
  // short solves).
  static SolveRegime choose(const Controls& controls, const StepSolveInfo& solves);
};

}  // namespace dda
