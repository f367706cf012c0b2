// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Which preconditioner the PCG uses, decided once per step
// (PcgSolver::begin_step).
//
// Auto is adaptive and deterministic: it looks only at iteration counts of
// earlier steps, which are the same for any thread count (PCG's reductions
// are fixed-order), so the choice — and with it every result bit — does not
// depend on the threads either.
//
//   * Small models (fewer than kMultigridMinBlocks blocks) and the first
//     step: block-Jacobi.
//   * Block-Jacobi whose last step needed more than kToMultigrid (1000) CG
//     iterations per solve (contacts and elasticity dominate the inertia:
//     quasi-static walls, slopes): multigrid from the next step on.
//   * Multigrid whose last step needed fewer than kToBlockJacobi (30) iterations
//     per solve (inertia dominates again, e.g. after Δt was cut): back to
//     block-Jacobi. The gap between the two thresholds (multigrid takes
//     about 4–5 times fewer iterations than block-Jacobi on walls) keeps the
//     choice from flip-flopping.
#include <memory>
#include <optional>

#include "solver/linear_solver.hpp"
#include "solver/solver_settings.hpp"

namespace dda {

// Facts about the system that decide Preconditioning::Auto.
struct SystemTraits {
  SystemTraits() = default;
  explicit SystemTraits(int blocks_) : blocks(blocks_) {}

  int blocks = 0;
  // The last solved step: the preconditioner it used and its CG iterations
  // per solve (StepStats::cg_iterations / open_close_iterations). Empty
  // before the first step.
  std::optional<Preconditioning> last_kind;
  double last_cg_per_solve = 0;
};

inline constexpr int kMultigridMinBlocks = 64;
// From measurements (callgrind, wall(10/20)): a multigrid PCG iteration costs
// about 4 block-Jacobi ones, and multigrid needs 4–6 times fewer iterations
// where block-Jacobi needs 300–600 per solve. Since open-close iterations
// solve loosely (Controls::cg_open_close_tolerance), block-Jacobi needs ~130
// per solve on wall(40) and multigrid only 2.6 times fewer at 4.8 times the
// cost (12 steps: 4.9 s against 9.1 s), so multigrid is kept for solves that
// block-Jacobi takes over a thousand iterations for.
inline constexpr double kToMultigrid = 1000;  // block-Jacobi CG iterations per solve
inline constexpr double kToBlockJacobi = 30;  // multigrid CG iterations per solve

// The kind to use for these traits (Auto resolved; others returned as given).
Preconditioning choose_preconditioning(Preconditioning requested, const SystemTraits& traits);
std::unique_ptr<Preconditioner> make_preconditioner(Preconditioning kind);

}  // namespace dda
