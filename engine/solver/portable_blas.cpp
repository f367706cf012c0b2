// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The six dense routines CHOLMOD's supernodal factor calls, defined by the
// engine so that their sums do not depend on the machine (portable_blas.hpp).
// Column-major, Fortran calling convention (every argument by address; the
// hidden lengths of the character arguments are not read). Arguments are
// trusted as a BLAS trusts them: CHOLMOD is the only caller.
#include "solver/portable_blas.hpp"

#include <dlfcn.h>
#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace dda {
namespace {

bool is(const char* flag, char c) { return (*flag | 0x20) == (c | 0x20); }  // case-insensitive, as the BLAS

// op(X)(i, l) of a column-major X with leading dimension ld.
struct Operand {
  const double* p;
  int ld;
  bool transposed;
  double operator()(int i, int l) const {
    return transposed ? p[l + static_cast<std::ptrdiff_t>(i) * ld] : p[i + static_cast<std::ptrdiff_t>(l) * ld];
  }
};

// Σ x_i·y_i over n contiguous entries, in four interleaved partial sums added
// in a fixed order at the end: vectorisable without reassociating anything
// at run time (the order is the code's, not the compiler's or the CPU's).
inline double dot(int n, const double* __restrict x, const double* __restrict y) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += x[i] * y[i], s1 += x[i + 1] * y[i + 1];
    s2 += x[i + 2] * y[i + 2], s3 += x[i + 3] * y[i + 3];
  }
  for (; i < n; ++i) s0 += x[i] * y[i];
  return (s0 + s1) + (s2 + s3);
}

// y −= a·x over n contiguous entries.
inline void subtract_scaled(int n, double a, const double* __restrict x, double* __restrict y) {
  for (int i = 0; i < n; ++i) y[i] -= a * x[i];
}

// ---- The product kernel -----------------------------------------------------
//
// C = α·op(A)·op(B) + β·C over the tiles a Triangle admits. Blocked as the
// GotoBLAS layout: k in chunks of kKc, rows of A in blocks of kMc packed into
// panels of kMr rows, op(B) packed into panels of kNr columns; each kMr × kNr
// tile sums its chunk over k in order and adds it to C. Every size is a
// constant: the order of each sum is the same on every machine.
constexpr int kMr = 4, kNr = 4, kKc = 256, kMc = 96;
enum class Triangle { All, Lower, Upper };

// Packed panels (operator new aligns to 16 bytes: the kernel's loads are aligned).
thread_local std::vector<double> packed_a, packed_b;

void pack_a(const Operand& a, int i0, int rows, int l0, int kc, double* out) {
  for (int ip = 0; ip < rows; ip += kMr)
    for (int l = 0; l < kc; ++l)
      for (int r = 0; r < kMr; ++r) *out++ = ip + r < rows ? a(i0 + ip + r, l0 + l) : 0.0;
}

void pack_b(const Operand& b, int j0, int cols, int l0, int kc, double* out) {
  for (int jp = 0; jp < cols; jp += kNr)
    for (int l = 0; l < kc; ++l)
      for (int c = 0; c < kNr; ++c) *out++ = jp + c < cols ? b(l0 + l, j0 + jp + c) : 0.0;
}

