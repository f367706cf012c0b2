#include "assembly/contact_terms.hpp"

#include <algorithm>

#include "core/parallel.hpp"

namespace dda {

void assemble_contact_rows(std::span<const Contact> contacts, const ContactLinearisation& lin,
                           const OpenCloseState& open_close, const ContactParameters& p, const BlockTerms& own,
                           bool all_rows, ContactOperator& system, VecX& rhs, std::vector<char>& row_reassembled) {
  const int n = system.rows();
  rhs.resize(6 * n);
  // The springs each contact acts with in this solve: normal on a closed
  // contact, shear too on a locked one.
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        const Contact& c = contacts[i];
        ContactOperator::Springs& k = system.springs(static_cast<int>(i));
        const ContactParameters::Springs full = p.springs(c);
        k.kn = c.state == ContactState::Open ? 0.0 : c.scale * full.kn;
        k.ks = c.state == ContactState::Locked ? c.scale * full.ks : 0.0;
      },
      1024);
  // Each block row is gathered by one task, adding its contacts in contact
  // order: no races, and the same sums whatever the thread count.
  row_reassembled.resize(n);
  parallel_for_each(
      n,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        const std::span<const int> row = system.row_contacts(b);
        // A row none of whose contacts changed state since the last assembly of
        // this step keeps its diagonal block and, without a sliding contact (whose
        // friction follows the latest N), its right-hand side: either would come
        // out the same to the bit.
        bool matrix_too = all_rows, sliding = false;
        for (std::size_t r = 0; r < row.size() && !matrix_too; ++r) {
          matrix_too = open_close.changed[row[r]];
          sliding = sliding || contacts[row[r]].state == ContactState::Sliding;
        }
        row_reassembled[b] = matrix_too || sliding;
        if (!matrix_too && !sliding) return;
        Symmetric6 diag = own.k[b];
        Vec6 f = own.f[b];
        for (const int i : row) {
          const Contact& c = contacts[i];
          if (c.state == ContactState::Open) continue;
          const ContactGradients& k = lin.gradients[i];
          const ContactOperator::Springs& springs = system.springs(i);
          const bool is_vertex_block = c.vblock == b;
          const Vec6& en_self = is_vertex_block ? k.en_v : k.en_e;
          const Vec6& es_self = is_vertex_block ? k.es_v : k.es_e;
          // Normal spring on dn = d0 + en·D (and, locked, shear spring on
          // ds = s0 + es·D): kn·en enᵀ (+ ks·es esᵀ) on the diagonal (its upper
          // triangle); the coupling to the other block stays with the operator.
          if (matrix_too) diag.add_outer(springs.kn, en_self);
          f -= springs.kn * lin.offsets[i].d0 * en_self;
          if (c.state == ContactState::Locked) {
            if (matrix_too) diag.add_outer(springs.ks, es_self);
            f -= springs.ks * open_close.iterate[i].s0 * es_self;
          } else {
            // Sliding: friction N·tanφ against the sliding direction, with N
            // from the previous iteration (lagged with friction_lag).
            const ContactIterate& it = open_close.iterate[i];
            const double friction = friction_normal(it, it.normal_force) * p.tan_friction[c.joint];
            f -= c.slide_sign * friction * es_self;
          }
        }
        rhs.segment<6>(6 * b) = f;
        if (matrix_too) system.rewrite_diagonal(b) = diag;
      },
      16);
  system.set_kinematics(lin.gradients);
  system.assembled();
}

}  // namespace dda
