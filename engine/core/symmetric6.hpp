// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A symmetric 6×6 matrix kept as its upper triangle: 21 numbers instead of
// 36, for the per-block arrays of models with 10^5 blocks (the block terms of
// the diagonal, the block-Jacobi inverses).
#include <array>

#include "core/types.hpp"

namespace dda {

class Symmetric6 {
 public:
  Symmetric6() = default;
  // From the upper triangle of m (m is taken to be symmetric).
  explicit Symmetric6(const Mat6& m) {
    for (int i = 0, k = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j) u_[k++] = m(i, j);
  }

  Mat6 full() const {
    Mat6 m;
    for (int i = 0, k = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j) m(i, j) = m(j, i) = u_[k++];
    return m;
  }

  // this += k·e·eᵀ (a spring's stiffness on the generalised displacement
  // e·D): 21 products instead of a full matrix's 36.
  void add_outer(double k, const Vec6& e) {
    const Vec6 ke = k * e;
    for (int i = 0, n = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j) u_[n++] += e[j] * ke[i];
  }

  // Entry (i, j) (either order).
  double& at(int i, int j) { return u_[kIndex[i][j]]; }
  double at(int i, int j) const { return u_[kIndex[i][j]]; }

  // The upper triangle, row by row.
  const std::array<double, 21>& upper() const { return u_; }
  template <class Archive>
  void fields(Archive& ar) {
    ar(u_);
  }

  // (this)·x, row by row, the terms of a row in column order from the first
  // product: the same bits as Eigen's Mat6·Vec6 of full() (which sums each row
  // in column order too; checked bit for bit by the test
  // Solver.Symmetric6ProductHasTheBitsOfTheFullProduct).
  Vec6 operator*(const Vec6& x) const {
    // Two rows at a time (one SSE2 register), as Eigen does it.
    Vec6 y;
    for (int i = 0; i < 6; i += 2) {
      Eigen::Vector2d s = Eigen::Vector2d(u_[kIndex[i][0]], u_[kIndex[i + 1][0]]) * x[0];
      for (int j = 1; j < 6; ++j) s += Eigen::Vector2d(u_[kIndex[i][j]], u_[kIndex[i + 1][j]]) * x[j];
      y.segment<2>(i) = s;
    }
    return y;
  }

 private:
  // Position of (i, j) in the upper triangle stored row by row.
  static constexpr int kIndex[6][6] = {{0, 1, 2, 3, 4, 5},     {1, 6, 7, 8, 9, 10},    {2, 7, 11, 12, 13, 14},
                                       {3, 8, 12, 15, 16, 17}, {4, 9, 13, 16, 18, 19}, {5, 10, 14, 17, 19, 20}};
  std::array<double, 21> u_{};
};

}  // namespace dda