// acc = Σ_l a(:, l)·b(l, :) over kc, l in order. SSE2, which every x86-64
// has: each register holds two rows of one column of the tile, eight hold
// the tile; a multiply and an add per pair (no FMA: the same rounding on
// every machine).
inline void tile_product(int kc, const double* __restrict a, const double* __restrict b, double (&acc)[kNr][kMr]) {
  static_assert(kMr == 4 && kNr == 4, "the kernel holds a 4 x 4 tile");
  __m128d c0l = _mm_setzero_pd(), c0h = c0l, c1l = c0l, c1h = c0l, c2l = c0l, c2h = c0l, c3l = c0l, c3h = c0l;
  for (int l = 0; l < kc; ++l, a += kMr, b += kNr) {
    const __m128d al = _mm_load_pd(a), ah = _mm_load_pd(a + 2);
    __m128d bj = _mm_load1_pd(b);
    c0l = _mm_add_pd(c0l, _mm_mul_pd(al, bj)), c0h = _mm_add_pd(c0h, _mm_mul_pd(ah, bj));
    bj = _mm_load1_pd(b + 1);
    c1l = _mm_add_pd(c1l, _mm_mul_pd(al, bj)), c1h = _mm_add_pd(c1h, _mm_mul_pd(ah, bj));
    bj = _mm_load1_pd(b + 2);
    c2l = _mm_add_pd(c2l, _mm_mul_pd(al, bj)), c2h = _mm_add_pd(c2h, _mm_mul_pd(ah, bj));
    bj = _mm_load1_pd(b + 3);
    c3l = _mm_add_pd(c3l, _mm_mul_pd(al, bj)), c3h = _mm_add_pd(c3h, _mm_mul_pd(ah, bj));
  }
  _mm_storeu_pd(&acc[0][0], c0l), _mm_storeu_pd(&acc[0][2], c0h);
  _mm_storeu_pd(&acc[1][0], c1l), _mm_storeu_pd(&acc[1][2], c1h);
  _mm_storeu_pd(&acc[2][0], c2l), _mm_storeu_pd(&acc[2][2], c2h);
  _mm_storeu_pd(&acc[3][0], c3l), _mm_storeu_pd(&acc[3][2], c3h);
}

void scale_c(Triangle tri, int m, int n, double beta, double* c, int ldc) {
  if (beta == 1) return;
  for (int j = 0; j < n; ++j) {
    const int lo = tri == Triangle::Lower ? j : 0, hi = tri == Triangle::Upper ? std::min(j + 1, m) : m;
    double* col = c + static_cast<std::ptrdiff_t>(j) * ldc;
    for (int i = lo; i < hi; ++i) col[i] = beta == 0 ? 0.0 : beta * col[i];
  }
}

// C += α·A·Bᵀ for a short k, without packing: for each column of C, the
// columns of A scaled by α·B(j, l) in order of l. The supernodal factor's
// updates from small supernodes (k of 6 to a few tens) are mostly this; their
// packing would cost as much as their products.
constexpr int kDirectDepth = 32;
void product_direct(Triangle tri, int m, int n, int k, double alpha, const Operand& a, const Operand& b, double* c,
                    int ldc) {
  for (int j = 0; j < n; ++j) {
    const int lo = tri == Triangle::Lower ? j : 0, hi = tri == Triangle::Upper ? std::min(j + 1, m) : m;
    if (lo >= hi) continue;
    double* col = c + static_cast<std::ptrdiff_t>(j) * ldc;
    for (int l = 0; l < k; ++l)
      subtract_scaled(hi - lo, -(alpha * b(l, j)), a.p + lo + static_cast<std::ptrdiff_t>(l) * a.ld, col + lo);
  }
}

void product(Triangle tri, int m, int n, int k, double alpha, const Operand& a, const Operand& b, double beta,
             double* c, int ldc) {
  if (m <= 0 || n <= 0) return;
  scale_c(tri, m, n, beta, c, ldc);
  if (alpha == 0 || k <= 0) return;
  if (!a.transposed && k <= kDirectDepth) {
    product_direct(tri, m, n, k, alpha, a, b, c, ldc);
    return;
  }
  const int n_padded = (n + kNr - 1) / kNr * kNr;
  for (int l0 = 0; l0 < k; l0 += kKc) {
    const int kc = std::min(kKc, k - l0);
    packed_b.resize(static_cast<std::size_t>(n_padded) * kc);
    pack_b(b, 0, n, l0, kc, packed_b.data());
    for (int i0 = 0; i0 < m; i0 += kMc) {
      const int rows = std::min(kMc, m - i0);
      packed_a.resize(static_cast<std::size_t>((rows + kMr - 1) / kMr * kMr) * kc);
      pack_a(a, i0, rows, l0, kc, packed_a.data());
      for (int jp = 0; jp < n; jp += kNr) {
        for (int ip = 0; ip < rows; ip += kMr) {
          const int i = i0 + ip;
          if (tri == Triangle::Lower && i + kMr - 1 < jp) continue;  // the tile lies above the diagonal
          if (tri == Triangle::Upper && i > jp + kNr - 1) continue;  // ... below it
          double acc[kNr][kMr];
          tile_product(kc, packed_a.data() + static_cast<std::size_t>(ip) * kc,
                       packed_b.data() + static_cast<std::size_t>(jp) * kc, acc);
          for (int cc = 0; cc < kNr && jp + cc < n; ++cc) {
            double* col = c + static_cast<std::ptrdiff_t>(jp + cc) * ldc;
            for (int r = 0; r < kMr && ip + r < rows; ++r) {
              const int row = i + r;
              if ((tri == Triangle::Lower && row < jp + cc) || (tri == Triangle::Upper && row > jp + cc)) continue;
              col[row] += alpha * acc[cc][r];
            }
          }
        }
      }
    }
  }
}

