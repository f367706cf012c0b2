// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/symmetric_block_matrix.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace dda {

void SymmetricBlockMatrix::set_structure(int n, std::span<const std::pair<int, int>> pairs) {
  n_ = n;
  upper_start_.assign(n + 1, 0);
  lower_start_.assign(n + 1, 0);
  for (const auto& [i, j] : pairs) {
    DDA_ASSERT(i < j && j < n, "off-diagonal pairs must satisfy i < j < n");
    ++upper_start_[i + 1];
    ++lower_start_[j + 1];
  }
  for (int i = 0; i < n; ++i) {
    upper_start_[i + 1] += upper_start_[i] + 1;  // + the diagonal
    lower_start_[i + 1] += lower_start_[i];
  }
  upper_col_.assign(upper_start_[n], 0);
  lower_row_.assign(lower_start_[n], 0);
  lower_block_.assign(lower_start_[n], 0);
  std::vector<int> fill_upper(upper_start_.begin(), upper_start_.end() - 1);
  std::vector<int> fill_lower(lower_start_.begin(), lower_start_.end() - 1);
  for (int i = 0; i < n; ++i) upper_col_[fill_upper[i]++] = i;
  // Sorted pairs: each row's upper columns ascend, and each row's lower
  // entries come in ascending row order.
  for (const auto& [i, j] : pairs) {
    const int k = fill_upper[i]++;
    upper_col_[k] = j;
    lower_row_[fill_lower[j]] = i;
    lower_block_[fill_lower[j]++] = k;
  }
  values_.assign(upper_col_.size(), Mat6::Zero());
}

int SymmetricBlockMatrix::find(int i, int j) const {
  if (i > j) return -1;
  const auto begin = upper_col_.begin() + upper_start_[i], end = upper_col_.begin() + upper_start_[i + 1];
  const auto it = std::lower_bound(begin, end, j);
  return (it != end && *it == j) ? static_cast<int>(it - upper_col_.begin()) : -1;
}

void SymmetricBlockMatrix::multiply_rows(int begin, int end, const VecX& x, VecX& y) const {
  for (int i = begin; i < end; ++i) {
    Vec6 s = Vec6::Zero();
    for (int r = lower_start_[i]; r < lower_start_[i + 1]; ++r)
      s.noalias() += values_[lower_block_[r]].transpose() * x.segment<6>(6 * lower_row_[r]);
    for (int k = upper_start_[i]; k < upper_start_[i + 1]; ++k)
      s.noalias() += values_[k] * x.segment<6>(6 * upper_col_[k]);
    y.segment<6>(6 * i) = s;
  }
}

}  // namespace dda
