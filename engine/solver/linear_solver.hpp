#pragma once
// Linear solvers behind one interface (as MFEM's linalg/solvers.hpp): an
// operator, tolerance, iteration limit, warm start from the given x, an
// optional monitor, and a report that says when the solve failed instead of
// carrying on. A distributed backend can slot in behind the same interface.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "core/symmetric6.hpp"
#include "solver/block_sparse_matrix.hpp"

namespace dda {

struct SolveReport {
  bool converged = false;
  bool finite = true;  // false when a NaN/Inf appeared
  int iterations = 0;
  double relative_residual = 0;
  // Iterations of a re-solve confined to the rows near the changed ones
  // (PcgSolver::patch_hops), and how many rows that patch had.
  int patch_iterations = 0;
  int patch_rows = 0;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual void set_operator(const LinearOperator& a) = 0;
  // Solves A·x = b; x holds the initial guess on entry.
  virtual SolveReport solve(const VecX& b, VecX& x) = 0;
  // Solves again after a change confined to some rows: x is what the last
  // solve returned (converged, untouched since), and A and b differ from that
  // solve's only in the block rows flagged in `changed_rows`. A solver may
  // then recompute the starting residual on those rows alone. The default
  // solves from scratch.
  virtual SolveReport resolve(const VecX& b, VecX& x, std::span<const char> /*changed_rows*/) { return solve(b, x); }

  double tolerance = 1e-10;  // on ‖b − A·x‖ / ‖b‖
  int max_iterations = 1000;
  // Called after every iteration with (iteration, relative residual).
  std::function<void(int, double)> monitor;
};

// Preconditioner interface: z = M⁻¹ r.
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // The blocks' centroids, for preconditioners that coarsen geometrically.
  // Called before setup() whenever the geometry may have changed.
  virtual void set_block_centroids(std::span<const Vec2> /*centroids*/) {}
  virtual void setup(const LinearOperator& a) = 0;
  virtual void apply(const VecX& r, VecX& z) const = 0;
  // A preconditioner whose block row i of z depends on row i of r alone
  // (block-Jacobi) can be applied by ranges of rows, inside the PCG's own
  // passes over the vectors: one parallel pass fewer per iteration.
  virtual bool applies_by_rows() const { return false; }
  virtual void apply_rows(std::size_t /*begin*/, std::size_t /*end*/, const VecX& /*r*/, VecX& /*z*/) const {}
};

// Block-Jacobi: the inverse of each 6×6 diagonal block (Cholesky).
class BlockJacobi final : public Preconditioner {
 public:
  void setup(const LinearOperator& a) override;
  void apply(const VecX& r, VecX& z) const override;
  bool applies_by_rows() const override { return true; }
  void apply_rows(std::size_t begin, std::size_t end, const VecX& r, VecX& z) const override;

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
  void set_operator(const LinearOperator& a) override;
  Preconditioner& preconditioner() { return *pre_; }
  void set_preconditioner(std::unique_ptr<Preconditioner> pre) { pre_ = std::move(pre); }
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

// Sparse direct LDLᵀ (Eigen). A test oracle, not used by the engine's step.
class DirectSolver final : public LinearSolver {
 public:
  void set_operator(const LinearOperator& a) override { a_ = &a.stored(); }
  SolveReport solve(const VecX& b, VecX& x) override;

 private:
  const BlockSparseMatrix* a_ = nullptr;
};

double deterministic_dot(const VecX& a, const VecX& b);

// The inverse of a symmetric positive definite 6×6 block by Cholesky, with
// fixed-size loops (Eigen's solve() with a matrix right-hand side goes
// through its general blocked triangular solver: 5× the instructions).
// Returns false, and the reciprocal diagonal, when the block is not
// positive definite.
bool invert_spd6(const Mat6& a, Mat6& inverse);

}  // namespace dda