// ---- Triangular solves ------------------------------------------------------

// op(A)·x = b in place; x with stride incx (negative: from the far end).
void triangular_solve(bool lower, bool transposed, bool unit, int n, const double* a, int lda, double* x, int incx) {
  if (n <= 0) return;
  if (incx == 1) {  // contiguous x: the column sweeps and row dots over slices
    const bool forward = lower != transposed;
    for (int s = 0; s < n; ++s) {
      const int j = forward ? s : n - 1 - s;
      const double* col = a + static_cast<std::ptrdiff_t>(j) * lda;
      if (!transposed) {
        if (!unit) x[j] /= col[j];
        if (lower)
          subtract_scaled(n - j - 1, x[j], col + j + 1, x + j + 1);
        else
          subtract_scaled(j, x[j], col, x);
      } else {
        const double t = x[j] - (lower ? dot(n - j - 1, col + j + 1, x + j + 1) : dot(j, col, x));
        x[j] = unit ? t : t / col[j];
      }
    }
    return;
  }
  auto A = [&](int i, int j) { return a[i + static_cast<std::ptrdiff_t>(j) * lda]; };
  auto X = [&](int i) -> double& {
    return incx > 0 ? x[static_cast<std::ptrdiff_t>(i) * incx] : x[static_cast<std::ptrdiff_t>(n - 1 - i) * -incx];
  };
  const bool forward = lower != transposed;  // L·x = b and Uᵀ·x = b run from the first unknown
  for (int s = 0; s < n; ++s) {
    const int j = forward ? s : n - 1 - s;
    if (!transposed) {
      // Column sweep: x_j is final; take its column out of the unknowns ahead.
      if (!unit) X(j) /= A(j, j);
      const double xj = X(j);
      if (lower)
        for (int i = j + 1; i < n; ++i) X(i) -= xj * A(i, j);
      else
        for (int i = 0; i < j; ++i) X(i) -= xj * A(i, j);
    } else {
      // Row of op(A) = column of A: x_j = (b_j − Σ A(i, j)·x_i) / A(j, j).
      double t = X(j);
      if (lower)
        for (int i = j + 1; i < n; ++i) t -= A(i, j) * X(i);
      else
        for (int i = 0; i < j; ++i) t -= A(i, j) * X(i);
      X(j) = unit ? t : t / A(j, j);
    }
  }
}

// B := B·L⁻ᵀ, L lower n × n, B m × n: column j of X is
// (B(:, j) − X(:, 0..j−1)·L(j, 0..j−1)ᵀ) / L(j, j), in column blocks of kNb
// whose coupling to the blocks before is one product.
constexpr int kNb = 64;
void solve_right_lower_transposed(bool unit, int m, int n, const double* l, int ldl, double* b, int ldb) {
  auto L = [&](int i, int j) { return l[i + static_cast<std::ptrdiff_t>(j) * ldl]; };
  auto col = [&](int j) { return b + static_cast<std::ptrdiff_t>(j) * ldb; };
  for (int j0 = 0; j0 < n; j0 += kNb) {
    const int nb = std::min(kNb, n - j0);
    if (j0 > 0) product(Triangle::All, m, nb, j0, -1.0, {b, ldb, false}, {l + j0, ldl, true}, 1.0, col(j0), ldb);
    for (int j = j0; j < j0 + nb; ++j) {
      double* xj = col(j);
      for (int p = j0; p < j; ++p) {
        const double ljp = L(j, p);
        const double* xp = col(p);
        for (int i = 0; i < m; ++i) xj[i] -= ljp * xp[i];
      }
      if (!unit) {
        const double d = L(j, j);
        for (int i = 0; i < m; ++i) xj[i] /= d;
      }
    }
  }
}

