// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The DDA system matrix without its off-diagonal blocks stored: the diagonal
// block of each rock block (elasticity, inertia, loads, and the springs of
// its contacts), plus the contact springs themselves. A spring of stiffness
// k on dn = d0 + e_v·Dv + e_e·De couples blocks v and e through k·e_v·e_eᵀ;
// the product A·x forms that coupling from the contact's two 6-vectors
// instead of reading a stored 6×6 block. Assembly then writes only the
// diagonal, and the largest array of the step (two off-diagonal blocks, 576
// bytes, per touching block pair) is gone.
//
// That pays where a solve takes a few CG iterations (wave problems: the
// assembly, redone every open-close iteration, was a fifth of the step). Where
// solves take hundreds (quasi-static walls), the product dominates and a
// stored 6×6 block (one per pair, however many contacts, kept once for both
// orders of the pair) is read faster than the springs of each contact:
// store_products(true) assembles such a matrix with the diagonal and
// multiplies with it.
//
// Rows are gathered, each by one task, over the contacts that touch the
// block in contact order: no races and the same sums for any thread count.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "contact/contact_kinematics.hpp"
#include "core/symmetric6.hpp"
#include "solver/block_sparse_matrix.hpp"
#include "solver/symmetric_block_matrix.hpp"

namespace dda {

class ContactOperator final : public LinearOperator {
 public:
  // The stiffnesses a contact's springs act with in this solve (0: not acting).
  struct Springs {
    double kn = 0;  // on the penetration (closed: sliding or locked)
    double ks = 0;  // on the shear (locked)
  };

  // After each contact search: `blocks` block rows and the blocks each
  // contact couples (vertex block, edge block). Springs start at zero.
  void set_contacts(int blocks, std::span<const Contact> contacts);
  // The contacts' linearisation the springs act through; kept by reference
  // until the next call (the caller keeps it alive and unmoved).
  void set_kinematics(std::span<const ContactGradients> kinematics);

  // Multiply with a stored matrix (assembled in assembled()) instead of
  // matrix-free.
  void store_products(bool on) { store_products_ = on; }

  // Assembly writes these; call assembled() when done. A diagonal block taken
  // for rewriting gets a new revision number (diagonal_revision), so the
  // preconditioner redoes only the rows an assembly rewrote.
  Symmetric6& rewrite_diagonal(int b) {
    diagonal_revision_[b] = revision_;
    return diagonal_[b];
  }
  Springs& springs(int contact) { return springs_[contact]; }
  void assembled();
  // Contacts touching block b, in ascending contact order.
  std::span<const int> row_contacts(int b) const {
    return {row_contacts_.data() + row_start_[b], static_cast<std::size_t>(row_start_[b + 1] - row_start_[b])};
  }

  // LinearOperator
  int rows() const override { return static_cast<int>(diagonal_.size()); }
  Mat6 diagonal_block(int i) const override { return diagonal_[i].full(); }
  std::uint64_t diagonal_revision(int i) const override { return diagonal_revision_[i]; }
  void multiply_rows(int begin, int end, const VecX& x, VecX& y) const override;
  // Every contact's other block (open contacts included), in contact order.
  bool append_neighbours(int i, std::vector<int>& out) const override {
    for (const int c : row_contacts(i)) out.push_back(other_block(c, i));
    return true;
  }
  // The entries as a stored matrix, assembled on the first call after
  // assembled(): one block per pair of blocks in the contact list (open
  // contacts included, so that the pattern holds for all the open-close
  // iterations of a step).
  const BlockSparseMatrix& stored() const;
  const BlockSparseMatrix* stored_matrix() const override { return &stored(); }

 private:
  // Upper triangles (21 numbers, not 36): the mat-vec of wave problems on
  // 10^5 blocks waits for memory, and this is one of the arrays it reads.
  std::vector<Symmetric6> diagonal_;
  std::vector<std::uint64_t> diagonal_revision_;
  std::uint64_t revision_ = 0;               // stamped on the diagonal blocks the current assembly rewrites
  std::vector<std::pair<int, int>> blocks_;  // per contact: (vertex block, edge block)
  std::vector<Springs> springs_;
  std::vector<int> row_start_, row_contacts_;
  std::span<const ContactGradients> kinematics_;
  bool store_products_ = false;

  template <typename Matrix>
  void shape(Matrix& matrix, bool& shaped) const;
  void assemble_products();
  int other_block(int contact, int b) const {
    return blocks_[contact].first == b ? blocks_[contact].second : blocks_[contact].first;
  }
  void add_coupling(Mat6& block, int contact, int b) const;

  SymmetricBlockMatrix products_;  // for store_products(true)
  bool products_shaped_ = false;
  mutable BlockSparseMatrix stored_;
  mutable bool stored_valid_ = false;
  mutable bool stored_shaped_ = false;  // stored_ has this contact list's pattern
};

}  // namespace dda
