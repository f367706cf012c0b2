// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The sparse direct solver of stiff systems (quasi-static walls, slopes,
// dynamic steps of a millisecond): CG preconditioned with a CHOLMOD factor
// (cholmod_factor.hpp) that is kept across open-close iterations and steps.
//
// A fresh factor is the exact inverse: the CG then ends after one iteration
// (a direct solve, with its residual checked). Between open-close
// iterations only the rows of the contacts that changed state change, and
// between steps the blocks move a little: the factor of an earlier system
// is then an almost exact preconditioner, and CG needs a few iterations
// (each a mat-vec and two triangular solves) instead of a factorisation. When
// a solve takes more than CholmodSettings::refactor_iterations, it stops,
// the current system is factorised, and the solve goes on from where it got
// (then one or two iterations). The symbolic analysis is redone only when
// the block pattern (the contact list) changed.
//
// Which systems are factorised depends only on iteration counts, which are
// the same for any thread count (the PCG's sums are fixed-order), and the
// factor's bits do not depend on the threads: results are identical for any
// thread count.
#include <functional>
#include <memory>

#include "solver/cholmod_factor.hpp"
#include "solver/pcg.hpp"

namespace dda {

// CG's preconditioner: M⁻¹ r by the factor's triangular solves. setup() keeps
// the factor (CholmodSolver decides when to refactorise).
class CholmodPreconditioner final : public Preconditioner {
 public:
  explicit CholmodPreconditioner(CholmodFactor& factor) : factor_(factor) {}
  void setup(const LinearOperator& /*a*/) override {}
  void apply(const VecX& r, VecX& z) const override { factor_.solve(r, z); }

 private:
  CholmodFactor& factor_;
};

class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver();
  void begin_step(const SolverSettings& settings, const StepSolveInfo& info) override;
  // Throws dda::Error when the operator has no stored matrix.
  void set_operator(const LinearOperator& a) override;
  SolveReport solve(const VecX& b, VecX& x) override { return solve_from(b, x, {}); }
  SolveReport resolve(const VecX& b, VecX& x, std::span<const char> changed_rows) override {
    return solve_from(b, x, changed_rows);
  }
  const char* name() const override { return "cholmod"; }
  // The factor in use, as the matrix it was made from (cholmod_factor.hpp).
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;
  const CholmodFactor& factor() const { return factor_; }
  // Factorises the operator's system now, to be kept for the solves to come
  // (the automatic choice's trial starts from the last step's system, as a
  // step with the factor does). False when it is not positive definite.
  bool factorise(const LinearOperator& a);

  // CG iterations a solve may take with the factor it has before the system
  // is factorised anew (CholmodSettings::refactor_iterations).
  int refactor_iterations = 6;
  // Asked, with the solve's iterations so far, before a kept factor that no
  // longer serves is replaced by a factorisation of the current system (the
  // automatic choice, solver_choice.hpp, declines one that would cost more
  // than a step with PCG). Declined: the solve returns unconverged and
  // declined_factorisation() says why. Empty: always.
  std::function<bool(int iterations)> may_refactorise;
  bool declined_factorisation() const { return declined_; }

 private:
  SolveReport solve_from(const VecX& b, VecX& x, std::span<const char> changed_rows);
  bool refactorise();

  CholmodFactor factor_;
  PcgSolver cg_;
  const LinearOperator* a_ = nullptr;
  bool declined_ = false;
};

}  // namespace dda