// A = L·Lᵀ in place (lower), blocked right-looking: each diagonal block
// factorised, the panel below solved, the trailing matrix updated by one
// rank-kNb product. Returns 0, or the 1-based column whose pivot is not
// positive (LAPACK's info).
int cholesky_lower(int n, double* a, int lda) {
  auto A = [&](int i, int j) -> double& { return a[i + static_cast<std::ptrdiff_t>(j) * lda]; };
  for (int j0 = 0; j0 < n; j0 += kNb) {
    const int nb = std::min(kNb, n - j0);
    for (int j = j0; j < j0 + nb; ++j) {
      double d = A(j, j);
      for (int p = j0; p < j; ++p) d -= A(j, p) * A(j, p);
      if (!(d > 0)) {
        A(j, j) = d;
        return j + 1;
      }
      d = std::sqrt(d);
      A(j, j) = d;
      for (int i = j + 1; i < j0 + nb; ++i) {
        double t = A(i, j);
        for (int p = j0; p < j; ++p) t -= A(i, p) * A(j, p);
        A(i, j) = t / d;
      }
    }
    const int below = n - j0 - nb;
    if (below <= 0) continue;
    double* panel = &A(j0 + nb, j0);
    solve_right_lower_transposed(false, below, nb, &A(j0, j0), lda, panel, lda);
    product(Triangle::Lower, below, below, nb, -1.0, {panel, lda, false}, {panel, lda, true}, 1.0, &A(j0 + nb, j0 + nb),
            lda);
  }
  return 0;
}

// A = Uᵀ·U in place (upper), column by column.
int cholesky_upper(int n, double* a, int lda) {
  auto A = [&](int i, int j) -> double& { return a[i + static_cast<std::ptrdiff_t>(j) * lda]; };
  for (int j = 0; j < n; ++j) {
    double d = A(j, j);
    for (int p = 0; p < j; ++p) d -= A(p, j) * A(p, j);
    if (!(d > 0)) {
      A(j, j) = d;
      return j + 1;
    }
    d = std::sqrt(d);
    A(j, j) = d;
    for (int i = j + 1; i < n; ++i) {
      double t = A(j, i);
      for (int p = 0; p < j; ++p) t -= A(p, j) * A(p, i);
      A(j, i) = t / d;
    }
  }
  return 0;
}

}  // namespace
}  // namespace dda

// ---- The Fortran entry points ---------------------------------------------------

extern "C" {

void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc) {
  using namespace dda;
  product(Triangle::All, *m, *n, *k, *alpha, {a, *lda, !is(transa, 'n')}, {b, *ldb, !is(transb, 'n')}, *beta, c, *ldc);
}

void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc) {
  using namespace dda;
  const bool t = !is(trans, 'n');  // C = α·Aᵀ·A + β·C, A k × n; else α·A·Aᵀ, A n × k
  product(is(uplo, 'l') ? Triangle::Lower : Triangle::Upper, *n, *n, *k, *alpha, {a, *lda, t}, {a, *lda, !t}, *beta, c,
          *ldc);
}

