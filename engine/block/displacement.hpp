#pragma once
// The first-order DDA displacement function (Shi 1988). A block has six
// unknowns D = (u0, v0, r0, εx, εy, γxy) about its centroid (x0, y0); the
// displacement of the point (x, y) is T(x, y)·D with
//
//   T = | 1  0  -(y-y0)  (x-x0)    0     (y-y0)/2 |
//       | 0  1   (x-x0)    0     (y-y0)  (x-x0)/2 |
#include <cmath>

#include "core/types.hpp"

namespace dda {

inline Mat26 displacement_matrix(const Vec2& p, const Vec2& centroid) {
  const double x = p.x() - centroid.x(), y = p.y() - centroid.y();
  Mat26 t;
  t << 1, 0, -y, x, 0, y / 2,  //
      0, 1, x, 0, y, x / 2;
  return t;
}

// Tᵀ·v for a point p: the generalised force of a point force v.
inline Vec6 displacement_transpose_times(const Vec2& p, const Vec2& centroid, const Vec2& v) {
  return displacement_matrix(p, centroid).transpose() * v;
}

// ∫ TᵀT dA over the block, from its area and second moments about the
// centroid (first moments vanish there). Used by the inertia sub-matrix.
Mat6 integrated_tt(double area, double sxx, double syy, double sxy);

}  // namespace dda

namespace dda {

// Displacement of the point p under the step solution D, as used to move
// vertices at the end of a step. The rigid rotation r0 is applied exactly
// (rotation matrix, not the linearised -r0·y, r0·x of T) so that spinning
// blocks do not grow; translation and strain are as in T.
inline Vec2 point_displacement(const Vec2& p, const Vec2& centroid, const Vec6& d) {
  const double x = p.x() - centroid.x(), y = p.y() - centroid.y();
  const double c = std::cos(d[2]) - 1.0, s = std::sin(d[2]);
  return {d[0] + c * x - s * y + d[3] * x + 0.5 * d[5] * y,  //
          d[1] + s * x + c * y + d[4] * y + 0.5 * d[5] * x};
}

}  // namespace dda
