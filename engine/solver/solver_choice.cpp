// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/solver_choice.hpp"

#include <climits>
#include <cmath>

#include "core/archive.hpp"
#include "core/load_check.hpp"

namespace dda {

AutoSolver::AutoSolver() = default;

void AutoSolver::save_state(ArchiveWriter& ar) const {
  ar(on_direct_, solves_, factorisations_, iterations_, pcg_work_, pcg_solves_, pcg_iterations_, direct_steps_,
     direct_work_, trial_excess_, gave_up_, retry_in_, retry_wait_, long_pcg_steps_);
  pcg_.save_state(ar);
  const bool has_direct = direct_ != nullptr;
  ar(has_direct);
  if (has_direct) direct_->save_state(ar);
}

void AutoSolver::load_state(ArchiveReader& ar) {
  ar(on_direct_, solves_, factorisations_, iterations_, pcg_work_, pcg_solves_, pcg_iterations_, direct_steps_,
     direct_work_, trial_excess_, gave_up_, retry_in_, retry_wait_, long_pcg_steps_);
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
  const bool last_on_pcg = !on_direct_ && !gave_up_;
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
  settings_ = settings;
  info_ = info;
  trial_step_ = on_direct_ && settings.kind == SolverKind::Auto && direct_steps_ < kTrialSteps;
  if (on_direct_) {
    if (!direct_) direct_ = std::make_unique<CholmodSolver>();
    direct_->begin_step(settings, info);
    // Rule 2: in the trial, a new factorisation only while the trial's work
    // with it stays within its budget.
    direct_->may_refactorise = nullptr;
    if (trial_step_)
      direct_->may_refactorise = [this](int iterations) {
        const double step = direct_step_work(iterations_ + iterations, factorisations_ + 1);
        return trial_excess_ + step - pcg_work_ <= kTrialBudget * pcg_work_;
      };
    return;
  }
  pcg_.begin_step(settings, info);
}

void AutoSolver::set_operator(const LinearOperator& a) {
  a_ = &a;
  current().set_operator(a);
}

// Closes the books on the step just done (its counts) and picks the backend
// of the next one (the header's rules 1 and 3).
void AutoSolver::choose(const StepSolveInfo& info) {
  if (solves_ == 0) return;  // no step yet
  if (gave_up_) {            // a trial gave up within the step (rule 2): PCG already, its counts mixed
    gave_up_ = false;
    return;
  }
  if (on_direct_) {
    const double work = direct_step_work();
    ++direct_steps_;
    if (direct_steps_ <= kTrialSteps) {
      trial_excess_ += work - pcg_work_;
      direct_work_ = pcg_work_ + trial_excess_ / direct_steps_;  // the trial's mean
    } else {
      direct_work_ = 0.8 * direct_work_ + 0.2 * work;
    }
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
    direct_work_ = trial_excess_ = 0;
  }
}

AutoSolver::FactorCosts AutoSolver::factor_costs(const CholmodFactor& f) {
  const double product_flops = 72.0 * static_cast<double>(f.stored_blocks());
  if (!(product_flops > 0)) return {};
  return {kSolveFlopWeight * 4 * f.factor_entries() / product_flops,
          kFactorFlopWeight * f.factor_flops() / product_flops + kFactorProducts};
}

double AutoSolver::direct_step_work(long iterations, int factorisations) const {
  const FactorCosts costs = factor_costs(direct_->factor());
  double work = static_cast<double>(iterations) * (1 + costs.solve) + factorisations * costs.factorisation;
  // The trial's first factorisation serves every step the factor is then
  // kept: counted as spread over kRetrySteps steps, not over the trial's
  // first (wall(200): a factorisation of 80,000 blocks outweighed a PCG step,
  // and PCG was kept at 5 times the factor's cost per step).
  if (direct_steps_ == 0 && factorisations > 0) work -= (1 - 1.0 / kRetrySteps) * costs.factorisation;
  return work;
}

void AutoSolver::give_up_trial() {
  on_direct_ = false;
  gave_up_ = true;
  retry_in_ = retry_wait_;
  retry_wait_ *= 2;
  pcg_.begin_step(settings_, info_);
  pcg_.set_operator(*a_);
}

SolveReport AutoSolver::solve_from(const VecX& b, VecX& x, std::span<const char> changed_rows) {
  LinearSolver& s = current();
  s.tolerance = tolerance;
  s.max_iterations = max_iterations;
  s.monitor = monitor;
  SolveReport r = changed_rows.empty() ? s.solve(b, x) : s.resolve(b, x, changed_rows);
  ++solves_;
  iterations_ += r.iterations;
  factorisations_ += r.factorisations;
  if (!on_direct_ || !direct_->declined_factorisation()) return r;
  // The trial gives up (rule 2): this solve goes on with PCG from where the
  // factor left x (a fresh solve: the PCG kept no residual of this system).
  give_up_trial();
  pcg_.tolerance = tolerance;
  pcg_.max_iterations = max_iterations;
  pcg_.monitor = monitor;
  const SolveReport p = pcg_.solve(b, x);
  iterations_ += p.iterations;
  SolveReport both = p;
  both.iterations += r.iterations;
  both.factorisations += r.factorisations;
  both.factor_iterations = r.factor_iterations;
  return both;
}

}  // namespace dda