void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb) {
  using namespace dda;
  const int rows = *m, cols = *n, ld = *ldb;
  if (rows <= 0 || cols <= 0) return;
  if (*alpha != 1)
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) {
        double& x = b[i + static_cast<std::ptrdiff_t>(j) * ld];
        x = *alpha == 0 ? 0.0 : *alpha * x;
      }
  if (*alpha == 0) return;
  const bool left = is(side, 'l'), lower = is(uplo, 'l'), transposed = !is(transa, 'n'), unit = is(diag, 'u');
  if (!left && lower && transposed) {  // the factor's X·Lᵀ = B
    solve_right_lower_transposed(unit, rows, cols, a, *lda, b, ld);
  } else if (left) {  // op(A)·X = B: each column of B
    for (int j = 0; j < cols; ++j)
      triangular_solve(lower, transposed, unit, rows, a, *lda, b + static_cast<std::ptrdiff_t>(j) * ld, 1);
  } else {  // X·op(A) = B ⇔ op(A)ᵀ·Xᵀ = Bᵀ: each row of B
    for (int i = 0; i < rows; ++i) triangular_solve(lower, !transposed, unit, cols, a, *lda, b + i, ld);
  }
}

void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx) {
  dda::triangular_solve(dda::is(uplo, 'l'), !dda::is(trans, 'n'), dda::is(diag, 'u'), *n, a, *lda, x, *incx);
}

void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a, const int* lda,
            const double* x, const int* incx, const double* beta, double* y, const int* incy) {
  const int rows = *m, cols = *n;
  if (rows <= 0 || cols <= 0) return;
  const bool transposed = !dda::is(trans, 'n');
  const int len_x = transposed ? rows : cols, len_y = transposed ? cols : rows;
  auto at = [](auto* v, int inc, int len, int i) -> decltype(*v) {
    return inc > 0 ? v[static_cast<std::ptrdiff_t>(i) * inc] : v[static_cast<std::ptrdiff_t>(len - 1 - i) * -inc];
  };
  if (*beta != 1)
    for (int i = 0; i < len_y; ++i) {
      double& yi = at(y, *incy, len_y, i);
      yi = *beta == 0 ? 0.0 : *beta * yi;
    }
  if (*alpha == 0) return;
  if (*incx == 1 && *incy == 1) {  // contiguous: columns as slices
    for (int j = 0; j < cols; ++j) {
      const double* col = a + static_cast<std::ptrdiff_t>(j) * *lda;
      if (!transposed)
        dda::subtract_scaled(rows, -*alpha * x[j], col, y);
      else
        y[j] += *alpha * dda::dot(rows, col, x);
    }
    return;
  }
  for (int j = 0; j < cols; ++j) {
    const double* col = a + static_cast<std::ptrdiff_t>(j) * *lda;
    if (!transposed) {
      const double t = *alpha * at(x, *incx, len_x, j);
      for (int i = 0; i < rows; ++i) at(y, *incy, len_y, i) += t * col[i];
    } else {
      double t = 0;
      for (int i = 0; i < rows; ++i) t += col[i] * at(x, *incx, len_x, i);
      at(y, *incy, len_y, j) += *alpha * t;
    }
  }
}

void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info) {
  if (*n < 0) {
    *info = -2;
  } else if (*lda < std::max(1, *n)) {
    *info = -4;
  } else {
    *info = dda::is(uplo, 'l') ? dda::cholesky_lower(*n, a, *lda) : dda::cholesky_upper(*n, a, *lda);
  }
}

}  // extern "C"

namespace dda {

bool portable_blas_bound() {
  static const bool bound = [] {
    const void* ours[] = {reinterpret_cast<const void*>(&dgemm_), reinterpret_cast<const void*>(&dsyrk_),
                          reinterpret_cast<const void*>(&dtrsm_), reinterpret_cast<const void*>(&dtrsv_),
                          reinterpret_cast<const void*>(&dgemv_), reinterpret_cast<const void*>(&dpotrf_)};
    const char* names[] = {"dgemm_", "dsyrk_", "dtrsm_", "dtrsv_", "dgemv_", "dpotrf_"};
    for (int i = 0; i < 6; ++i)
      if (dlsym(RTLD_DEFAULT, names[i]) != ours[i]) return false;
    return true;
  }();
  return bound;
}

}  // namespace dda
