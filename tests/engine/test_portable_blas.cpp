// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The engine's own dense kernels of the CHOLMOD factor (solver/portable_blas.hpp)
// against the BLAS and LAPACK definitions, computed naively in long double:
// every argument combination, sizes across the kernels' block edges (the 4 × 4
// tile, the direct path's depth of 32, the 64-column blocks, the 256-deep
// chunks), strides larger than the rows, negative increments. Tolerance:
// 1e-12 relative to the sums of magnitudes (round-off of sums of a few
// hundred terms is ~1e-14).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/portable_blas.hpp"

extern "C" {
void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*, const double*, const int*,
            const double*, const int*, const double*, double*, const int*);
void dsyrk_(const char*, const char*, const int*, const int*, const double*, const double*, const int*, const double*,
            double*, const int*);
void dtrsm_(const char*, const char*, const char*, const char*, const int*, const int*, const double*, const double*,
            const int*, double*, const int*);
void dtrsv_(const char*, const char*, const char*, const int*, const double*, const int*, double*, const int*);
void dgemv_(const char*, const int*, const int*, const double*, const double*, const int*, const double*, const int*,
            const double*, double*, const int*);
void dpotrf_(const char*, const int*, double*, const int*, int*);
}

namespace {

using Matrix = std::vector<double>;  // column-major with a leading dimension

std::mt19937_64 rng(7);
Matrix random_matrix(int rows, int cols, int ld) {
  std::uniform_real_distribution<double> u(-1, 1);
  Matrix m(static_cast<std::size_t>(ld) * std::max(cols, 1));
  for (double& x : m) x = u(rng);
  (void)rows;
  return m;
}

// op(X)(i, l).
double op(const Matrix& x, int ld, bool t, int i, int l) { return t ? x[l + i * ld] : x[i + l * ld]; }

constexpr double kTolerance = 1e-12;

TEST(PortableBlas, BindsCholmodsCallsInThisProgram) { EXPECT_TRUE(dda::portable_blas_bound()); }

TEST(PortableBlas, GemmMatchesItsDefinitionForEveryOpAndSize) {
  const int sizes[] = {0, 1, 3, 5, 17, 70};
  const int depths[] = {0, 1, 7, 33, 300};
  for (const bool ta : {false, true})
    for (const bool tb : {false, true})
      for (const int m : sizes)
        for (const int n : sizes)
          for (const int k : depths) {
            if (m > 17 && n > 17 && k > 33) continue;  // keep it quick: the large sizes one at a time
            const int lda = (ta ? k : m) + 3, ldb = (tb ? n : k) + 2, ldc = m + 1;
            const Matrix a = random_matrix(ta ? k : m, ta ? m : k, lda), b = random_matrix(tb ? n : k, tb ? k : n, ldb);
            Matrix c = random_matrix(m, n, ldc);
            const Matrix c0 = c;
            const double alpha = -0.75, beta = 0.5;
            dgemm_(ta ? "T" : "N", tb ? "T" : "N", &m, &n, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(),
                   &ldc);
            for (int j = 0; j < n; ++j)
              for (int i = 0; i < m; ++i) {
                long double s = 0, size = std::abs(beta * c0[i + j * ldc]);
                for (int l = 0; l < k; ++l) {
                  s += static_cast<long double>(op(a, lda, ta, i, l)) * op(b, ldb, tb, l, j);
                  size += std::abs(op(a, lda, ta, i, l) * op(b, ldb, tb, l, j));
                }
                const long double expected = alpha * s + beta * c0[i + j * ldc];
                ASSERT_NEAR(c[i + j * ldc], static_cast<double>(expected), kTolerance * (1 + static_cast<double>(size)))
                    << "op " << ta << tb << " m " << m << " n " << n << " k " << k;
              }
            // Padding between columns untouched.
            for (int j = 0; j < n; ++j) EXPECT_EQ(c[m + j * ldc], c0[m + j * ldc]);
          }
}

TEST(PortableBlas, GemmWithZeroBetaIgnoresWhatCHolds) {
  const int m = 6, n = 5, k = 40;
  const Matrix a = random_matrix(m, k, m), b = random_matrix(k, n, k);
  Matrix c(m * n, std::nan(""));
  const double alpha = 1, beta = 0;
  dgemm_("N", "N", &m, &n, &k, &alpha, a.data(), &m, b.data(), &k, &beta, c.data(), &m);
  for (const double x : c) EXPECT_TRUE(std::isfinite(x));
}

TEST(PortableBlas, SyrkUpdatesOnlyItsTriangle) {
  for (const bool lower : {true, false})
    for (const bool t : {false, true})
      for (const int n : {1, 4, 9, 70})
        for (const int k : {1, 20, 40, 300}) {
          const int lda = (t ? k : n) + 1, ldc = n + 2;
          const Matrix a = random_matrix(t ? k : n, t ? n : k, lda);
          Matrix c = random_matrix(n, n, ldc);
          const Matrix c0 = c;
          const double alpha = -1, beta = 1;
          dsyrk_(lower ? "L" : "U", t ? "T" : "N", &n, &k, &alpha, a.data(), &lda, &beta, c.data(), &ldc);
          for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
              if (lower ? i < j : i > j) {
                ASSERT_EQ(c[i + j * ldc], c0[i + j * ldc]);  // the other triangle untouched
                continue;
              }
              long double s = 0, size = std::abs(c0[i + j * ldc]);
              for (int l = 0; l < k; ++l) {
                const double p = op(a, lda, t, i, l) * op(a, lda, t, j, l);
                s += static_cast<long double>(op(a, lda, t, i, l)) * op(a, lda, t, j, l), size += std::abs(p);
              }
              ASSERT_NEAR(c[i + j * ldc], static_cast<double>(alpha * s + beta * c0[i + j * ldc]),
                          kTolerance * (1 + static_cast<double>(size)));
            }
        }
}

