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
//     (kSolveFlopWeight, kFactorFlopWeight; calibrated on wall(40), see
//     docs/performance.md).
//
//   1. Steps start with PCG. After kLongStepsBeforeTrial steps in a row whose
//      solves took over kToDirect CG iterations each (stiff systems: walls,
//      slopes, long dynamic steps; wave problems take 6–17), the next steps
//      use the factor. (Not after one: the first step solves tightly in every
//      open-close iteration, solve_regime.hpp, and its PCG work is not that
//      of the steps after it, which the factor is judged against.)
//   2. After kTrialSteps steps with the factor, and on each step after, its
//      average work per step (the trial's mean, then an exponential average)
//      is compared with the last PCG step's; where PCG was cheaper, steps go
//      back to PCG and the factor is tried again only after kRetrySteps steps
//      (doubled after each failed trial). The trial's first factorisation is
//      counted as spread over kRetrySteps steps: it serves every step the
//      factor is kept, and on large systems it would otherwise outweigh the
//      trial (wall(200)).
//   3. The step back to PCG reports the last PCG step's counts
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
  void set_operator(const LinearOperator& a) override { current().set_operator(a); }
  SolveReport solve(const VecX& b, VecX& x) override;
  SolveReport resolve(const VecX& b, VecX& x, std::span<const char> changed_rows) override;
  const char* name() const override { return on_direct_ ? "cholmod" : "pcg"; }
  // Checkpoints: the choice, the counts it is made from, and both solvers'
  // kept state (PCG's preconditioner, the factor).
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;

  static constexpr double kToDirect = 30;      // PCG iterations per solve
  static constexpr int kDirectMinBlocks = 64;  // smaller systems stay with PCG
  static constexpr int kLongStepsBeforeTrial = 2;
  static constexpr int kTrialSteps = 4;             // before the factor's work is judged
  static constexpr int kRetrySteps = 50;            // PCG steps before the factor is tried again
  static constexpr double kPcgIterationWork = 1.6;  // a PCG iteration in products A·x
  // CPU time per flop against the product's (bench_engine --solver-only,
  // wall(20) and wall(40) on one thread): the triangular solves read each
  // entry of L once and run at 2–5 GFlop/s (out of cache on wall(40)), the
  // product at 11–12 and the factorisation (dense kernels) at 8–13. With
  // these the model's factor/PCG work per step is 0.91 on wall(20) and 1.2
  // on wall(40) (quasi-static), where the CPU seconds measured side by side
  // gave 0.84 and 1.12–1.28.
  static constexpr double kSolveFlopWeight = 5.0;   // a triangular-solve flop in product flops
  static constexpr double kFactorFlopWeight = 1.0;  // a factorisation flop in product flops

 private:
  LinearSolver& current() { return on_direct_ ? static_cast<LinearSolver&>(*direct_) : pcg_; }
  SolveReport counted(const SolveReport& r);
  void choose(const StepSolveInfo& info);
  double direct_step_work() const;    // of this step's counts, in products
  double factorisation_work() const;  // one numeric factorisation, in products

  PcgSolver pcg_;
  std::unique_ptr<CholmodSolver> direct_;  // made on first use
  bool on_direct_ = false;
  // This step's counts.
  int solves_ = 0, factorisations_ = 0;
  long iterations_ = 0;
  // The last PCG step: its work, and its counts for the solve regime and
  // the PCG's own preconditioner choice (StepSolveInfo).
  double pcg_work_ = 0;
  int pcg_solves_ = 0;
  long pcg_iterations_ = 0;
  // Steps with the factor since the switch, and their average work.
  int direct_steps_ = 0;
  double direct_work_ = 0;
  int retry_in_ = 0, retry_wait_ = kRetrySteps;
  int long_pcg_steps_ = 0;  // PCG steps in a row over kToDirect iterations per solve
};

}  // namespace dda
