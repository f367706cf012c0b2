#include "solver/solver_choice.hpp"

#include <climits>
#include <cmath>

#include "core/archive.hpp"
#include "core/load_check.hpp"

namespace dda {

AutoSolver::AutoSolver() = default;

void AutoSolver::save_state(ArchiveWriter& ar) const {
  ar(on_direct_, solves_, factorisations_, iterations_, pcg_work_, pcg_solves_, pcg_iterations_, direct_steps_,
     direct_work_, retry_in_, retry_wait_, long_pcg_steps_);
  pcg_.save_state(ar);
  const bool has_direct = direct_ != nullptr;
  ar(has_direct);
  if (has_direct) direct_->save_state(ar);
}

void AutoSolver::load_state(ArchiveReader& ar) {
  ar(on_direct_, solves_, factorisations_, iterations_, pcg_work_, pcg_solves_, pcg_iterations_, direct_steps_,
     direct_work_, retry_in_, retry_wait_, long_pcg_steps_);
  pcg_.load_state(ar);
  bool has_direct = false;
  ar(has_direct);
  direct_.reset();
  if (has_direct) {
    direct_ = std::make_unique<CholmodSolver>();
    direct_->load_state(ar);
  }
  // The counts feed sums and a doubling wait; on the factor, the factor is there.
  const LoadCheck check(ar.what());
  constexpr long long kMaxCount = 1LL << 40;
  const long long counts[] = {solves_,       factorisations_, iterations_, pcg_solves_,    pcg_iterations_,
                              direct_steps_, retry_in_,       retry_wait_, long_pcg_steps_};
  for (const long long n : counts) check.require(n >= 0 && n < kMaxCount, "its solver counts hold ", n);
  check.require(std::isfinite(pcg_work_) && std::isfinite(direct_work_), "its solver's work figures are not finite");
  check.require(!on_direct_ || direct_, "its solver is on a CHOLMOD factor it does not hold");
}

StepSolveInfo AutoSolver::choose_backend(const SolverSettings& settings, const StepSolveInfo& info) {
  const bool last_on_pcg = !on_direct_;
  choose(info);
  if (settings.kind != SolverKind::Auto) on_direct_ = settings.kind == SolverKind::Cholmod;
  solves_ = factorisations_ = 0;
  iterations_ = 0;
  // Back on PCG after the factor: the last PCG step's counts, for the solve
  // regime and the PCG's preconditioner. (The factor's first step keeps the
  // last PCG step's: it has none of its own.)
  StepSolveInfo own = info;
  if (!on_direct_ && !last_on_pcg) {
    own.last_step_solves = pcg_solves_;
    own.last_step_iterations = pcg_iterations_;
  }
  return own;
}

void AutoSolver::begin_step(const SolverSettings& settings, const StepSolveInfo& info) {
  if (on_direct_) {
    if (!direct_) direct_ = std::make_unique<CholmodSolver>();
    direct_->begin_step(settings, info);
    return;
  }
  pcg_.begin_step(settings, info);
}

// Closes the books on the step just done (its counts) and picks the backend
// of the next one (the header's rules 1 and 2).
void AutoSolver::choose(const StepSolveInfo& info) {
  if (solves_ == 0) return;  // no step yet
  if (on_direct_) {
    double work = direct_step_work();
    // The trial's first factorisation serves every step the factor is then
    // kept: counted as spread over kRetrySteps steps, not over the trial's
    // kTrialSteps (wall(200): a factorisation of 80,000 blocks outweighed
    // four PCG steps, and PCG was kept at 5 times the factor's cost per step).
    if (direct_steps_ == 0 && factorisations_ > 0)
      work -= (1 - static_cast<double>(kTrialSteps) / kRetrySteps) * factorisation_work();
    ++direct_steps_;
    direct_work_ = direct_steps_ <= kTrialSteps ? direct_work_ + (work - direct_work_) / direct_steps_
                                                : 0.8 * direct_work_ + 0.2 * work;
    if (direct_steps_ >= kTrialSteps && direct_work_ > pcg_work_) {
      on_direct_ = false;
      retry_in_ = retry_wait_;
      retry_wait_ = retry_wait_ < INT_MAX / 2 ? 2 * retry_wait_ : INT_MAX;
    }
    return;
  }
  pcg_work_ = kPcgIterationWork * static_cast<double>(iterations_);
  pcg_solves_ = solves_;
  pcg_iterations_ = iterations_;
  const bool long_solves = static_cast<double>(iterations_) > kToDirect * solves_;
  long_pcg_steps_ = long_solves ? long_pcg_steps_ + 1 : 0;
  if (retry_in_ > 0) {
    --retry_in_;
  } else if (info.blocks >= kDirectMinBlocks && long_pcg_steps_ >= kLongStepsBeforeTrial) {
    on_direct_ = true;
    long_pcg_steps_ = 0;
    direct_steps_ = 0;
    direct_work_ = 0;
  }
}

double AutoSolver::direct_step_work() const {
  const CholmodFactor& f = direct_->factor();
  const double product_flops = 72.0 * f.stored_blocks();
  if (!(product_flops > 0)) return static_cast<double>(iterations_);
  const double solve = kSolveFlopWeight * 4 * f.factor_entries() / product_flops;
  return static_cast<double>(iterations_) * (1 + solve) + factorisations_ * factorisation_work();
}

double AutoSolver::factorisation_work() const {
  const CholmodFactor& f = direct_->factor();
  const double product_flops = 72.0 * f.stored_blocks();
  if (!(product_flops > 0)) return 0;
  // The factorisation, and the stored matrix assembled for it (about two products).
  return kFactorFlopWeight * f.factor_flops() / product_flops + 2;
}

SolveReport AutoSolver::counted(const SolveReport& r) {
  ++solves_;
  iterations_ += r.iterations;
  factorisations_ += r.factorisations;
  return r;
}

SolveReport AutoSolver::solve(const VecX& b, VecX& x) {
  LinearSolver& s = current();
  s.tolerance = tolerance;
  s.max_iterations = max_iterations;
  s.monitor = monitor;
  return counted(s.solve(b, x));
}

SolveReport AutoSolver::resolve(const VecX& b, VecX& x, std::span<const char> changed_rows) {
  LinearSolver& s = current();
  s.tolerance = tolerance;
  s.max_iterations = max_iterations;
  s.monitor = monitor;
  return counted(s.resolve(b, x, changed_rows));
}

}  // namespace dda