// A well-conditioned triangle: unit-ish diagonal, small off-diagonal entries.
Matrix triangle(int n, int ld) {
  Matrix t = random_matrix(n, n, ld);
  for (double& x : t) x *= 0.1;
  for (int i = 0; i < n; ++i) t[i + i * ld] = 1.5 + 0.5 * std::abs(t[i + i * ld]);
  return t;
}

TEST(PortableBlas, TrsmSolvesEverySideTriangleAndOp) {
  for (const bool left : {true, false})
    for (const bool lower : {true, false})
      for (const bool t : {false, true})
        for (const bool unit : {false, true})
          for (const int m : {1, 5, 70})
            for (const int n : {1, 6, 130}) {
              const int na = left ? m : n, lda = na + 1, ldb = m + 3;
              const Matrix a = triangle(na, lda);
              const Matrix b0 = random_matrix(m, n, ldb);
              Matrix x = b0;
              const double alpha = 2;
              dtrsm_(left ? "L" : "R", lower ? "L" : "U", t ? "T" : "N", unit ? "U" : "N", &m, &n, &alpha, a.data(),
                     &lda, x.data(), &ldb);
              // op(A) as a dense matrix with its triangle only.
              auto opa = [&](int i, int j) {
                const int r = t ? j : i, c = t ? i : j;
                if (r == c) return unit ? 1.0 : a[r + c * lda];
                return (lower ? r > c : r < c) ? a[r + c * lda] : 0.0;
              };
              // Residual: op(A)·X − α·B (left) or X·op(A) − α·B (right).
              for (int j = 0; j < n; ++j)
                for (int i = 0; i < m; ++i) {
                  long double s = 0, size = 0;
                  for (int p = 0; p < na; ++p) {
                    const double term = left ? opa(i, p) * x[p + j * ldb] : x[i + p * ldb] * opa(p, j);
                    s += term, size += std::abs(term);
                  }
                  ASSERT_NEAR(static_cast<double>(s), alpha * b0[i + j * ldb],
                              kTolerance * (1 + static_cast<double>(size)))
                      << left << lower << t << unit << " m " << m << " n " << n;
                }
            }
}

