// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/cholmod_solver.hpp"

#include <algorithm>

#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/load_check.hpp"
#include "solver/block_sparse_matrix.hpp"

namespace dda {

CholmodSolver::CholmodSolver() : cg_(std::make_unique<CholmodPreconditioner>(factor_)) {}

void CholmodSolver::begin_step(const SolverSettings& settings, const StepSolveInfo& /*info*/) {
  refactor_iterations = settings.cholmod.refactor_iterations;
  factor_.ordering = settings.cholmod.ordering;
}

void CholmodSolver::save_state(ArchiveWriter& ar) const {
  const bool ready = factor_.ready();
  ar(ready);
  if (ready) ar(factor_.ordering, factor_.factorised_matrix());
}

void CholmodSolver::load_state(ArchiveReader& ar) {
  bool ready = false;
  ar(ready);
  if (!ready) return;
  BlockSparseMatrix a;
  ar(factor_.ordering, a);
  a.check_loaded(LoadCheck(ar.what()), "the CHOLMOD factor's matrix");
  if (!factor_.factorise(a))
    throw Error(msg(ar.what(), " is damaged: the CHOLMOD factor it holds cannot be made again"));
}

void CholmodSolver::set_operator(const LinearOperator& a) {
  a_ = &a;
  cg_.set_operator(a);
}

bool CholmodSolver::factorise(const LinearOperator& a) {
  set_operator(a);
  return refactorise();
}

bool CholmodSolver::refactorise() {
  const BlockSparseMatrix* stored = a_->stored_matrix();
  if (!stored) throw Error("the CHOLMOD solver needs the operator's entries, and this operator is matrix-free only");
  return factor_.factorise(*stored);
}

SolveReport CholmodSolver::solve_from(const VecX& b, VecX& x, std::span<const char> changed_rows) {
  DDA_ASSERT(a_ != nullptr, "CholmodSolver::solve before set_operator");
  int factorised = 0;
  auto factorise = [&] {
    ++factorised;
    return refactorise();
  };
  // A factor of other dimensions (blocks added or removed) cannot serve.
  if ((!factor_.ready() || factor_.block_rows() != a_->rows()) && !factorise()) {
    SolveReport failed;  // not positive definite: not converged, the step cuts Δt
    failed.factorisations = factorised;
    return failed;
  }
  cg_.tolerance = tolerance;
  cg_.monitor = monitor;
  // With the factor of an earlier system: at most refactor_iterations, then
  // factorise this one and go on from where the CG got.
  cg_.max_iterations = factorised ? max_iterations : std::min(max_iterations, refactor_iterations);
  SolveReport report = changed_rows.empty() ? cg_.solve(b, x) : cg_.resolve(b, x, changed_rows);
  declined_ =
      !report.converged && report.finite && !factorised && may_refactorise && !may_refactorise(report.iterations);
  if (!report.converged && report.finite && !factorised && !declined_) {
    const int before = report.iterations;
    if (factorise()) {
      cg_.max_iterations = max_iterations;
      report = cg_.solve(b, x);
    }
    report.iterations += before;
  }
  report.factorisations = factorised;
  report.factor_iterations = report.iterations;
  return report;
}

}  // namespace dda
