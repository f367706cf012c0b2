// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The step's linear solver: PCG (pcg.hpp) or the kept CHOLMOD factor
// (cholmod_solver.hpp), chosen once per step (SolverSettings::kind; Auto
// below).
//
// Auto decides from the work the run counted, in units of one PCG iteration
// (about one product A·x):
//
//   * PCG's work in a step: its CG iterations × kPcgIterationWork.
//   * The factor's work in a step: its CG iterations × (1 + the two
//     triangular solves) + its factorisations × the factorisation, from
//     CHOLMOD's own counts (nnz(L), flops) against the product's 72 flops per
//     stored block, each weighted by how fast this kind of flop runs
//     (kSolveFlopWeight, kFactorFlopWeight, kFactorEntryWeight,
//     kFactorProducts; fitted on walls 10 to 100, see below and
//     docs/direct_solver.md).
//
//   1. Steps start with PCG. After a PCG step whose solves took over
//      kToDirect CG iterations each (stiff systems: walls, slopes, long
//      dynamic steps; wave problems take 6–17), the next step tries the
//      factor: one trial step, with the factor of the PCG step's last
//      system, made as that step ends (end_step), so that the trial meets
//      what every step with a kept factor meets: the system moved on by a
//      step (under the holding law a settling wall's contacts change, and
//      the factor must be made again; under Shi's law on wall(100) the kept
//      factor serves for steps). That first factorisation is counted as spread
//      over kRetrySteps steps: it serves every step the factor is then kept,
//      and on large systems it would otherwise outweigh the trial
//      (wall(200)). Within the trial a new factorisation is made only while
//      the step's work stays within (1 + kTrialBudget) PCG steps; past it
//      the trial gives up and the step finishes on PCG.
//   2. The trial step is judged against the last PCG step that measured
//      PCG's work. The run's first step does not (it solves tightly in every
//      open-close iteration, solve_regime.hpp: two to three times the work
//      of the steps after it), so a trial right after it is followed by one
//      PCG step that measures, and judged then. Whichever is cheaper takes
//      the steps after. The trial comes second so that the steps a run is
//      judged by (and the bench's timed ones, from the third) start on the
//      cheaper solver: on a settling wall under the holding law the trial
//      shows a factorisation in every step (PCG wins), under Shi's law on
//      wall(100) almost none (the factor wins).
//   3. On the factor, each step's work goes into an average, compared with
//      the last PCG step's; where PCG was cheaper, steps go back to PCG. The
//      average is the plain mean of the first kMeanSteps steps (the trial's
//      included: a dynamic wall's second step, the trial, made one
//      factorisation where the steps after it made two), then exponential
//      (a settled wall's kept factor is made again every few steps, and one
//      such step must not send it back). When PCG takes over (a trial that
//      gave up or lost, a factor that lost), the factor is freed, and the
//      next trial comes after kRetrySteps PCG steps (doubled each time).
//   4. Each backend's step is solved in the regime of that backend's last
//      step (choose_backend reports its counts): the step back to PCG in the
//      long-solve regime of the PCG steps, not in the short one the factor's
//      few iterations would choose; the trial in the short one of a run on
//      the factor (as after no step: a step with the factor predicts the
//      contacts' states, and under the holding law that prediction is what
//      makes the kept factor stale; judged in the long regime, the trial
//      showed no factorisation where the steps after it made one each).
//
// The trial is made, not priced from CHOLMOD's symbolic analysis before its
// numeric factor (which would spare its memory, the factor's, on walls that
// then go back to PCG): the analysis prices the cheapest step the factor
// could make (one CG iteration, the factorisation spread as in rule 1) at 10
// to 34 PCG iterations on walls 10 to 200, far below any PCG step that calls
// for a trial, and the same analysis goes with a trial that loses (wall(200)
// under the holding law: the kept factor fails the next step) and one that
// wins (the same wall under Shi's law). What decides is whether the kept
// factor serves the next step, which only the trial shows.
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
  int end_step() override;
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
  static constexpr double kTrialBudget = 0.5;  // of a PCG step: what a trial may cost beyond PCG
  static constexpr int kRetrySteps = 50;       // PCG steps before the factor is tried again
  static constexpr int kMeanSteps = 3;         // steps on the factor averaged alike (rule 3)
  // The model's constants, fitted to the CPU time per step, within the step,
  // of walls 10, 20, 40 and 100 with each solver on one thread (the CG
  // iterations, factorisations and their time; docs/direct_solver.md). The
  // unit is a PCG iteration as the step runs it: a product and the CG's
  // vector passes, 1.1 to 1.9 products measured alone (the passes weigh most
  // where the product is smallest). A CG iteration with the factor cost 4.9,
  // 7.9, 16.5 and 17.7 PCG iterations (its two triangular solves read each
  // entry of L once: 1.7 product flops per flop); a numeric factorisation
  // 200-240, 340, 440 and 450, nowhere near its flop count (×16 from
  // wall(10) to wall(100)): its cost follows L's entries (the values scattered
  // into L, the supernodes' passes over it: kFactorEntryWeight each) plus a
  // part that follows the matrix (the values copied in, kFactorProducts), and
  // the dense kernels' flops run fast on the large supernodes (a tenth of a
  // product flop each).
  static constexpr double kPcgIterationWork = 1.0;   // a PCG iteration, the unit
  static constexpr double kSolveFlopWeight = 1.7;    // a triangular-solve flop in product flops
  static constexpr double kFactorFlopWeight = 0.1;   // a factorisation flop in product flops
  static constexpr double kFactorEntryWeight = 160;  // a factorisation's work per entry of L, in product flops
  static constexpr double kFactorProducts = 60;      // a factorisation's part that follows the matrix, in products

  // The cost model's figures for a factor of these sizes, in PCG iterations:
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
  void choose();
  // The factor's work in PCG iterations over `iterations` CG iterations and
  // `factorisations` (this step's counts by default); in a trial step its
  // first factorisation counts as spread over kRetrySteps steps.
  double direct_step_work(long iterations, int factorisations) const;
  double direct_step_work() const { return direct_step_work(iterations_, factorisations_); }
  void close_direct_step();
  void close_pcg_step();
  int start_trial();
  void give_up_trial();  // rule 1: the rest of the step, and the steps after, on PCG
  void wait_before_retrying();

  PcgSolver pcg_;
  std::unique_ptr<CholmodSolver> direct_;  // made on first use
  bool on_direct_ = false;
  // This step: its settings and what it knows of its solves (for a switch
  // to PCG within it), its operator, whether it is a trial step, and
  // whether that trial gave up in it (its counts then mix the two); whether
  // the step before it was solved with PCG alone.
  SolverSettings settings_;
  StepSolveInfo info_;
  const LinearOperator* a_ = nullptr;
  bool trial_step_ = false, gave_up_ = false, last_on_pcg_ = true;
  // This step's counts.
  int solves_ = 0, factorisations_ = 0;
  long iterations_ = 0;
  // The last PCG step: its work, and its counts for the solve regime and
  // the PCG's own preconditioner choice (StepSolveInfo); how many PCG steps
  // the run made (the first does not measure, rule 2), and whether this one
  // measures for a trial just made.
  double pcg_work_ = 0;
  int pcg_solves_ = 0;
  long pcg_iterations_ = 0;
  int pcg_steps_ = 0;
  bool measuring_ = false;
  // Steps with the factor since the switch (the trial's included), their
  // average work, and the last one's counts (for the solve regime).
  int direct_steps_ = 0;
  double direct_work_ = 0;
  int direct_solves_ = 0;
  long direct_iterations_ = 0;
  int retry_in_ = 0, retry_wait_ = kRetrySteps;
};

}  // namespace dda
