// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The Assemble stage of each open-close iteration: each block row's diagonal
// block and right-hand side, its own terms (block_terms.hpp) plus what its
// contacts add for the current iterate (ContactTerms, as the contact law
// decides them: contact/contact_model.hpp); the couplings between blocks
// stay with the matrix-free operator (contact_operator.hpp).
#include <span>
#include <vector>

#include "assembly/block_terms.hpp"
#include "assembly/contact_operator.hpp"
#include "contact/contact_model.hpp"

namespace dda {

// Sets every contact's springs in `system` (terms[i].kn, .ks), then gathers
// the rows: all of them, or (all_rows false) only those with a contact that
// changed since the last contribution (changed) or whose force follows the
// iterate; the others would come out the same to the bit. Writes rhs and,
// per row, whether it was rewritten (row_reassembled).
void assemble_contact_rows(std::span<const Contact> contacts, const ContactLinearisation& lin,
                           std::span<const ContactTerms> terms, std::span<const char> changed, const BlockTerms& own,
                           bool all_rows, ContactOperator& system, VecX& rhs, std::vector<char>& row_reassembled);

}  // namespace dda
