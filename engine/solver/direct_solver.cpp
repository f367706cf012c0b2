// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/direct_solver.hpp"

#include <Eigen/SparseCholesky>

#include "core/error.hpp"
#include "solver/block_sparse_matrix.hpp"

namespace dda {

void DirectSolver::set_operator(const LinearOperator& a) {
  a_ = a.stored_matrix();
  if (!a_) throw Error("the direct solver needs the operator's entries, and this operator is matrix-free only");
}

SolveReport DirectSolver::solve(const VecX& b, VecX& x) {
  DDA_ASSERT(a_ != nullptr, "DirectSolver::solve before set_operator");
  SolveReport report;
  Eigen::SparseMatrix<double> a = a_->to_sparse();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  if (ldlt.info() != Eigen::Success) return report;
  x = ldlt.solve(b);
  report.finite = x.allFinite();
  report.converged = report.finite;
  const double bn = b.norm();
  report.relative_residual = bn > 0 ? (b - a * x).norm() / bn : 0;
  report.iterations = 1;
  return report;
}

}  // namespace dda