TEST(PortableBlas, TrsvAndGemvTakeAnyStride) {
  for (const int inc : {1, 2, -1, -3})
    for (const bool lower : {true, false})
      for (const bool t : {false, true})
        for (const int n : {1, 7, 90}) {
          const int lda = n + 1;
          const Matrix a = triangle(n, lda);
          const int span = 1 + (n - 1) * std::abs(inc);
          Matrix x0 = random_matrix(span, 1, span), x = x0;
          dtrsv_(lower ? "L" : "U", t ? "T" : "N", "N", &n, a.data(), &lda, x.data(), &inc);
          auto at = [&](const Matrix& v, int i) { return inc > 0 ? v[i * inc] : v[(n - 1 - i) * -inc]; };
          for (int i = 0; i < n; ++i) {
            long double s = 0, size = 0;
            for (int p = 0; p < n; ++p) {
              const int r = t ? p : i, c = t ? i : p;
              const double aij = r == c || (lower ? r > c : r < c) ? a[r + c * lda] : 0.0;
              s += aij * at(x, p), size += std::abs(aij * at(x, p));
            }
            ASSERT_NEAR(static_cast<double>(s), at(x0, i), kTolerance * (1 + static_cast<double>(size)));
          }
          // gemv: y = α·op(A)·x + β·y with the full matrix.
          const int m = n + 3, ldg = m + 1, len_x = t ? m : n, len_y = t ? n : m;
          const Matrix g = random_matrix(m, n, ldg);
          const int span_x = 1 + (len_x - 1) * std::abs(inc), span_y = 1 + (len_y - 1) * std::abs(inc);
          const Matrix xv = random_matrix(span_x, 1, span_x);
          Matrix y = random_matrix(span_y, 1, span_y);
          const Matrix y0 = y;
          const double alpha = 1.25, beta = -0.5;
          dgemv_(t ? "T" : "N", &m, &n, &alpha, g.data(), &ldg, xv.data(), &inc, &beta, y.data(), &inc);
          auto vat = [&](const Matrix& v, int len, int i) { return inc > 0 ? v[i * inc] : v[(len - 1 - i) * -inc]; };
          for (int i = 0; i < len_y; ++i) {
            long double s = 0, size = std::abs(beta * vat(y0, len_y, i));
            for (int p = 0; p < len_x; ++p) {
              const double gij = t ? g[p + i * ldg] : g[i + p * ldg];
              s += gij * vat(xv, len_x, p), size += std::abs(gij * vat(xv, len_x, p));
            }
            ASSERT_NEAR(vat(y, len_y, i), static_cast<double>(alpha * s + beta * vat(y0, len_y, i)),
                        kTolerance * (1 + static_cast<double>(size)));
          }
        }
}

TEST(PortableBlas, PotrfFactorsAndReportsTheFirstBadPivot) {
  for (const bool lower : {true, false})
    for (const int n : {1, 5, 64, 65, 150}) {
      const int lda = n + 2;
      // A = B·Bᵀ + n·I: positive definite.
      const Matrix b = random_matrix(n, n, n);
      Matrix a(static_cast<std::size_t>(lda) * n, 0.0);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          double s = i == j ? n : 0.0;
          for (int l = 0; l < n; ++l) s += b[i + l * n] * b[j + l * n];
          a[i + j * lda] = s;
        }
      const Matrix a0 = a;
      int info = -99;
      dpotrf_(lower ? "L" : "U", &n, a.data(), &lda, &info);
      ASSERT_EQ(info, 0);
      for (int j = 0; j < n; ++j)
        for (int i = j; i < n; ++i) {  // (L·Lᵀ)(i, j) or (Uᵀ·U)(i, j)
          long double s = 0;
          for (int p = 0; p <= j; ++p) s += lower ? a[i + p * lda] * a[j + p * lda] : a[p + i * lda] * a[p + j * lda];
          ASSERT_NEAR(static_cast<double>(s), a0[i + j * lda], kTolerance * 4 * n * n);
        }
      // Indefinite at column 3 (1-based): reported there.
      if (n >= 5) {
        Matrix d(static_cast<std::size_t>(lda) * n, 0.0);
        for (int i = 0; i < n; ++i) d[i + i * lda] = i == 2 ? -1.0 : 2.0;
        dpotrf_(lower ? "L" : "U", &n, d.data(), &lda, &info);
        EXPECT_EQ(info, 3);
      }
    }
}

}  // namespace
