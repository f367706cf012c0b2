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
  ar(on_direct_, solves_, factorisations_, iterations_, pcg_work_, pcg_solves_, pcg_iterations_, pcg_steps_, measuring_,
     direct_steps_, direct_work_, direct_solves_, direct_iterations_, gave_up_, last_on_pcg_, retry_in_, retry_wait_);
  pcg_.save_state(ar);
  const bool has_direct = direct_ != nullptr;
  ar(has_direct);
  if (has_direct) direct_->save_state(ar);
}

void AutoSolver::load_state(ArchiveReader& ar) {
  ar(on_direct_, solves_, factorisations_, iterations_, pcg_work_, pcg_solves_, pcg_iterations_, pcg_steps_, measuring_,
     direct_steps_, direct_work_, direct_solves_, direct_iterations_, gave_up_, last_on_pcg_, retry_in_, retry_wait_);
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
  const long long counts[] = {solves_,    factorisations_, iterations_,    pcg_solves_,        pcg_iterations_,
                              pcg_steps_, direct_steps_,   direct_solves_, direct_iterations_, retry_in_,
                              retry_wait_};
  for (const long long n : counts) check.require(n >= 0 && n < kMaxCount, "its solver counts hold ", n);
  check.require(std::isfinite(pcg_work_) && std::isfinite(direct_work_), "its solver's work figures are not finite");
  check.require(!on_direct_ || direct_, "its solver is on a CHOLMOD factor it does not hold");
}

StepSolveInfo AutoSolver::choose_backend(const SolverSettings& settings, const StepSolveInfo& info) {
  if (settings.kind != SolverKind::Auto) on_direct_ = settings.kind == SolverKind::Cholmod;
  // Rule 4: the last step of this backend's counts, for the solve regime
  // and the PCG's preconditioner (none before the trial's: the factor's
  // regime after no step).
  StepSolveInfo own = info;
  if (settings.kind != SolverKind::Auto) return own;
  if (on_direct_) {
    own.last_step_solves = direct_solves_;
    own.last_step_iterations = direct_iterations_;
  } else if (!last_on_pcg_) {
    own.last_step_solves = pcg_solves_;
    own.last_step_iterations = pcg_iterations_;
  }
  return own;
}

void AutoSolver::begin_step(const SolverSettings& settings, const StepSolveInfo& info) {
  settings_ = settings;
  info_ = info;
  trial_step_ = on_direct_ && settings.kind == SolverKind::Auto && direct_steps_ == 0;
  if (on_direct_) {
    if (!direct_) direct_ = std::make_unique<CholmodSolver>();
    direct_->begin_step(settings, info);
    // Rule 1: in the trial, a new factorisation only while the step's work
    // with it stays within its budget.
    direct_->may_refactorise = nullptr;
    if (trial_step_)
      direct_->may_refactorise = [this](int iterations) {
        return direct_step_work(iterations_ + iterations, factorisations_ + 1) <= (1 + kTrialBudget) * pcg_work_;
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
// of the next one (the header's rules 1 to 3); a trial next starts from a
// factor of this step's last system.
int AutoSolver::end_step() {
  last_on_pcg_ = !on_direct_ && !gave_up_;
  const bool was_on_direct = on_direct_;
  if (settings_.kind == SolverKind::Auto && solves_ > 0) choose();
  solves_ = factorisations_ = 0;
  iterations_ = 0;
  gave_up_ = false;
  // PCG takes over until the next trial, which makes its own factor: the
  // factor's memory is given back.
  if (!on_direct_ && !measuring_) direct_.reset();
  return on_direct_ && !was_on_direct && direct_steps_ == 0 ? start_trial() : 0;
}

void AutoSolver::choose() {
  if (gave_up_) return;  // a trial gave up within the step (rule 1): PCG already, its counts mixed
  if (on_direct_)
    close_direct_step();
  else
    close_pcg_step();
}

// Rule 1: the factor of the PCG step's last system, counted in the trial
// step (its first factorisation). Not positive definite: the trial step
// factorises its own first system.
int AutoSolver::start_trial() {
  const BlockSparseMatrix* stored = a_ ? a_->stored_matrix() : nullptr;
  if (!stored) return 0;
  if (!direct_) direct_ = std::make_unique<CholmodSolver>();
  direct_->begin_step(settings_, info_);
  direct_->factorise(*a_);
  factorisations_ = 1;
  return 1;
}

void AutoSolver::close_direct_step() {
  const double work = direct_step_work();
  ++direct_steps_;
  direct_work_ = direct_steps_ <= kMeanSteps ? direct_work_ + (work - direct_work_) / direct_steps_
                                             : 0.8 * direct_work_ + 0.2 * work;
  direct_solves_ = solves_;
  direct_iterations_ = iterations_;
  if (direct_steps_ == 1 && pcg_steps_ < 2) {  // rule 2: no PCG step has measured yet
    on_direct_ = false;
    measuring_ = true;
    return;
  }
  if (direct_work_ > pcg_work_) {
    on_direct_ = false;
    wait_before_retrying();
  }
}

void AutoSolver::close_pcg_step() {
  pcg_work_ = kPcgIterationWork * static_cast<double>(iterations_);
  pcg_solves_ = solves_;
  pcg_iterations_ = iterations_;
  ++pcg_steps_;
  if (measuring_) {  // rule 2: the trial just made against this step
    measuring_ = false;
    on_direct_ = direct_work_ <= pcg_work_;
    if (!on_direct_) wait_before_retrying();
    return;
  }
  const bool long_solves = static_cast<double>(iterations_) > kToDirect * solves_;
  if (retry_in_ > 0) {
    --retry_in_;
  } else if (a_->rows() >= kDirectMinBlocks && long_solves) {
    on_direct_ = true;
    direct_steps_ = direct_solves_ = 0;
    direct_iterations_ = 0;
    direct_work_ = 0;
  }
}

void AutoSolver::wait_before_retrying() {
  retry_in_ = retry_wait_;
  retry_wait_ = retry_wait_ < INT_MAX / 2 ? 2 * retry_wait_ : INT_MAX;
}

AutoSolver::FactorCosts AutoSolver::factor_costs(const CholmodFactor& f) {
  const double product_flops = 72.0 * static_cast<double>(f.stored_blocks());
  if (!(product_flops > 0)) return {};
  return {kSolveFlopWeight * 4 * f.factor_entries() / product_flops,
          (kFactorFlopWeight * f.factor_flops() + kFactorEntryWeight * f.factor_entries()) / product_flops +
              kFactorProducts};
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
  wait_before_retrying();
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
  // The trial gives up (rule 1): this solve goes on with PCG from where the
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
