// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "assembly/contact_operator.hpp"

#include <algorithm>
#include <atomic>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {
// Revision numbers unique across operators (a preconditioner may see several).
std::uint64_t new_revision() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}
}  // namespace

void ContactOperator::set_contacts(int blocks, std::span<const Contact> contacts) {
  const std::size_t nc = contacts.size();
  diagonal_.resize(blocks);
  revision_ = new_revision();
  diagonal_revision_.assign(blocks, revision_);
  blocks_.resize(nc);
  springs_.assign(nc, Springs{});
  row_start_.assign(blocks + 1, 0);
  for (std::size_t i = 0; i < nc; ++i) {
    blocks_[i] = {contacts[i].vblock, contacts[i].eblock};
    ++row_start_[contacts[i].vblock + 1];
    ++row_start_[contacts[i].eblock + 1];
  }
  for (int b = 0; b < blocks; ++b) row_start_[b + 1] += row_start_[b];
  row_contacts_.resize(row_start_[blocks]);
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  for (std::size_t i = 0; i < nc; ++i) {  // ascending i: each row's list is in contact order
    row_contacts_[fill[blocks_[i].first]++] = static_cast<int>(i);
    row_contacts_[fill[blocks_[i].second]++] = static_cast<int>(i);
  }
  kinematics_ = {};
  stored_valid_ = stored_shaped_ = products_shaped_ = false;
}

void ContactOperator::set_kinematics(std::span<const ContactGradients> kinematics) {
  DDA_ASSERT(kinematics.size() == blocks_.size(), "one linearisation per contact");
  kinematics_ = kinematics;
  stored_valid_ = false;
}

void ContactOperator::assembled() {
  stored_valid_ = false;
  if (store_products_) assemble_products();
  revision_ = new_revision();
}

// Gives a stored form the pattern of this contact list (once per list): one
// block per pair of blocks in the list, open contacts included, so that the
// pattern holds for all the open-close iterations of a step.
template <typename Matrix>
void ContactOperator::shape(Matrix& matrix, bool& shaped) const {
  if (shaped) return;
  std::vector<std::pair<int, int>> coupled;
  coupled.reserve(blocks_.size());
  for (const auto& [v, e] : blocks_) coupled.emplace_back(std::min(v, e), std::max(v, e));
  std::sort(coupled.begin(), coupled.end());
  coupled.erase(std::unique(coupled.begin(), coupled.end()), coupled.end());
  matrix.set_structure(rows(), coupled);
  shaped = true;
}

// Adds contact i's springs to the block (b, other) of row b:
// kn·en_b·en_otherᵀ + ks·es_b·es_otherᵀ.
void ContactOperator::add_coupling(Mat6& block, int i, int b) const {
  const Springs& k = springs_[i];
  if (k.kn == 0 && k.ks == 0) return;  // open
  const ContactGradients& c = kinematics_[i];
  const bool vertex_side = blocks_[i].first == b;
  const Vec6 &en_self = vertex_side ? c.en_v : c.en_e, &en_other = vertex_side ? c.en_e : c.en_v;
  const Vec6 &es_self = vertex_side ? c.es_v : c.es_e, &es_other = vertex_side ? c.es_e : c.es_v;
  block += k.kn * en_self * en_other.transpose();
  if (k.ks != 0) block += k.ks * es_self * es_other.transpose();
}

// Row b writes its diagonal block and its blocks (b, j > b); a contact's
// coupling lands in the row of its smaller block, oriented from there.
void ContactOperator::assemble_products() {
  const int n = rows();
  shape(products_, products_shaped_);
  parallel_for_each(
      n,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        products_.value(products_.diagonal(b)) = diagonal_[b].full();
        for (int r = row_start_[b]; r < row_start_[b + 1]; ++r) {
          const int other = other_block(row_contacts_[r], b);
          if (other > b) products_.value(products_.find(b, other)).setZero();
        }
        for (int r = row_start_[b]; r < row_start_[b + 1]; ++r) {
          const int i = row_contacts_[r];
          const int other = other_block(i, b);
          if (other > b) add_coupling(products_.value(products_.find(b, other)), i, b);
        }
      },
      16);
}

void ContactOperator::multiply_rows(int begin, int end, const VecX& x, VecX& y) const {
  if (store_products_) {
    products_.multiply_rows(begin, end, x, y);
    return;
  }
  for (int b = begin; b < end; ++b) {
    Vec6 s = diagonal_[b] * Vec6(x.segment<6>(6 * b));
    for (int r = row_start_[b]; r < row_start_[b + 1]; ++r) {
      const int i = row_contacts_[r];
      const Springs& k = springs_[i];
      if (k.kn == 0 && k.ks == 0) continue;  // open
      const ContactGradients& c = kinematics_[i];
      const bool vertex_side = blocks_[i].first == b;
      const auto x_other = x.segment<6>(6 * other_block(i, b));
      // Row b of k·e eᵀ restricted to the other block: k·e_self·(e_other·x_other).
      s += (k.kn * (vertex_side ? c.en_e : c.en_v).dot(x_other)) * (vertex_side ? c.en_v : c.en_e);
      if (k.ks != 0) s += (k.ks * (vertex_side ? c.es_e : c.es_v).dot(x_other)) * (vertex_side ? c.es_v : c.es_e);
    }
    y.segment<6>(6 * b) = s;
  }
}

const BlockSparseMatrix& ContactOperator::stored() const {
  if (stored_valid_) return stored_;
  const int n = rows();
  shape(stored_, stored_shaped_);
  parallel_for_each(
      n,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        for (int e = stored_.row_begin(b); e < stored_.row_end(b); ++e) stored_.value(e).setZero();
        stored_.value(stored_.diagonal(b)) = diagonal_[b].full();
        for (int r = row_start_[b]; r < row_start_[b + 1]; ++r) {
          const int i = row_contacts_[r];
          add_coupling(stored_.value(stored_.find(b, other_block(i, b))), i, b);
        }
      },
      16);
  stored_valid_ = true;
  return stored_;
}

}  // namespace dda
