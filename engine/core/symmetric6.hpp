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

  // (this)·x, row by row, the terms of a row in column order.
  Vec6 operator*(const Vec6& x) const {
    Vec6 y;
    for (int i = 0; i < 6; ++i) {
      double s = 0;
      for (int j = 0; j < 6; ++j) s += u_[index(i, j)] * x[j];
      y[i] = s;
    }
    return y;
  }

 private:
  // Position of (i, j) in the upper triangle stored row by row.
  static constexpr int index(int i, int j) {
    if (i > j) return index(j, i);
    return i * 6 - i * (i - 1) / 2 + (j - i);
  }
  std::array<double, 21> u_{};
};

}  // namespace dda
