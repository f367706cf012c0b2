// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/cholmod_factor.hpp"

#include <dlfcn.h>

#include <cholmod.h>
#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "solver/block_sparse_matrix.hpp"
#include "solver/portable_blas.hpp"

namespace dda {

namespace {

// No OpenMP teams: CHOLMOD opens an OpenMP parallel region per large
// supernode, whose threads then spin and sleep against the step's TBB threads
// (on two cores a fifth of the factorisation's time went to waking them).
// Looked up at run time, so that a CHOLMOD built without OpenMP links too.
void use_one_thread_inside() {
  static std::once_flag once;
  std::call_once(once, [] {
    using SetInt = void (*)(int);
    // Maximum active levels 0: every parallel region runs on its caller's thread alone.
    if (auto set = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"))) set(0);
  });
}

}  // namespace

CholmodFactor::CholmodFactor() : common_(new cholmod_common) {
  // The factor's dense kernels are the engine's own (portable_blas.hpp): the
  // same bits on every machine. A program that links the engine in a way
  // that leaves CHOLMOD calling another BLAS is refused, not run with bits
  // that depend on the machine.
  if (!portable_blas_bound())
    throw Error(
        "CHOLMOD's BLAS calls do not reach the engine's own kernels (solver/portable_blas.hpp): link the "
        "engine statically into the program, or use solver = \"pcg\"");
  use_one_thread_inside();
  cholmod_start(common_);
  common_->print = 0;  // failures are reported through the return values
  common_->supernodal = CHOLMOD_SUPERNODAL;
  common_->nmethods = 1;
  common_->method[0].ordering = CHOLMOD_GIVEN;  // the block ordering of analyse()
  common_->postorder = 1;
  common_->quick_return_if_not_posdef = 1;
}

CholmodFactor::~CholmodFactor() {
  if (x_) cholmod_free_dense(&x_, common_);
  if (y_) cholmod_free_dense(&y_, common_);
  if (e_) cholmod_free_dense(&e_, common_);
  if (l_) cholmod_free_factor(&l_, common_);
  if (a_) cholmod_free_sparse(&a_, common_);
  cholmod_finish(common_);
  delete common_;
}

std::size_t CholmodFactor::peak_bytes() const { return common_->memory_usage; }

// The scalar lower triangle's pattern (column 6J + c holds rows 6I + r with
// I ≥ J coupled to J, r ≥ c on the diagonal block), the block ordering, and
// the symbolic factor.
void CholmodFactor::analyse(const BlockSparseMatrix& a) {
  const int n = a.rows();
  if (l_) cholmod_free_factor(&l_, common_);
  if (a_) cholmod_free_sparse(&a_, common_);
  ready_ = false;
  blocks_ = n;
  row_starts_.assign(a.row_starts().begin(), a.row_starts().end());
  columns_.assign(a.columns().begin(), a.columns().end());

  // Block lower triangle, for the ordering.
  std::vector<int> upper_count(n, 0);  // blocks (J, I ≥ J) of each block row, the diagonal included
  std::size_t block_entries = 0;
  for (int j = 0; j < n; ++j) {
    for (int k = a.row_begin(j); k < a.row_end(j); ++k)
      if (a.col(k) >= j) ++upper_count[j];
    block_entries += upper_count[j];
  }
  cholmod_sparse* g = cholmod_allocate_sparse(n, n, block_entries, 1, 1, -1, CHOLMOD_PATTERN, common_);
  if (!g) throw Error("CHOLMOD could not allocate the block graph (out of memory?)");
  {
    int* gp = static_cast<int*>(g->p);
    int* gi = static_cast<int*>(g->i);
    gp[0] = 0;
    for (int j = 0, e = 0; j < n; ++j) {
      for (int k = a.row_begin(j); k < a.row_end(j); ++k)
        if (a.col(k) >= j) gi[e++] = a.col(k);
      gp[j + 1] = e;
    }
  }
  std::vector<int> block_perm(n);
  const int ok = ordering == FillOrdering::Metis ? cholmod_metis(g, nullptr, 0, 1, block_perm.data(), common_)
                                                 : cholmod_amd(g, nullptr, 0, block_perm.data(), common_);
  cholmod_free_sparse(&g, common_);
  if (!ok) throw Error("CHOLMOD could not order the system (out of memory?)");
  std::vector<int> perm(6 * static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < 6; ++r) perm[6 * k + r] = 6 * block_perm[k] + r;

  // Scalar lower triangle: column 6J + c has (6 − c) diagonal-block entries
  // and 6 per block (I > J).
  value_start_.assign(n + 1, 0);
  for (int j = 0; j < n; ++j) value_start_[j + 1] = value_start_[j] + 21 + 36 * (upper_count[j] - 1);
  a_ = cholmod_allocate_sparse(6 * n, 6 * n, value_start_[n], 1, 1, -1, CHOLMOD_REAL, common_);
  if (!a_) throw Error("CHOLMOD could not allocate the system (out of memory?)");
  int* ap = static_cast<int*>(a_->p);
  int* ai = static_cast<int*>(a_->i);
  for (int j = 0; j < n; ++j) {
    int e = value_start_[j];
    for (int c = 0; c < 6; ++c) {
      ap[6 * j + c] = e;
      for (int k = a.row_begin(j); k < a.row_end(j); ++k) {
        const int i = a.col(k);
        if (i < j) continue;
        for (int r = i == j ? c : 0; r < 6; ++r) ai[e++] = 6 * i + r;
      }
    }
  }
  ap[6 * n] = value_start_[n];

  l_ = cholmod_analyze_p(a_, perm.data(), nullptr, 0, common_);
  if (!l_) throw Error("CHOLMOD could not analyse the system (out of memory?)");
  ++analyses_;
  factor_flops_ = common_->fl;
  factor_entries_ = common_->lnz;
}

// The values of a, in the analysed pattern's order; each block row writes its
// own six columns.
void CholmodFactor::fill_values(const BlockSparseMatrix& a) {
  double* ax = static_cast<double*>(a_->x);
  parallel_for_each(
      static_cast<std::size_t>(blocks_),
      [&](std::size_t jj) {
        const int j = static_cast<int>(jj);
        int e = value_start_[j];
        for (int c = 0; c < 6; ++c)
          for (int k = a.row_begin(j); k < a.row_end(j); ++k) {
            const int i = a.col(k);
            if (i < j) continue;
            // A(6I + r, 6J + c) = A(6J + c, 6I + r): row c of the stored block (J, I).
            const Mat6& v = a.value(k);
            for (int r = i == j ? c : 0; r < 6; ++r) ax[e++] = v(c, r);
          }
      },
      16);
}

// fill_values() backwards: the analysed pattern, each block (J, I ≥ J) from
// a_'s values and its mirror (I, J) as its transpose.
BlockSparseMatrix CholmodFactor::factorised_matrix() const {
  DDA_ASSERT(ready_, "CholmodFactor::factorised_matrix without a factor");
  std::vector<std::pair<int, int>> pairs;
  for (int j = 0; j < blocks_; ++j)
    for (int k = row_starts_[j]; k < row_starts_[j + 1]; ++k)
      if (columns_[k] > j) pairs.emplace_back(j, columns_[k]);
  BlockSparseMatrix m;
  m.set_structure(blocks_, pairs);
  DDA_ASSERT(std::ranges::equal(m.row_starts(), row_starts_) && std::ranges::equal(m.columns(), columns_),
             "CholmodFactor: the analysed pattern is not one set_structure makes");
  const double* ax = static_cast<const double*>(a_->x);
  for (int j = 0; j < blocks_; ++j) {
    int e = value_start_[j];
    for (int c = 0; c < 6; ++c)
      for (int k = m.row_begin(j); k < m.row_end(j); ++k) {
        const int i = m.col(k);
        if (i < j) continue;
        Mat6& v = m.value(k);
        for (int r = i == j ? c : 0; r < 6; ++r) {
          v(c, r) = ax[e++];
          if (i == j) v(r, c) = v(c, r);
        }
      }
    for (int k = m.row_begin(j); k < m.row_end(j); ++k)
      if (m.col(k) > j) m.value(m.find(m.col(k), j)) = m.value(k).transpose();
  }
  return m;
}

bool CholmodFactor::factorise(const BlockSparseMatrix& a) {
  const bool same_pattern = l_ && a.rows() == blocks_ && std::ranges::equal(a.row_starts(), row_starts_) &&
                            std::ranges::equal(a.columns(), columns_);
  if (!same_pattern) analyse(a);
  fill_values(a);
  ready_ = false;
  if (!cholmod_factorize(a_, l_, common_)) throw Error("CHOLMOD could not factorise the system (out of memory?)");
  ++factorisations_;
  ready_ = common_->status == CHOLMOD_OK && l_->minor == l_->n;
  return ready_;
}

void CholmodFactor::solve(const VecX& r, VecX& z) const {
  DDA_ASSERT(ready_ && r.size() == 6 * static_cast<Eigen::Index>(blocks_), "CholmodFactor::solve without a factor");
  cholmod_dense b{};
  b.nrow = b.nzmax = b.d = static_cast<std::size_t>(r.size());
  b.ncol = 1;
  b.x = const_cast<double*>(r.data());  // read only
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, l_, &b, nullptr, &x_, nullptr, &y_, &e_, common_))
    throw Error("CHOLMOD could not solve with its factor (out of memory?)");
  z.resize(r.size());
  std::copy_n(static_cast<const double*>(x_->x), r.size(), z.data());
}

}  // namespace dda
