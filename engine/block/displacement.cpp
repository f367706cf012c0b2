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
Mat6 integrated_tt(double area, double sxx, double syy, double sxy) {
  Mat6 m = Mat6::Zero();
  m(0, 0) = 0.0 + area;
  m(1, 1) = 0.0 + area;
  m(2, 2) = (0.0 + syy) + sxx;
  m(2, 3) = m(3, 2) = 0.0 + -sxy;
  m(2, 4) = m(4, 2) = 0.0 + sxy;
  m(2, 5) = m(5, 2) = (0.0 + -0.5 * syy) + 0.5 * sxx;
  m(3, 3) = 0.0 + sxx;
  m(3, 5) = m(5, 3) = 0.0 + 0.5 * sxy;
  m(4, 4) = 0.0 + syy;
  m(4, 5) = m(5, 4) = 0.0 + 0.5 * sxy;
  m(5, 5) = (0.0 + 0.25 * syy) + 0.25 * sxx;
  return m;
}

}  // namespace dda
