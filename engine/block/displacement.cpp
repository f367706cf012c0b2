#include "block/displacement.hpp"

namespace dda {

// Each entry of T is a linear polynomial c + a·X + b·Y in the centroidal
// coordinates X = x-x0, Y = y-y0. The integral of a product of two such
// polynomials over the block only needs S, ∫X², ∫Y², ∫XY, since ∫X = ∫Y = 0.
namespace {
struct Linear {
  double c = 0, a = 0, b = 0;
};
}  // namespace

Mat6 integrated_tt(double area, double sxx, double syy, double sxy) {
  Linear t[2][6];
  t[0][0] = {1, 0, 0};
  t[0][2] = {0, 0, -1};
  t[0][3] = {0, 1, 0};
  t[0][5] = {0, 0, 0.5};
  t[1][1] = {1, 0, 0};
  t[1][2] = {0, 1, 0};
  t[1][4] = {0, 0, 1};
  t[1][5] = {0, 0.5, 0};
  Mat6 m = Mat6::Zero();
  for (int j = 0; j < 6; ++j)
    for (int k = 0; k < 6; ++k)
      for (int r = 0; r < 2; ++r) {
        const Linear &p = t[r][j], &q = t[r][k];
        m(j, k) += p.c * q.c * area + p.a * q.a * sxx + p.b * q.b * syy + (p.a * q.b + p.b * q.a) * sxy;
      }
  return m;
}

}  // namespace dda
