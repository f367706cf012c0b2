// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The first-order DDA displacement function (Shi 1988). A block has six
// unknowns D = (u0, v0, r0, εx, εy, γxy) about its centroid (x0, y0); the
// displacement of the point (x, y) is T(x, y)·D with
//
//   T = | 1  0  -(y-y0)  (x-x0)    0     (y-y0)/2 |
//       | 0  1   (x-x0)    0     (y-y0)  (x-x0)/2 |
#include <cmath>

#include "core/symmetric6.hpp"
#include "core/types.hpp"

namespace dda {

inline Mat26 displacement_matrix(const Vec2& p, const Vec2& centroid) {
  const double x = p.x() - centroid.x(), y = p.y() - centroid.y();
  Mat26 t;
  t << 1, 0, -y, x, 0, y / 2,  //
      0, 1, x, 0, y, x / 2;
  return t;
}

// Tᵀ·v for a point p: the generalised force of a point force v. Written out
// (the same sums as displacement_matrix(p, centroid).transpose() * v without
// the products by 0 and 1): the contact kinematics take four per contact.
inline Vec6 displacement_transpose_times(const Vec2& p, const Vec2& centroid, const Vec2& v) {
  const double x = p.x() - centroid.x(), y = p.y() - centroid.y();
  Vec6 f;
  f << v.x(), v.y(), -y * v.x() + x * v.y(), x * v.x(), y * v.y(), y / 2 * v.x() + x / 2 * v.y();
  return f;
}

// ∫ TᵀT dA over the block (the inertia sub-matrix over ρ), from its area and
// second moments about the centroid (first moments vanish there). Of its 36
// entries ten are distinct and the rest zero; it is made and applied for
// every block several times a step, so it is kept as those ten, and its
// products give the bits of the full matrix's Eigen products (each row summed
// in column order; the zero entries add nothing). Eigen evaluates
// c·(M·x) as (c·M)·x: write tt.scaled(c) * x for it.
struct IntegratedTt {
  double area = 0;                                                                         // (0, 0) and (1, 1)
  double t22 = 0, t23 = 0, t24 = 0, t25 = 0, t33 = 0, t35 = 0, t44 = 0, t45 = 0, t55 = 0;  // (3, 4) is 0

  // c·∫TᵀT, entry by entry.
  IntegratedTt scaled(double c) const {
    return {c * area, c * t22, c * t23, c * t24, c * t25, c * t33, c * t35, c * t44, c * t45, c * t55};
  }
  Vec6 operator*(const Vec6& x) const {
    Vec6 y;
    y[0] = area * x[0];
    y[1] = area * x[1];
    y[2] = ((t22 * x[2] + t23 * x[3]) + t24 * x[4]) + t25 * x[5];
    y[3] = (t23 * x[2] + t33 * x[3]) + t35 * x[5];
    y[4] = (t24 * x[2] + t44 * x[4]) + t45 * x[5];
    y[5] = ((t25 * x[2] + t35 * x[3]) + t45 * x[4]) + t55 * x[5];
    return y;
  }
  // k += c·∫TᵀT, on the upper triangle.
  void add_scaled_to(double c, Symmetric6& k) const {
    k.at(0, 0) += c * area;
    k.at(1, 1) += c * area;
    k.at(2, 2) += c * t22;
    k.at(2, 3) += c * t23;
    k.at(2, 4) += c * t24;
    k.at(2, 5) += c * t25;
    k.at(3, 3) += c * t33;
    k.at(3, 5) += c * t35;
    k.at(4, 4) += c * t44;
    k.at(4, 5) += c * t45;
    k.at(5, 5) += c * t55;
  }
  Mat6 full() const;
};
IntegratedTt integrated_tt(double area, double sxx, double syy, double sxy);

}  // namespace dda

namespace dda {

// Displacement of the points of one block under its step solution D, as used
// to move vertices at the end of a step. The rigid rotation r0 is applied
// exactly (rotation matrix, not the linearised -r0·y, r0·x of T) so that
// spinning blocks do not grow; translation and strain are as in T. The
// rotation's cosine and sine are taken once for all the block's points.
class BlockMotion {
 public:
  BlockMotion(const Vec6& d, const Vec2& centroid)
      : d_(d), centroid_(centroid), cos_minus_1_(std::cos(d[2]) - 1.0), sin_(std::sin(d[2])) {}
  // T·D itself, the rotation linearised: the motion of a mesh element
  // (block/mesh.hpp), whose corners are nodes shared with its neighbours and
  // must move by the nodes' displacement, the same from every element.
  static BlockMotion linear(const Vec6& d, const Vec2& centroid) { return BlockMotion(d, centroid, 0.0, d[2]); }
  Vec2 operator()(const Vec2& p) const {
    const double x = p.x() - centroid_.x(), y = p.y() - centroid_.y();
    const double c = cos_minus_1_, s = sin_;
    return {d_[0] + c * x - s * y + d_[3] * x + 0.5 * d_[5] * y,  //
            d_[1] + s * x + c * y + d_[4] * y + 0.5 * d_[5] * x};
  }

 private:
  BlockMotion(const Vec6& d, const Vec2& centroid, double cos_minus_1, double sin)
      : d_(d), centroid_(centroid), cos_minus_1_(cos_minus_1), sin_(sin) {}
  Vec6 d_;
  Vec2 centroid_;
  double cos_minus_1_, sin_;
};

inline Vec2 point_displacement(const Vec2& p, const Vec2& centroid, const Vec6& d) {
  return BlockMotion(d, centroid)(p);
}

}  // namespace dda
