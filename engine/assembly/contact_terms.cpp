// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "assembly/contact_terms.hpp"

#include <algorithm>

#include "core/parallel.hpp"

namespace dda {

void assemble_contact_rows(std::span<const Contact> contacts, const ContactLinearisation& lin,
                           std::span<const ContactTerms> terms, std::span<const char> changed, const BlockTerms& own,
                           bool all_rows, ContactOperator& system, VecX& rhs, std::vector<char>& row_reassembled) {
  const int n = system.rows();
  rhs.resize(6 * n);
  // Each block row is gathered by one task, adding its contacts in contact
  // order: no races, and the same sums whatever the thread count. The task
  // of a contact's vertex block also hands the operator the springs it acts
  // with in this solve.
  row_reassembled.resize(n);
  parallel_for_each(
      n,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        const std::span<const int> row = system.row_contacts(b);
        // A row none of whose contacts changed since the last assembly of this
        // step keeps its diagonal block and, without a contact whose force
        // follows the iterate (sliding friction following the latest N), its
        // right-hand side: either would come out the same to the bit.
        bool matrix_too = all_rows, follows = false;
        for (std::size_t r = 0; r < row.size() && !matrix_too; ++r) {
          matrix_too = changed[row[r]];
          follows = follows || terms[row[r]].follows_iterate;
        }
        row_reassembled[b] = matrix_too || follows;
        // (A kept row's contacts keep their springs too: a contact's springs
        // change only with its state, and a change reassembles both its rows.)
        if (!matrix_too && !follows) return;
        Symmetric6 diag = own.k[b];
        Vec6 f = own.f[b];
        for (const int i : row) {
          const ContactTerms& t = terms[i];
          if (contacts[i].vblock == b) system.springs(i) = {t.kn, t.ks};
          if (!t.acts) continue;
          const ContactGradients& k = lin.gradients[i];
          const bool is_vertex_block = contacts[i].vblock == b;
          const Vec6& en_self = is_vertex_block ? k.en_v : k.en_e;
          const Vec6& es_self = is_vertex_block ? k.es_v : k.es_e;
          // kn·en enᵀ (+ ks·es esᵀ) on the diagonal (its upper triangle); the
          // coupling to the other block stays with the operator.
          if (matrix_too) diag.add_outer(t.kn, en_self);
          f -= t.normal * en_self;
          if (matrix_too && t.shear_spring) diag.add_outer(t.ks, es_self);
          f -= t.shear * es_self;
        }
        rhs.segment<6>(6 * b) = f;
        if (matrix_too) system.rewrite_diagonal(b) = diag;
      },
      16);
  system.set_kinematics(lin.gradients);
  system.assembled();
}

}  // namespace dda
