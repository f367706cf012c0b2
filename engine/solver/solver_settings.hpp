// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What the controls tell the linear solver: one part per backend, each read by
// its backend alone (LinearSolver::begin_step). A new backend (a sparse
// direct factorisation, PETSc) adds its part here and its name to
// make_linear_solver; the step does not change.
namespace dda {

// The PCG preconditioner. Block-Jacobi (the inverse of each block's 6×6
// diagonal) is cheap and enough where inertia dominates (waves); a multigrid
// preconditioner pays off where contacts and elasticity dominate (quasi-static
// walls, slopes). Auto picks by the system at hand (preconditioner_choice.hpp).
enum class Preconditioning { Auto, BlockJacobi, Multigrid };
constexpr Preconditioning enum_last(Preconditioning) { return Preconditioning::Multigrid; }  // (core/archive.hpp)

// Knobs of the preconditioned conjugate-gradient solver (pcg.hpp) alone.
struct PcgSettings {
  Preconditioning preconditioner = Preconditioning::Auto;
  // Block-Jacobi keeps a block's inverse while every entry of the diagonal
  // block stays within this fraction (of its largest entry) of the block the
  // inverse was made from. How fast the CG converges depends on it, and
  // where a loose open-close solve stops (which friction's normal force
  // sees), not the tolerance reached; 0: invert every rewritten block anew.
  double jacobi_refresh_tolerance = 1e-4;
  // A re-solve after a local change first solves on the changed rows and
  // those within this many couplings of them, the rest held (PcgSolver); 0:
  // off. Only in steps whose solve regime allows local re-solves (wave
  // problems); the global PCG then checks the whole residual and finishes if
  // need be, so the solve meets its tolerance either way.
  int patch_hops = 8;
};

// The sparse direct factorisation (cholmod_solver.hpp).
enum class FillOrdering { Metis, Amd };  // of the block graph, before the factorisation
constexpr FillOrdering enum_last(FillOrdering) { return FillOrdering::Amd; }  // (core/archive.hpp)
struct CholmodSettings {
  FillOrdering ordering = FillOrdering::Metis;
  // CG iterations a solve may take with the factor of an earlier system
  // before the current one is factorised: the factor is kept while it
  // preconditions well enough that a few iterations (a mat-vec and two
  // triangular solves each) cost less than a factorisation.
  int refactor_iterations = 6;
};

// Which solver steps: Auto chooses from the cost the run measures
// (solver_choice.hpp); the others are fixed.
enum class SolverKind { Auto, Pcg, Cholmod };

// The preconditioner of meshed models' nodes (MeshedSolver,
// assembly/mesh_reduction.hpp): each meshed block's own nodal matrix,
// factorised (a Cholesky factor per meshed block, kept while it serves), or
// the nodes' 2×2 diagonal blocks.
enum class MeshPreconditioning { BlockFactor, NodeJacobi };
constexpr MeshPreconditioning enum_last(MeshPreconditioning) {
  return MeshPreconditioning::NodeJacobi;
}  // (core/archive.hpp)

struct SolverSettings {
  SolverKind kind = SolverKind::Auto;
  PcgSettings pcg;
  CholmodSettings cholmod;
  MeshPreconditioning mesh_preconditioner = MeshPreconditioning::BlockFactor;
};

}  // namespace dda
