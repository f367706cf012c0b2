// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "block/displacement.hpp"

namespace dda {

// Each entry of T is a linear polynomial c + a·X + b·Y in the centroidal
// coordinates X = x-x0, Y = y-y0:
//
//   T = | 1  0  −Y  X  0  Y/2 |
//       | 0  1   X  0  Y  X/2 |
//
// The integral of a product of two such polynomials over the block only needs
// S, ∫X², ∫Y², ∫XY, since ∫X = ∫Y = 0. Written out entry by entry (it runs
// for every block every step); each entry is summed in the order of rows of T
// (first row, then second), from +0, as a loop over T's entries would.
IntegratedTt integrated_tt(double area, double sxx, double syy, double sxy) {
  IntegratedTt m;
  m.area = 0.0 + area;
  m.t22 = (0.0 + syy) + sxx;
  m.t23 = 0.0 + -sxy;
  m.t24 = 0.0 + sxy;
  m.t25 = (0.0 + -0.5 * syy) + 0.5 * sxx;
  m.t33 = 0.0 + sxx;
  m.t35 = 0.0 + 0.5 * sxy;
  m.t44 = 0.0 + syy;
  m.t45 = 0.0 + 0.5 * sxy;
  m.t55 = (0.0 + 0.25 * syy) + 0.25 * sxx;
  return m;
}

Mat6 IntegratedTt::full() const {
  Mat6 m = Mat6::Zero();
  m(0, 0) = m(1, 1) = area;
  m(2, 2) = t22;
  m(2, 3) = m(3, 2) = t23;
  m(2, 4) = m(4, 2) = t24;
  m(2, 5) = m(5, 2) = t25;
  m(3, 3) = t33;
  m(3, 5) = m(5, 3) = t35;
  m(4, 4) = t44;
  m(4, 5) = m(5, 4) = t45;
  m(5, 5) = t55;
  return m;
}

}  // namespace dda
