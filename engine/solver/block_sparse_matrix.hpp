// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The global DDA matrix: symmetric, 6×6 blocks, one block row per rock block,
// a block (i, j) wherever blocks i and j are in contact. Stored in full
// (both (i,j) and (j,i)) as compressed block rows so that each row is owned
// by exactly one task in assembly and in the mat-vec: deterministic and
// lock-free.
#include <Eigen/SparseCore>
#include <span>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "solver/linear_operator.hpp"

namespace dda {

class LoadCheck;

class BlockSparseMatrix final : public LinearOperator {
 public:
  // n block rows; `pairs` are the off-diagonal couplings (i < j), sorted and unique.
  void set_structure(int n, std::span<const std::pair<int, int>> pairs);

  int rows() const override { return n_; }
  int nonzero_blocks() const { return static_cast<int>(cols_.size()); }
  int row_begin(int i) const { return row_start_[i]; }
  int row_end(int i) const { return row_start_[i + 1]; }
  int col(int k) const { return cols_[k]; }
  int diagonal(int i) const { return diag_[i]; }
  // Index of block (i, j) in values(), or -1 when not stored.
  int find(int i, int j) const;
  // The sparsity pattern (compressed block rows), e.g. to tell whether it changed.
  std::span<const int> row_starts() const { return row_start_; }
  std::span<const int> columns() const { return cols_; }

  Mat6& value(int k) { return values_[k]; }
  const Mat6& value(int k) const { return values_[k]; }

  // y = A·x, parallel over block rows.
  void multiply(const VecX& x, VecX& y) const;

  // LinearOperator
  Mat6 diagonal_block(int i) const override { return values_[diag_[i]]; }
  void multiply_rows(int begin, int end, const VecX& x, VecX& y) const override;
  bool append_neighbours(int i, std::vector<int>& out) const override {
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k)
      if (cols_[k] != i) out.push_back(cols_[k]);
    return true;
  }
  const BlockSparseMatrix* stored_matrix() const override { return this; }

  // Scalar sparse copy (test oracle and debugging only; not used in the step).
  Eigen::SparseMatrix<double> to_sparse() const;

  // Checkpoints (core/archive.hpp): the pattern and the values.
  template <class Archive>
  void fields(Archive& ar) {
    ar(n_, row_start_, cols_, diag_, values_);
  }
  // Read from a checkpoint: a pattern set_structure could have made (rows
  // from 0 to the columns' end, columns ascending and in range, the pattern
  // symmetric, every diagonal found), a value per stored block
  // (core/load_check.hpp; `name` names the matrix).
  void check_loaded(const LoadCheck& check, const char* name) const;

 private:
  int n_ = 0;
  std::vector<int> row_start_, cols_, diag_;
  std::vector<Mat6> values_;
};

}  // namespace dda
