// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Linear solvers behind one interface (as MFEM's linalg/solvers.hpp): an
// operator, tolerance, iteration limit, warm start from the given x, an
// optional monitor, and a report that says when the solve failed instead of
// carrying on. The step holds a LinearSolver made by make_linear_solver and
// knows no backend.
//
// The backends:
//   * PcgSolver (pcg.hpp): CG with block-Jacobi or multigrid; matrix-free
//     products, cheap where the blocks' inertia dominates (wave problems).
//   * CholmodSolver (cholmod_solver.hpp): CG preconditioned with a sparse
//     Cholesky factor kept across open-close iterations and steps, for stiff
//     systems (walls, slopes). It asks the operator for its entries through
//     LinearOperator::stored_matrix().
//   * AutoSolver (solver_choice.hpp), what make_linear_solver returns: steps
//     with one of them, chosen each step from the work the run counted
//     (SolverSettings::kind overrides).
// A distributed backend (PETSc, block size 6) would copy the block rows of
// stored_matrix() into a MATBAIJ matrix, with its settings in its own part of
// SolverSettings and a SolverKind.
#include <functional>
#include <memory>
#include <span>

#include "core/types.hpp"
#include "solver/linear_operator.hpp"
#include "solver/solver_settings.hpp"

namespace dda {

class ArchiveWriter;
class ArchiveReader;

struct SolveReport {
  bool converged = false;
  bool finite = true;  // false when a NaN/Inf appeared
  int iterations = 0;
  double relative_residual = 0;
  // Iterations of a re-solve confined to the rows near the changed ones
  // (PcgSettings::patch_hops), and how many rows that patch had.
  int patch_iterations = 0;
  int patch_rows = 0;
  int factorisations = 0;     // numeric factorisations of the system (a direct backend)
  int factor_iterations = 0;  // of `iterations`, those preconditioned with a sparse factor (CholmodSolver)
};

// What the step knows of its solves, told to the solver once per step before
// the first of them (LinearSolver::begin_step).
struct StepSolveInfo {
  int blocks = 0;                         // block rows of the systems to come
  std::span<const Vec2> block_centroids;  // for solvers that coarsen geometrically
  // The step's solve regime allows a re-solve after a local change to start
  // locally: a local change stays local where the blocks' inertia dominates
  // their springs (wave problems), not where solves are long (walls).
  bool local_resolves = false;
  // The previous step's solves and their iterations in all (0 before the
  // first step; after choose_backend, of the last step solved the way this
  // one is): the same for any thread count, so choices made from them keep
  // results independent of the threads.
  int last_step_solves = 0;
  long last_step_iterations = 0;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // Once per step, first: a solver with more than one backend (AutoSolver)
  // settles which one the step solves with, and returns `info` with the last
  // step's counts replaced by those of the last step solved that way. The
  // step's solve regime (world/solve_regime.hpp) is chosen from them: the
  // previous step's few iterations with a factor say nothing of a PCG step.
  // The default keeps the counts.
  virtual StepSolveInfo choose_backend(const SolverSettings& /*settings*/, const StepSolveInfo& info) { return info; }
  // Once per step, before its solves: the settings (each backend reads its
  // own part) and what the step knows of its solves. The default ignores both.
  virtual void begin_step(const SolverSettings& /*settings*/, const StepSolveInfo& /*info*/) {}
  // Once per step, after its last solve (before a checkpoint can be taken):
  // a solver that decides from the step's counts decides here, and may
  // prepare for the next step with the step's last system (AutoSolver
  // factorises it for a trial of the factor). Returns the numeric
  // factorisations it made, for the step's stats. The default does nothing.
  virtual int end_step() { return 0; }
  virtual void set_operator(const LinearOperator& a) = 0;
  // Solves A·x = b; x holds the initial guess on entry.
  virtual SolveReport solve(const VecX& b, VecX& x) = 0;
  // Solves again after a change confined to some rows: x is what the last
  // solve returned (converged, untouched since), and A and b differ from that
  // solve's only in the block rows flagged in `changed_rows`. A solver may
  // then recompute the starting residual on those rows alone. The default
  // solves from scratch.
  virtual SolveReport resolve(const VecX& b, VecX& x, std::span<const char> /*changed_rows*/) { return solve(b, x); }
  // The backend that solves ("pcg", "cholmod"), for the step's stats.
  virtual const char* name() const = 0;

  // Checkpoints (world/checkpoint.hpp): what the solver carries from one step
  // to the next that changes a result bit (a preconditioner kept while it
  // still serves, a choice made from the last step). The default: nothing.
  virtual void save_state(ArchiveWriter& /*ar*/) const {}
  virtual void load_state(ArchiveReader& /*ar*/) {}

  double tolerance = 1e-10;  // on ‖b − A·x‖ / ‖b‖
  int max_iterations = 1000;
  // Called after every iteration with (iteration, relative residual).
  std::function<void(int, double)> monitor;
};

// The solver a World steps with.
std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings);

// Preconditioner interface: z = M⁻¹ r.
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // The PCG's settings, whenever they may have changed (once per step).
  virtual void configure(const PcgSettings& /*settings*/) {}
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
  // As LinearSolver's: what it keeps from step to step (default: nothing).
  virtual void save_state(ArchiveWriter& /*ar*/) const {}
  virtual void load_state(ArchiveReader& /*ar*/) {}
};

double deterministic_dot(const VecX& a, const VecX& b);

// The inverse of a symmetric positive definite 6×6 block by Cholesky, with
// fixed-size loops (Eigen's solve() with a matrix right-hand side goes
// through its general blocked triangular solver: 5× the instructions).
// Returns false, and the reciprocal diagonal, when the block is not
// positive definite.
bool invert_spd6(const Mat6& a, Mat6& inverse);

}  // namespace dda
