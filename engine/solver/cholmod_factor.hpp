// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A sparse Cholesky factor A = L·Lᵀ of a stored block matrix by CHOLMOD
// (SuiteSparse), supernodal, and M⁻¹ r by its two triangular solves.
//
//   * The ordering is computed on the block graph (one node per rock block,
//     an edge per coupled pair) and expanded to the 6 unknowns of each block:
//     a sixth of the graph to order, and supernodes that never split a block.
//     METIS nested dissection by default (its seed is fixed: the same
//     ordering every run), AMD on request.
//   * analyse() (the ordering and the symbolic factor) runs when the block
//     pattern differs from the one analysed last: once per contact list,
//     since the stored pattern holds every pair the list couples, open
//     contacts included. factorise() only refills the values and redoes the
//     numeric factor.
//   * Determinism: the supernodal factor's dense kernels are the engine's own
//     (portable_blas.hpp), not the system BLAS's, whose kernels differ by
//     CPU; CHOLMOD runs on the caller's thread (no OpenMP teams). Everything
//     else is fixed-order, so the factor's bits depend neither on the step's
//     threads nor on the machine.
#include <cstddef>
#include <vector>

#include "core/types.hpp"
#include "solver/block_sparse_matrix.hpp"
#include "solver/solver_settings.hpp"

struct cholmod_common_struct;
struct cholmod_factor_struct;
struct cholmod_sparse_struct;
struct cholmod_dense_struct;

namespace dda {

class CholmodFactor {
 public:
  CholmodFactor();
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  FillOrdering ordering = FillOrdering::Metis;

  // Analyses (when the pattern changed since the last analysis) and
  // factorises a. False when a is not positive definite (then ready() is
  // false until the next successful factorise).
  bool factorise(const BlockSparseMatrix& a);
  bool ready() const { return ready_; }
  // The matrix of the last factorisation (while ready()), rebuilt from the
  // triangle CHOLMOD holds: the factor keeps no copy of its own (on
  // wall(200) it would be 160 MB). A checkpoint stores it and a restored run
  // factorises it again: the same triangle, ordering and single-threaded
  // kernels give the same factor bit for bit, so the run continues as the
  // straight run would have.
  BlockSparseMatrix factorised_matrix() const;
  // z = A⁻¹ r with the factor (r and z sized 6 × the factor's block rows).
  void solve(const VecX& r, VecX& z) const;
  int block_rows() const { return blocks_; }
  std::size_t stored_blocks() const { return columns_.size(); }  // of the analysed block pattern

  // Counts and sizes, for the step's stats and the cost model of the
  // automatic solver choice (solver_choice.hpp): all the same for any
  // thread count.
  int analyses() const { return analyses_; }
  int factorisations() const { return factorisations_; }
  double factor_flops() const { return factor_flops_; }      // one numeric factorisation (CHOLMOD's count)
  double factor_entries() const { return factor_entries_; }  // nnz(L)
  std::size_t peak_bytes() const;                            // CHOLMOD's peak memory since construction

 private:
  void analyse(const BlockSparseMatrix& a);
  void fill_values(const BlockSparseMatrix& a);

  cholmod_common_struct* common_;
  cholmod_sparse_struct* a_ = nullptr;  // lower triangle, scalar, the analysed pattern
  cholmod_factor_struct* l_ = nullptr;
  mutable cholmod_dense_struct *x_ = nullptr, *y_ = nullptr, *e_ = nullptr;  // cholmod_solve2's workspace
  std::vector<int> row_starts_, columns_;                                    // the block pattern analysed
  std::vector<int> value_start_;  // per block row: where its 6 scalar columns start in a_
  int blocks_ = 0;
  bool ready_ = false;
  int analyses_ = 0, factorisations_ = 0;
  double factor_flops_ = 0, factor_entries_ = 0;
};

}  // namespace dda
