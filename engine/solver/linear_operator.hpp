// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The system matrix as the solvers see it: symmetric, in block rows of 6
// (one per rock block), with its diagonal blocks and the product y = A·x by
// ranges of block rows. Either stored (BlockSparseMatrix) or matrix-free
// (the contact springs, assembly/contact_operator.hpp); a stored matrix is a
// capability an operator may offer, not a duty (stored_matrix()).
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace dda {

class BlockSparseMatrix;

class LinearOperator {
 public:
  virtual ~LinearOperator() = default;
  virtual int rows() const = 0;  // block rows
  virtual Mat6 diagonal_block(int i) const = 0;
  // A number that changes whenever diagonal block i is rewritten, unique
  // across operators; 0 when not tracked (treat the block as new). Lets a
  // preconditioner redo only the rows whose diagonal changed.
  virtual std::uint64_t diagonal_revision(int /*i*/) const { return 0; }
  // (A·x) for block rows [begin, end) written into the same rows of y (sized
  // by the caller); other rows of y are left alone. Rows are independent:
  // ranges may run in parallel, and a row's result never depends on how the
  // rows were split.
  virtual void multiply_rows(int begin, int end, const VecX& x, VecX& y) const = 0;
  // Appends the block rows that row i couples to (its off-diagonal blocks)
  // to `out` and returns true; an operator that cannot say returns false.
  virtual bool append_neighbours(int /*i*/, std::vector<int>& /*out*/) const { return false; }
  // Capability: the operator's entries as a stored matrix, for what needs
  // them (multigrid's Galerkin products, a direct factorisation). An operator
  // that is matrix-free only answers nullptr (the default); one that can
  // assemble its entries may do so on the call.
  virtual const BlockSparseMatrix* stored_matrix() const { return nullptr; }
};

}  // namespace dda
