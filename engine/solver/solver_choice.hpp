// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The step's linear solver: PCG (pcg.hpp) or the kept CHOLMOD factor
// (cholmod_solver.hpp), chosen once per step (SolverSettings::kind; Auto
// below).
//
// Auto decides from the work the run counted, in units of one product A·x:
//
//   * PCG's work in a step: its CG iterations × kPcgIterationWork.
//   * The factor's work in a step: its CG iterations × (1 + the two
//     triangular solves) + its factorisations × the factorisation, from
//     CHOLMOD's own counts (nnz(L), flops) against the product's 72 flops per
//     stored block, each weighted by how fast this kind of flop runs
//     (kSolveFlopWeight, kFactorFlopWeight, kFactorProducts; fitted on
//     walls 20 to 100, see below and docs/direct_solver.md).
//
//   1. Steps start with PCG. After kLongStepsBeforeTrial steps in a row whose
//      solves took over kToDirect CG iterations each (stiff systems: walls,
//      slopes, long dynamic steps; wave problems take 6–17), the next step
//      tries the factor. (Not after one: the first step solves tightly in
//      every open-close iteration, solve_regime.hpp, and its PCG work is not
//      that of the steps after it, which the factor is judged against.)
//   2. The trial lasts kTrialSteps steps, over which the factor's work per
//      step is summed against the last PCG step's. It gives up, and the step
//      finishes on PCG, as soon as a new factorisation would take that sum
//      past kTrialBudget of a PCG step: where the contacts' states change in
//      every step (a settling wall under the holding law) the factor must be
//      made again each step, and a trial that ran its steps cost two
//      factorisations a step at twice PCG's work. A trial that ends with the
//      factor no dearer than PCG keeps it.
//   3. After the trial, each step's work with the factor goes into an
//      exponential average (from the trial's mean), compared with the last
//      PCG step's; where PCG was cheaper, steps go back to PCG. A trial that
//      gave up or lost is tried again only after kRetrySteps steps (doubled
//      after each). The trial's first factorisation is counted as spread
//      over kRetrySteps steps: it serves every step the factor is then kept,
//      and on large systems it would otherwise outweigh the trial
//      (wall(200)).
//   4. The step back to PCG reports the last PCG step's counts
//      (choose_backend), so it is solved in the long-solve regime of the PCG
//      steps, not in the short one the factor's few iterations would choose.
//
// Counts, not seconds: seconds depend on the machine's load, and the choice
// changes the answer within the solver tolerance, so a choice from timings
// would make results differ from run to run. Iteration counts and CHOLMOD's
// sizes are the same for any thread count and any run.
#include <memory>

#include "solver/cholmod_solver.hpp"
#include "solver/pcg.hpp"

namespace dda {

class AutoSolver final : public LinearSolver {
 public:
  AutoSolver();
  StepSolveInfo choose_backend(const SolverSettings& settings, const StepSolveInfo& info) override;
  void begin_step(const SolverSettings& settings, const StepSolveInfo& info) override;
  void set_operator(const LinearOperator& a) override;
  SolveReport solve(const VecX& b, VecX& x) override { return solve_from(b, x, {}); }
  SolveReport resolve(const VecX& b, VecX& x, std::span<const char> changed_rows) override {
    return solve_from(b, x, changed_rows);
  }
  const char* name() const override { return on_direct_ ? "cholmod" : "pcg"; }
  // Checkpoints: the choice, the counts it is made from, and both solvers'
  // kept state (PCG's preconditioner, the factor).
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;

  static constexpr double kToDirect = 30;      // PCG iterations per solve
  static constexpr int kDirectMinBlocks = 64;  // smaller systems stay with PCG
  static constexpr int kLongStepsBeforeTrial = 2;
  static constexpr int kTrialSteps = 3;        // before the factor's work is judged
  static constexpr double kTrialBudget = 0.5;  // of a PCG step: what a trial may cost beyond PCG
  static constexpr int kRetrySteps = 50;       // PCG steps before the factor is tried again
  // The model's constants, fitted to the CPU time per step of wall(20),
  // wall(40) and wall(100) with each solver on one thread (12 steps each,
  // quasi-static and dynamic, both contact laws; docs/direct_solver.md): a PCG
  // iteration costs about one product (the stored product dominates it); a
  // CG iteration with the factor 14, 19 and 23 PCG iterations, its two
  // triangular solves reading each entry of L once (2.8 product flops per
  // flop); a numeric factorisation 290, 290 and 380 of them, far from its
  // flop count (×6 from wall(20) to wall(100)): the values copied in, the
  // small supernodes and the stored matrix assembled for it cost in
  // proportion to the matrix (kFactorProducts), the dense kernels by their
  // flops (a quarter of a product flop each).
  static constexpr double kPcgIterationWork = 1.0;   // a PCG iteration in products A·x
  static constexpr double kSolveFlopWeight = 2.8;    // a triangular-solve flop in product flops
  static constexpr double kFactorFlopWeight = 0.25;  // a factorisation flop in product flops
  static constexpr double kFactorProducts = 200;     // a factorisation's cost besides its flops, in products

  // The cost model's figures for a factor of these sizes, in products A·x:
  // a solve with it (its two triangular solves), and a numeric
  // factorisation with the stored matrix assembled for it. A CG iteration
  // with the factor costs 1 + solve.
  struct FactorCosts {
    double solve = 0, factorisation = 0;
  };
  static FactorCosts factor_costs(const CholmodFactor& f);

 private:
  LinearSolver& current() { return on_direct_ ? static_cast<LinearSolver&>(*direct_) : pcg_; }
  SolveReport solve_from(const VecX& b, VecX& x, std::span<const char> changed_rows);
  void choose(const StepSolveInfo& info);
  // The factor's work in products over `iterations` CG iterations and
  // `factorisations` (this step's counts by default); in a trial's first
  // step its first factorisation counts as spread over kRetrySteps steps.
  double direct_step_work(long iterations, int factorisations) const;
  double direct_step_work() const { return direct_step_work(iterations_, factorisations_); }
  void give_up_trial();  // rule 2: the rest of the step, and the steps after, on PCG

  PcgSolver pcg_;
  std::unique_ptr<CholmodSolver> direct_;  // made on first use
  bool on_direct_ = false;
  // This step: its settings and what it knows of its solves (for a switch
  // to PCG within it), its operator, whether it is a trial's first step,
  // and whether that trial gave up in it (its counts then mix the two).
  SolverSettings settings_;
  StepSolveInfo info_;
  const LinearOperator* a_ = nullptr;
  bool trial_step_ = false, gave_up_ = false;
  // This step's counts.
  int solves_ = 0, factorisations_ = 0;
  long iterations_ = 0;
  // The last PCG step: its work, and its counts for the solve regime and
  // the PCG's own preconditioner choice (StepSolveInfo).
  double pcg_work_ = 0;
  int pcg_solves_ = 0;
  long pcg_iterations_ = 0;
  // Steps with the factor since the switch, and their average work; in the
  // trial, the sum of its steps' work less PCG's.
  int direct_steps_ = 0;
  double direct_work_ = 0, trial_excess_ = 0;
  int retry_in_ = 0, retry_wait_ = kRetrySteps;
  int long_pcg_steps_ = 0;  // PCG steps in a row over kToDirect iterations per solve
};

}  // namespace dda
