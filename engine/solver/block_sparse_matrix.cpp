// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/block_sparse_matrix.hpp"

#include "core/load_check.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace dda {

void BlockSparseMatrix::set_structure(int n, std::span<const std::pair<int, int>> pairs) {
  n_ = n;
  std::vector<int> count(n, 1);  // the diagonal
  for (const auto& [i, j] : pairs) {
    DDA_ASSERT(i < j && j < n, "off-diagonal pairs must satisfy i < j < n");
    ++count[i];
    ++count[j];
  }
  row_start_.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) row_start_[i + 1] = row_start_[i] + count[i];
  cols_.assign(row_start_[n], 0);
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  for (int i = 0; i < n; ++i) cols_[fill[i]++] = i;
  for (const auto& [i, j] : pairs) {
    cols_[fill[i]++] = j;
    cols_[fill[j]++] = i;
  }
  diag_.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    std::sort(cols_.begin() + row_start_[i], cols_.begin() + row_start_[i + 1]);
    diag_[i] = find(i, i);
  }
  values_.assign(cols_.size(), Mat6::Zero());
}

int BlockSparseMatrix::find(int i, int j) const {
  const auto begin = cols_.begin() + row_start_[i], end = cols_.begin() + row_start_[i + 1];
  const auto it = std::lower_bound(begin, end, j);
  return (it != end && *it == j) ? static_cast<int>(it - cols_.begin()) : -1;
}

void BlockSparseMatrix::multiply(const VecX& x, VecX& y) const {
  y.resize(6 * n_);
  parallel_for_each(
      n_, [&](std::size_t i) { multiply_rows(static_cast<int>(i), static_cast<int>(i) + 1, x, y); }, 32);
}

void BlockSparseMatrix::multiply_rows(int begin, int end, const VecX& x, VecX& y) const {
  for (int i = begin; i < end; ++i) {
    Vec6 s = Vec6::Zero();
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k) s.noalias() += values_[k] * x.segment<6>(6 * cols_[k]);
    y.segment<6>(6 * i) = s;
  }
}

Eigen::SparseMatrix<double> BlockSparseMatrix::to_sparse() const {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(values_.size() * 36);
  for (int i = 0; i < n_; ++i)
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k)
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c)
          if (values_[k](r, c) != 0) t.emplace_back(6 * i + r, 6 * cols_[k] + c, values_[k](r, c));
  Eigen::SparseMatrix<double> a(6 * n_, 6 * n_);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

void BlockSparseMatrix::check_loaded(const LoadCheck& check, const char* name) const {
  check.require(n_ >= 0 && row_start_.size() == static_cast<std::size_t>(n_) + 1 && row_start_[0] == 0 &&
                    row_start_.back() == static_cast<long long>(cols_.size()) &&
                    diag_.size() == row_start_.size() - 1 && values_.size() == cols_.size(),
                name, "'s lists do not match its ", n_, " rows");
  for (int i = 0; i < n_; ++i) {
    check.require(row_start_[i] <= row_start_[i + 1], name, "'s row ", i, " ends before it starts");
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k)
      check.require(cols_[k] >= 0 && cols_[k] < n_ && (k == row_start_[i] || cols_[k - 1] < cols_[k]), name, "'s row ",
                    i, " has columns out of order or range");
  }
  for (int i = 0; i < n_; ++i) {
    check.require(diag_[i] == find(i, i) && diag_[i] >= 0, name, "'s row ", i, " has no diagonal block");
    for (int k = row_start_[i]; k < row_start_[i + 1]; ++k)
      check.require(find(cols_[k], i) >= 0, name, "'s pattern is not symmetric at row ", i);
  }
}

}  // namespace dda
