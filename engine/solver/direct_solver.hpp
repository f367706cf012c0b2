// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Sparse direct LDLᵀ (Eigen's simplicial factorisation). A test oracle for
// the PCG, not used by the engine's step; it shows the stored-matrix
// capability a direct backend uses (linear_solver.hpp).
#include "solver/linear_solver.hpp"

namespace dda {

class DirectSolver final : public LinearSolver {
 public:
  // Throws dda::Error when the operator has no stored matrix.
  void set_operator(const LinearOperator& a) override;
  SolveReport solve(const VecX& b, VecX& x) override;
  const char* name() const override { return "ldlt"; }

 private:
  const BlockSparseMatrix* a_ = nullptr;
};

}  // namespace dda
