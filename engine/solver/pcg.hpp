// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Preconditioned conjugate gradients, the step's linear solver, and its
// block-Jacobi preconditioner (multigrid.hpp holds the other).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/symmetric6.hpp"
#include "solver/linear_solver.hpp"

namespace dda {

// Block-Jacobi: the inverse of each 6×6 diagonal block (Cholesky).
class BlockJacobi final : public Preconditioner {
 public:
  void configure(const PcgSettings& settings) override { refresh_tolerance = settings.jacobi_refresh_tolerance; }
  void setup(const LinearOperator& a) override;
  void apply(const VecX& r, VecX& z) const override;
  bool applies_by_rows() const override { return true; }
  void apply_rows(std::size_t begin, std::size_t end, const VecX& r, VecX& z) const override;
  // The kept inverses and the blocks they were made from (the operator's
  // revision numbers are not kept: a restored one checks every block).
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;

  // Relative change of a diagonal block below which its inverse is kept.
  double refresh_tolerance = 1e-4;

 private:
  // The diagonal blocks inverse_ was made from, and the operator's revision
  // numbers of the blocks last looked at.
  std::vector<Symmetric6> basis_;
  std::vector<std::uint64_t> revision_;
  std::vector<Symmetric6> inverse_;
};

// Preconditioned conjugate gradients with a parallel mat-vec and
// deterministic (fixed-chunk) dot products. The vector updates are fused
// with the dot products that follow them (A·p with pᵀAp; the x and r
// updates with ‖r‖²), so an iteration is the mat-vec, the preconditioner and
// three more passes over the vectors.
class PcgSolver final : public LinearSolver {
 public:
  explicit PcgSolver(std::unique_ptr<Preconditioner> pre = std::make_unique<BlockJacobi>());
  // Chooses the preconditioner (PcgSettings::preconditioner; Auto decides
  // from the last step's iterations per solve, preconditioner_choice.hpp),
  // hands it the settings and the centroids, and sets patch_hops.
  void begin_step(const SolverSettings& settings, const StepSolveInfo& info) override;
  void set_operator(const LinearOperator& a) override;
  const char* name() const override { return "pcg"; }
  Preconditioner& preconditioner() { return *pre_; }
  void set_preconditioner(std::unique_ptr<Preconditioner> pre) { pre_ = std::move(pre); }
  // The preconditioner chosen last and its state.
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;
  SolveReport solve(const VecX& b, VecX& x) override { return solve_from(b, x, {}); }
  // Keeps the last solve's residual on the rows not flagged (one mat-vec
  // fewer per open-close iteration after the first).
  SolveReport resolve(const VecX& b, VecX& x, std::span<const char> changed_rows) override {
    return solve_from(b, x, changed_rows);
  }
  // A re-solve first solves on a patch: the changed rows and the rows within
  // patch_hops couplings of them, the rest of x held (0: off). Where the
  // system is diagonally dominant (wave problems: a block's inertia against
  // its springs), the correction a local change asks for dies out within a
  // few blocks, and a patch iteration costs its rows, not the whole system.
  // The global PCG then takes over from the patch's answer (often with
  // nothing left to do). Used only when the patch is under
  // patch_max_share of the rows and the preconditioner applies by rows.
  // begin_step sets it from PcgSettings::patch_hops where the step allows
  // local re-solves, else 0.
  int patch_hops = 0;
  double patch_max_share = 0.25;

 private:
  SolveReport solve_from(const VecX& b, VecX& x, std::span<const char> changed_rows);
  bool build_patch(std::span<const char> changed_rows);
  void size_patch_buffers(std::size_t blocks);
  double solve_on_patch(VecX& x, double bnorm, SolveReport& report);
  template <typename F>
  double chunked_sum(std::size_t blocks, F&& f);
  // Two sums at once: f(begin, end, first, second) adds the chunk's shares.
  template <typename F>
  std::pair<double, double> chunked_sums(std::size_t blocks, F&& f);

  const LinearOperator* a_ = nullptr;
  std::unique_ptr<Preconditioner> pre_;
  std::optional<Preconditioning> kind_;     // what begin_step chose last (empty: none yet)
  VecX r_, z_, p_, ap_;                     // reused between solves: no allocation in the step loop
  bool residual_valid_ = false;             // r_ = b − A·x for the x the last solve returned (converged)
  std::vector<double> partial_, partial2_;  // per-chunk partial sums of the fused kernels
  // The patch of a re-solve: its rows (ascending), the rows just outside it
  // whose residual its correction changes, a mark per row (on either list),
  // and its search direction and total correction (full length, zero
  // outside the patch between solves).
  std::vector<int> patch_, patch_boundary_, neighbours_;
  std::vector<char> patch_mark_;
  VecX patch_p_, patch_d_;
};

}  // namespace dda
