// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A symmetric matrix of 6×6 blocks stored once per block pair: the upper
// triangle (i, j ≥ i) by block rows, and for each row the blocks of the
// rows above that hold its lower part, read transposed. Half the memory
// traffic of full storage in the product, which is what long solves on large
// models (walls of 10^4–10^5 blocks) wait for. The product is gathered row by
// row, each by one task, in a fixed order: the same sums for any thread count.
#include <span>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace dda {

class SymmetricBlockMatrix {
 public:
  // n block rows; `pairs` are the off-diagonal couplings (i < j), sorted and unique.
  void set_structure(int n, std::span<const std::pair<int, int>> pairs);

  int rows() const { return n_; }
  // Block (i, j), i ≤ j, in the upper triangle: its index in value(), or -1.
  int find(int i, int j) const;
  int diagonal(int i) const { return upper_start_[i]; }  // the first block of row i
  Mat6& value(int k) { return values_[k]; }
  const Mat6& value(int k) const { return values_[k]; }

  // (A·x) for block rows [begin, end) into the same rows of y.
  void multiply_rows(int begin, int end, const VecX& x, VecX& y) const;

 private:
  int n_ = 0;
  std::vector<int> upper_start_, upper_col_;                // row i: blocks (i, j ≥ i), diagonal first
  std::vector<int> lower_start_, lower_row_, lower_block_;  // row i: blocks (j < i, i), read as (i, j)ᵀ
  std::vector<Mat6> values_;
};

}  // namespace dda
